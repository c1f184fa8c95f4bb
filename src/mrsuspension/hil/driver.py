"""Drive-current regulator of the HiL platform (dissertation section 7.2.2).

The DSP's D/A output (12-bit, 25 mA at 10 V) drives an amplifier; the coil current is
sensed across a 1 ohm resistor and fed back through the A/D converter to a PI(D)
regulator with K_P = 1, K_I = 3000, K_D = 0; the current is limited to 0.3 A.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mrsuspension.errors import check_range

__all__ = ["PICurrentDriver"]

_INF = math.inf


@dataclass
class PICurrentDriver:
    """Discrete PI current regulator with anti-windup and a quantised D/A output.

    ``u = K_P e + K_I integral(e)``, ``e = i_ref - i_m``, with ``i_m`` the sense voltage over
    ``sense_resistance``. The output (the amplifier's current demand [A]) is clamped to
    ``[0, current_limit]`` and converted by a ``bits``-bit unipolar D/A over
    ``[0, da_full_scale]``. Anti-windup: the integrator is frozen while the output is
    saturated in the direction the error pushes it (conditional integration).

    A demand or a measured current that is NaN or infinite never raises: the output is
    0 A and the integrator is cleared (the safety supervisor trips on the same reading).

    Parameters
    ----------
    kp, ki : float
        Proportional [-] and integral [1/s] gains (defaults 1 and 3000, section 7.2.2).
    current_limit : float
        Largest drive current [A] (0.3 A).
    bits : int
        D/A resolution (12; 0: no quantisation).
    da_full_scale : float
        Amplifier demand at the D/A's full scale [A].
    sense_resistance : float
        Current-sense resistor [ohm]; the regulator is given the sense voltage.

    Examples
    --------
    >>> drv = PICurrentDriver()
    >>> drv.reset(1e-3)
    >>> round(drv.update(0.1, 0.0), 4)  # K_P e + K_I T e = 0.4 saturates: no integration
    0.1
    >>> round(drv.update(0.1, 0.1), 4)  # on target: the output holds
    0.1
    >>> drv.update(0.1, float("nan")), drv.integral  # a broken reading: coil off
    (0.0, 0.0)
    >>> drv.direct(float("inf"))
    0.0
    """

    kp: float = 1.0
    ki: float = 3000.0
    current_limit: float = 0.3
    bits: int = 12
    da_full_scale: float = 0.5
    sense_resistance: float = 1.0

    def __post_init__(self) -> None:
        check_range("kp", self.kp, 0.0, None)
        check_range("ki", self.ki, 0.0, None)
        check_range("current_limit", self.current_limit, 0.0, None, low_inclusive=False)
        check_range("da_full_scale", self.da_full_scale, 0.0, None, low_inclusive=False)
        check_range("sense_resistance", self.sense_resistance, 0.0, None, low_inclusive=False)
        self._lsb = self.da_full_scale / (1 << self.bits) if self.bits else 0.0
        self.reset(1e-3)

    def reset(self, period: float) -> None:
        """Integrator to zero; the regulator runs every ``period`` seconds."""
        self.period = float(period)
        self.integral = 0.0
        self.output = 0.0

    def _da(self, u: float) -> float:
        if not 0.0 < u < _INF:  # negative, zero, NaN or infinite: no current
            return 0.0
        if u > self.current_limit:
            u = self.current_limit
        if self._lsb:
            u = math.floor(u / self._lsb + 0.5) * self._lsb
            top = self.da_full_scale - self._lsb
            if u > top:
                u = top
            if u > self.current_limit:
                u = math.floor(self.current_limit / self._lsb) * self._lsb
        return u

    def update(self, reference: float, sense_voltage: float) -> float:
        """One regulator tick: the D/A output (amplifier demand [A]) for this period."""
        measured = sense_voltage / self.sense_resistance
        e = reference - measured
        if not -_INF < e < _INF:  # a demand or a reading that is not a number: coil off
            return self.off()
        integral = self.integral + self.ki * self.period * e
        u = self.kp * e + integral
        # conditional integration: do not wind up against a saturated output
        if (u > self.current_limit and e > 0.0) or (u < 0.0 and e < 0.0):
            u = self.kp * e + self.integral
        else:
            self.integral = integral
        self.output = self._da(u)
        return self.output

    def direct(self, reference: float) -> float:
        """Feed-through (for a coil that follows its command at once): clamp and D/A only."""
        self.integral = 0.0
        self.output = self._da(reference)
        return self.output

    def off(self) -> float:
        """Current to zero at once (safe state); the integrator is cleared."""
        self.integral = 0.0
        self.output = 0.0
        return 0.0
