"""Realistic sensing: body velocity from an accelerometer, and a stroke sensor.

Skyhook needs the absolute body velocity ``z_s'``, which no sensor measures; the
dissertation recommends obtaining it "from directly measurable acceleration, although
the phase response would need to be examined" (section 8.3). Two standard estimators,
each a compiled per-sample kernel updating a small state array (for the engine to
inline) with its exact discrete frequency response:

* **Leaky integrator** ``v' = a - v / tau``: ``V/A = 1 / (s + 1/tau)``. A constant
  acceleration offset ``a0`` (accelerometer bias, gravity from tilt) gives the bounded
  estimate ``a0 tau`` instead of a ramp. Its phase lead over the ideal integrator
  ``1/(j w)`` is ``atan(1 / (w tau))``.
* **Band-pass observer**: the integrator followed by a second-order Butterworth-type
  high-pass, ``V/A = (1/s) s^2 / (s^2 + 2 zeta w_c s + w_c^2) = s / (s^2 + 2 zeta w_c s
  + w_c^2)``: a constant offset gives exactly zero velocity in steady state. This is
  the usual high-pass-filtered ("drift-free") integration of accelerometer signals;
  the phase lead over ``1/(j w)`` is ``180 deg - atan2(2 zeta w_c w, w_c^2 - w^2)``.

Both are discretised exactly for an acceleration held constant over each sample period
``T = 1/fs`` (zero-order hold, as the engine holds its inputs; model reference, section 7):
``x[k+1] = Phi x[k] + Gamma a[k]`` with ``Phi = exp(A T)``,
``Gamma = A^-1 (Phi - I) B``, and the estimate after sample ``k`` is the updated state
(``v_hat[k] = C x[k+1]``), so the response is ``H(z) = z C (z I - Phi)^-1 Gamma``.
:func:`phase_error` compares it with the ideal integrator sampled at the same instants:
as ``fs`` grows it tends to the continuous phase lead above (plus half a sample,
``180 f / fs`` degrees, from the hold).

The stroke sensor (:class:`StrokeSensor`, kernel :func:`stroke_sensor_update`) samples
``x_d`` at its own rate, adds white noise from a pre-generated seeded array, quantises to
its resolution and differences successive readings for the stroke rate ``v_d``.

Examples
--------
>>> tau = leaky_integrator_tau(1.0, max_phase_error=10.0, fs=1000.0)
>>> round(tau, 3), round(float(phase_error(1.0, leaky_integrator_response(1.0, tau, 1000.0))), 3)
(0.919, 10.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.errors import ValidationError, check_finite, check_range

__all__ = [
    "BP_SIZE",
    "BUTTERWORTH_ZETA",
    "LEAKY_SIZE",
    "STROKE_SIZE",
    "BandPassObserver",
    "LeakyIntegrator",
    "Sensing",
    "StrokeSensor",
    "band_pass_coefficients",
    "band_pass_corner",
    "band_pass_response",
    "band_pass_update",
    "leaky_integrator_coefficients",
    "leaky_integrator_response",
    "leaky_integrator_tau",
    "leaky_integrator_update",
    "phase_error",
    "stroke_sensor_update",
]

FloatArray = npt.NDArray[np.float64]
ComplexArray = npt.NDArray[np.complex128]

#: state size of the leaky integrator (the estimate v_hat [m/s])
LEAKY_SIZE = 1
#: state size of the band-pass observer (x1 [m], x2 = v_hat [m/s])
BP_SIZE = 2
#: stroke-sensor state: last reading [m], last rate [m/s], readings so far (0, 1, 2+)
STROKE_SIZE = 3

#: default damping ratio of the band-pass observer's high-pass (Butterworth, 1/sqrt(2))
BUTTERWORTH_ZETA = 1.0 / math.sqrt(2.0)


# --- kernels ---------------------------------------------------------------------------


@njit(cache=True, inline="always")
def leaky_integrator_update(state: np.ndarray, acc: float, decay: float, gain: float) -> float:
    """Advance the leaky integrator by one sample and return the estimate ``v_hat`` [m/s].

    ``state[0] = decay state[0] + gain acc`` with ``decay = exp(-T/tau)`` and
    ``gain = tau (1 - decay)`` (:func:`leaky_integrator_coefficients`): the exact
    solution of ``v' = a - v/tau`` over one period ``T`` with ``a`` [m/s^2] held.

    Examples
    --------
    >>> s = np.zeros(LEAKY_SIZE)
    >>> d, g = leaky_integrator_coefficients(1.0, 100.0)
    >>> round(leaky_integrator_update(s, 1.0, d, g), 6)  # 1 - exp(-0.01)
    0.00995
    """
    v = decay * state[0] + gain * acc
    state[0] = v
    return v


@njit(cache=True, inline="always")
def band_pass_update(state: np.ndarray, acc: float, coef: np.ndarray) -> float:
    """Advance the band-pass observer by one sample and return ``v_hat`` [m/s].

    ``x[k+1] = Phi x[k] + Gamma a[k]`` with ``coef = (Phi00, Phi01, Phi10, Phi11,
    Gamma0, Gamma1)`` from :func:`band_pass_coefficients`; ``state = (x1, x2)``,
    ``v_hat = x2``.

    Examples
    --------
    >>> s = np.zeros(BP_SIZE)
    >>> c = band_pass_coefficients(0.1, 1000.0)
    >>> round(band_pass_update(s, 1.0, c), 6)  # ~ T for the first sample
    0.001
    """
    x1 = state[0]
    x2 = state[1]
    n1 = coef[0] * x1 + coef[1] * x2 + coef[4] * acc
    n2 = coef[2] * x1 + coef[3] * x2 + coef[5] * acc
    state[0] = n1
    state[1] = n2
    return n2


@njit(cache=True, inline="always")
def stroke_sensor_update(
    state: np.ndarray, stroke: float, noise: float, resolution: float, fs: float
) -> tuple[float, float]:
    """One reading of the stroke sensor: ``(x_d measured [m], v_d estimate [m/s])``.

    The reading is ``resolution * round((stroke + noise) / resolution)`` (no quantisation
    when ``resolution`` is 0); the rate is the backward difference of successive readings
    times ``fs`` [Hz] (0 at the first reading). Call it once per sensor sample (at
    ``fs``) and hold the outputs in between; ``noise`` [m] is the next value of a
    pre-generated array (:meth:`StrokeSensor.noise`).

    Examples
    --------
    >>> s = np.zeros(STROKE_SIZE)
    >>> stroke_sensor_update(s, 0.0104, 0.0, 0.001, 100.0)
    (0.01, 0.0)
    >>> x, v = stroke_sensor_update(s, 0.0121, 0.0, 0.001, 100.0)
    >>> round(x, 6), round(v, 6)
    (0.012, 0.2)
    """
    x = stroke + noise
    if resolution > 0.0:
        x = resolution * math.floor(x / resolution + 0.5)
    rate = 0.0
    if state[2] > 0.0:
        rate = (x - state[0]) * fs
    state[0] = x
    state[1] = rate
    if state[2] < 2.0:
        state[2] += 1.0
    return x, rate


# --- coefficients and exact responses -----------------------------------------------------


def _positive(name: str, value: object, unit: str) -> float:
    return float(check_range(name, value, 0.0, None, unit=unit, low_inclusive=False))


def _freq(freq: npt.ArrayLike) -> FloatArray:
    return np.asarray(check_range("freq", freq, 0.0, None, unit="Hz", low_inclusive=False))


def leaky_integrator_coefficients(tau: float, fs: float) -> tuple[float, float]:
    """``(decay, gain)`` of the exact ZOH leaky integrator: ``exp(-T/tau)``, ``tau (1 - decay)``.

    Parameters
    ----------
    tau : float
        Time constant [s] (> 0).
    fs : float
        Sample rate [Hz] (> 0).

    Examples
    --------
    >>> d, g = leaky_integrator_coefficients(2.0, 1000.0)
    >>> round(d, 9), round(g, 9)
    (0.99950012, 0.000999750)
    """
    tau = _positive("tau", tau, "s")
    period = 1.0 / _positive("fs", fs, "Hz")
    decay = math.exp(-period / tau)
    return decay, -tau * math.expm1(-period / tau)


def leaky_integrator_response(
    freq: npt.ArrayLike, tau: float, fs: float | None = None
) -> ComplexArray:
    """Exact frequency response ``V_hat / A`` [s] of the leaky integrator at ``freq`` [Hz].

    With ``fs`` [Hz], the discrete kernel's ``H = gain / (1 - decay e^{-j w T})``;
    without, the continuous ``1 / (j w + 1/tau)``.

    Examples
    --------
    >>> h = leaky_integrator_response([1.0], 1.0, 1e6)
    >>> bool(np.allclose(h, leaky_integrator_response([1.0], 1.0), rtol=1e-5))
    True
    """
    f = _freq(freq)
    tau = _positive("tau", tau, "s")
    w = 2.0 * np.pi * f
    if fs is None:
        return np.asarray(1.0 / (1j * w + 1.0 / tau), dtype=complex)
    decay, gain = leaky_integrator_coefficients(tau, fs)
    return np.asarray(gain / (1.0 - decay * np.exp(-1j * w / float(fs))), dtype=complex)


def _band_pass_matrices(corner: float, zeta: float) -> tuple[FloatArray, FloatArray]:
    wc = 2.0 * math.pi * corner
    a = np.array([[0.0, 1.0], [-wc * wc, -2.0 * zeta * wc]])
    b = np.array([0.0, 1.0])
    return a, b


def band_pass_coefficients(corner: float, fs: float, zeta: float = BUTTERWORTH_ZETA) -> FloatArray:
    """The six ZOH coefficients ``(Phi00, Phi01, Phi10, Phi11, Gamma0, Gamma1)`` of the observer.

    Parameters
    ----------
    corner : float
        High-pass corner frequency ``f_c = w_c / (2 pi)`` [Hz] (> 0, below ``fs / 2``).
    fs : float
        Sample rate [Hz].
    zeta : float
        High-pass damping ratio (> 0; default 1/sqrt(2), Butterworth).

    Examples
    --------
    >>> c = band_pass_coefficients(0.1, 1000.0)
    >>> c.shape, round(float(c[0]), 6)
    ((6,), 1.0)
    """
    from scipy.linalg import expm  # scipy loads on first use

    corner = _positive("corner", corner, "Hz")
    rate = _positive("fs", fs, "Hz")
    zeta = _positive("zeta", zeta, "")
    if corner >= rate / 2:
        raise ValidationError(f"corner must be below fs/2 = {rate / 2:g} Hz; got {corner:g} Hz")
    a, b = _band_pass_matrices(corner, zeta)
    # Van Loan: expm([[A, B], [0, 0]] T) = [[Phi, Gamma], [0, 1]] (exact ZOH, A invertible or not)
    m = np.zeros((3, 3))
    m[:2, :2] = a
    m[:2, 2] = b
    e = expm(m / rate)
    phi, gamma = e[:2, :2], e[:2, 2]
    return np.array([phi[0, 0], phi[0, 1], phi[1, 0], phi[1, 1], gamma[0], gamma[1]])


def band_pass_response(
    freq: npt.ArrayLike, corner: float, fs: float | None = None, zeta: float = BUTTERWORTH_ZETA
) -> ComplexArray:
    """Exact frequency response ``V_hat / A`` [s] of the band-pass observer at ``freq`` [Hz].

    With ``fs``, the discrete kernel's ``z C (z I - Phi)^-1 Gamma`` at ``z = e^{j w T}``;
    without, the continuous ``s / (s^2 + 2 zeta w_c s + w_c^2)``.

    Examples
    --------
    >>> h = band_pass_response([1.0], 0.1, 1e6)
    >>> bool(np.allclose(h, band_pass_response([1.0], 0.1), rtol=1e-5))
    True
    """
    f = _freq(freq)
    corner = _positive("corner", corner, "Hz")
    zeta = _positive("zeta", zeta, "")
    w = 2.0 * np.pi * f
    if fs is None:
        s = 1j * w
        wc = 2.0 * np.pi * corner
        return np.asarray(s / (s * s + 2.0 * zeta * wc * s + wc * wc), dtype=complex)
    c = band_pass_coefficients(corner, fs, zeta)
    z = np.exp(1j * w / float(fs))
    p00, p01, p10, p11, g0, g1 = c
    # (z I - Phi)^-1 by the 2x2 adjugate; output row C = (0, 1)
    det = (z - p00) * (z - p11) - p01 * p10
    x2 = (p10 * g0 + (z - p00) * g1) / det
    return np.asarray(z * x2, dtype=complex)


def phase_error(freq: npt.ArrayLike, response: npt.ArrayLike) -> FloatArray:
    """Phase [deg] of an estimator's ``response`` relative to the ideal integrator ``1/(j w)``.

    Positive: the estimate leads the true velocity (leaky integration and high-pass
    filtering lead at low frequency). ``response`` is ``V_hat / A`` at ``freq`` [Hz]
    (e.g. :func:`leaky_integrator_response`).

    Examples
    --------
    >>> round(float(phase_error(1.0, leaky_integrator_response(1.0, 1 / (2 * np.pi)))), 6)
    45.0
    """
    f = _freq(freq)
    h = np.asarray(response, dtype=complex)
    return np.asarray(np.degrees(np.angle(h * 2j * np.pi * f)), dtype=float)


def _solve(fun: Callable[[float], float], lo: float, hi: float) -> float:
    from scipy.optimize import brentq  # scipy loads on first use

    return float(brentq(fun, lo, hi, xtol=1e-12, rtol=1e-12))


def _check_target(freq: float, max_phase_error: float, fs: float | None) -> tuple[float, float]:
    f = float(check_range("freq", freq, 0.0, None, unit="Hz", low_inclusive=False))
    err = float(
        check_range(
            "max_phase_error",
            max_phase_error,
            0.0,
            90.0,
            unit="deg",
            low_inclusive=False,
            high_inclusive=False,
        )
    )
    if fs is not None:
        rate = _positive("fs", fs, "Hz")
        if f >= rate / 2:
            raise ValidationError(f"freq must be below fs/2 = {rate / 2:g} Hz; got {f:g} Hz")
        hold = 180.0 * f / rate  # the half-sample lead of the hold, which no tau removes
        if err <= hold * 1.0001:
            raise ValidationError(
                f"max_phase_error must exceed the sampling lead 180 f/fs = {hold:.3g} deg "
                f"at {f:g} Hz and fs = {rate:g} Hz; got {err:g} deg"
            )
    return f, err


def leaky_integrator_tau(
    freq: float, max_phase_error: float = 10.0, fs: float | None = None
) -> float:
    """The shortest time constant ``tau`` [s] whose phase error at ``freq`` [Hz] is ``max_phase_error``.

    The phase lead falls with frequency, so the estimate then leads by at most
    ``max_phase_error`` [deg] at every frequency from ``freq`` up to where the hold's
    half-sample lead takes over; the shortest ``tau`` forgets an acceleration offset
    fastest (its estimate ``a0 tau`` is smallest). Continuous:
    ``tau = 1 / (2 pi f tan(max_phase_error))``; with ``fs`` the exact discrete response
    is solved for.

    Examples
    --------
    >>> round(leaky_integrator_tau(1.0, 10.0), 4)  # 1 / (2 pi tan 10 deg)
    0.9026
    """
    f, err = _check_target(freq, max_phase_error, fs)
    tau0 = 1.0 / (2.0 * math.pi * f * math.tan(math.radians(err)))
    if fs is None:
        return tau0

    def gap(log_tau: float) -> float:
        return float(phase_error(f, leaky_integrator_response(f, math.exp(log_tau), fs))) - err

    lo, hi = math.log(tau0) - 3.0, math.log(tau0) + 12.0
    return math.exp(_solve(gap, lo, hi))


def band_pass_corner(
    freq: float,
    max_phase_error: float = 10.0,
    fs: float | None = None,
    zeta: float = BUTTERWORTH_ZETA,
) -> float:
    """The highest corner ``f_c`` [Hz] whose phase error at ``freq`` [Hz] is ``max_phase_error`` [deg].

    As :func:`leaky_integrator_tau` for the band-pass observer: a higher corner rejects
    drift and low-frequency noise faster.

    Examples
    --------
    >>> round(band_pass_corner(1.0, 10.0), 4)
    0.1228
    """
    f, err = _check_target(freq, max_phase_error, fs)
    zeta = _positive("zeta", zeta, "")

    def gap(log_fc: float) -> float:
        h = band_pass_response(f, math.exp(log_fc), fs, zeta)
        return float(phase_error(f, h)) - err

    return math.exp(_solve(gap, math.log(f) - 14.0, math.log(f)))


# --- Python-facing estimators ---------------------------------------------------------------


@dataclass(frozen=True)
class LeakyIntegrator:
    """Leaky-integrator velocity estimator ``v' = a - v / tau`` sampled at ``fs``.

    Parameters
    ----------
    tau : float
        Time constant [s] (> 0): see :func:`leaky_integrator_tau`.
    fs : float
        Sample rate of the accelerometer [Hz] (> 0).

    Examples
    --------
    >>> est = LeakyIntegrator(tau=1.0, fs=1000.0)
    >>> v = est.estimate(np.ones(20000))  # 1 m/s^2 offset: bounded at a0 tau
    >>> round(float(v[-1]), 6)
    1.0
    """

    tau: float
    fs: float

    def __post_init__(self) -> None:
        leaky_integrator_coefficients(self.tau, self.fs)

    def response(self, freq: npt.ArrayLike) -> ComplexArray:
        """Exact discrete response ``V_hat / A`` [s] at ``freq`` [Hz].

        Examples
        --------
        >>> LeakyIntegrator(1.0, 1000.0).response([1.0]).shape
        (1,)
        """
        return leaky_integrator_response(freq, self.tau, self.fs)

    def estimate(self, acc: npt.ArrayLike) -> FloatArray:
        """Velocity estimates [m/s] for accelerations ``acc`` [m/s^2] sampled at ``fs``, from rest.

        Examples
        --------
        >>> LeakyIntegrator(1.0, 10.0).estimate([0.0, 0.0]).tolist()
        [0.0, 0.0]
        """
        a = check_finite("acc", acc).ravel()
        decay, gain = leaky_integrator_coefficients(self.tau, self.fs)
        return _run_leaky(a, decay, gain)


@dataclass(frozen=True)
class BandPassObserver:
    """Band-pass velocity observer ``s / (s^2 + 2 zeta w_c s + w_c^2)`` sampled at ``fs``.

    Parameters
    ----------
    corner : float
        High-pass corner ``f_c`` [Hz]: see :func:`band_pass_corner`.
    fs : float
        Sample rate [Hz].
    zeta : float
        Damping ratio of the high-pass (default 1/sqrt(2)).

    Examples
    --------
    >>> v = BandPassObserver(0.1, 1000.0).estimate(np.ones(200000))  # offset: rejected
    >>> abs(float(v[-1])) < 1e-3
    True
    """

    corner: float
    fs: float
    zeta: float = BUTTERWORTH_ZETA

    def __post_init__(self) -> None:
        band_pass_coefficients(self.corner, self.fs, self.zeta)

    def response(self, freq: npt.ArrayLike) -> ComplexArray:
        """Exact discrete response ``V_hat / A`` [s] at ``freq`` [Hz].

        Examples
        --------
        >>> BandPassObserver(0.1, 1000.0).response([1.0, 2.0]).shape
        (2,)
        """
        return band_pass_response(freq, self.corner, self.fs, self.zeta)

    def estimate(self, acc: npt.ArrayLike) -> FloatArray:
        """Velocity estimates [m/s] for accelerations ``acc`` [m/s^2] sampled at ``fs``, from rest.

        Examples
        --------
        >>> BandPassObserver(0.1, 10.0).estimate([0.0]).tolist()
        [0.0]
        """
        a = check_finite("acc", acc).ravel()
        return _run_band_pass(a, band_pass_coefficients(self.corner, self.fs, self.zeta))


@dataclass(frozen=True)
class StrokeSensor:
    """A stroke (suspension displacement) sensor: sample rate, resolution and white noise.

    Parameters
    ----------
    fs : float
        Sample rate [Hz] (> 0).
    resolution : float
        Quantisation step [m] (>= 0; 0: none).
    noise_std : float
        Standard deviation of the white measurement noise [m] (>= 0).
    seed : int
        Seed of the noise generator (:func:`numpy.random.default_rng`): the same seed gives
        the same noise array.

    Examples
    --------
    >>> s = StrokeSensor(fs=500.0, resolution=1e-4, noise_std=0.0)
    >>> x, v = s.measure(0.01 * np.sin(2 * np.pi * np.arange(0.0, 1.0, 1e-3)), 1000.0)
    >>> x.shape, v.shape
    ((1000,), (1000,))
    """

    fs: float
    resolution: float = 0.0
    noise_std: float = 0.0
    seed: int = 0

    def __post_init__(self) -> None:
        _positive("fs", self.fs, "Hz")
        check_range("resolution", self.resolution, 0.0, None, unit="m")
        check_range("noise_std", self.noise_std, 0.0, None, unit="m")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer):
            raise ValidationError(f"seed must be an integer; got {self.seed!r}")

    def noise(self, n: int) -> FloatArray:
        """``n`` samples of the sensor's white noise [m] (pre-generated, reproducible).

        Examples
        --------
        >>> bool(np.array_equal(StrokeSensor(100.0, noise_std=1e-4, seed=3).noise(5),
        ...                     StrokeSensor(100.0, noise_std=1e-4, seed=3).noise(5)))
        True
        """
        rng = np.random.default_rng(self.seed)
        return np.asarray(rng.normal(0.0, 1.0, int(n)) * self.noise_std, dtype=float)

    def measure(self, stroke: npt.ArrayLike, fs: float) -> tuple[FloatArray, FloatArray]:
        """Held readings ``(x_d [m], v_d [m/s])`` of a stroke record sampled at ``fs`` [Hz].

        ``fs`` must be an integer multiple of the sensor's rate; the sensor reads every
        ``fs / self.fs``-th sample (the first at index 0) and holds in between.

        Examples
        --------
        >>> x, v = StrokeSensor(fs=2.0).measure([0.0, 1.0, 2.0, 3.0], 4.0)
        >>> x.tolist(), v.tolist()
        ([0.0, 0.0, 2.0, 2.0], [0.0, 0.0, 4.0, 4.0])
        """
        x = check_finite("stroke", stroke).ravel()
        rate = _positive("fs", fs, "Hz")
        ratio = rate / self.fs
        step = round(ratio)
        if step < 1 or abs(ratio - step) > 1e-9 * ratio:
            raise ValidationError(
                f"fs must be an integer multiple of the sensor rate {self.fs:g} Hz; got {rate:g} Hz"
            )
        n_read = (x.size + step - 1) // step
        return _run_stroke(x, self.noise(n_read), step, float(self.resolution), float(self.fs))


@dataclass(frozen=True)
class Sensing:
    """What a vehicle's controllers measure: body velocity and suspension stroke.

    The vehicle engine (:class:`~mrsuspension.engine.vehicle.VehicleSimulation`'s
    ``sensing``) gives every corner's controller the body velocity ``velocity``
    estimates from that corner's body acceleration (sampled at the estimator's ``fs``
    and held, the acceleration at the start of the step as a sampled controller reads
    it) and, with ``stroke``, the stroke and stroke rate that sensor reads. The default
    is ideal sensing: the true velocity and stroke.

    Parameters
    ----------
    velocity : LeakyIntegrator or BandPassObserver, optional
        The body-velocity estimator of every corner (None: the true velocity).
    stroke : StrokeSensor, optional
        The stroke sensor of every corner (None: the true stroke and rate); corner ``i``
        draws its noise with ``seed + i``.

    Examples
    --------
    >>> Sensing().is_ideal
    True
    >>> tau = leaky_integrator_tau(1.0, 10.0, fs=1000.0)
    >>> Sensing(LeakyIntegrator(tau, 1000.0)).describe()["velocity"]["kind"]
    'leaky-integrator'
    >>> Sensing("leaky")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: sensing velocity must be None (ideal), a LeakyIntegrator or a BandPassObserver; got 'leaky'
    """

    velocity: LeakyIntegrator | BandPassObserver | None = None
    stroke: StrokeSensor | None = None

    def __post_init__(self) -> None:
        if self.velocity is not None and not isinstance(
            self.velocity, LeakyIntegrator | BandPassObserver
        ):
            raise ValidationError(
                "sensing velocity must be None (ideal), a LeakyIntegrator or a "
                f"BandPassObserver; got {self.velocity!r}"
            )
        if self.stroke is not None and not isinstance(self.stroke, StrokeSensor):
            raise ValidationError(
                f"sensing stroke must be None (ideal) or a StrokeSensor; got {self.stroke!r}"
            )

    @property
    def is_ideal(self) -> bool:
        """True when the controllers get the true velocity and stroke."""
        return self.velocity is None and self.stroke is None

    def describe(self) -> dict[str, object]:
        """Plain data: the estimator and the stroke sensor with their settings.

        Examples
        --------
        >>> Sensing().describe()
        {'velocity': {'kind': 'ideal'}, 'stroke': {'kind': 'ideal'}}
        """
        v = self.velocity
        if isinstance(v, LeakyIntegrator):
            vel: dict[str, object] = {"kind": "leaky-integrator", "tau": v.tau, "fs": v.fs}
        elif isinstance(v, BandPassObserver):
            vel = {"kind": "band-pass", "corner": v.corner, "fs": v.fs, "zeta": v.zeta}
        else:
            vel = {"kind": "ideal"}
        st = self.stroke
        stroke: dict[str, object] = (
            {"kind": "ideal"}
            if st is None
            else {
                "kind": "sensor",
                "fs": st.fs,
                "resolution": st.resolution,
                "noise_std": st.noise_std,
                "seed": st.seed,
            }
        )
        return {"velocity": vel, "stroke": stroke}


@njit(cache=True)
def _run_leaky(a: np.ndarray, decay: float, gain: float) -> np.ndarray:
    state = np.zeros(LEAKY_SIZE)
    out = np.empty(a.size)
    for k in range(a.size):
        out[k] = leaky_integrator_update(state, a[k], decay, gain)
    return out


@njit(cache=True)
def _run_band_pass(a: np.ndarray, coef: np.ndarray) -> np.ndarray:
    state = np.zeros(BP_SIZE)
    out = np.empty(a.size)
    for k in range(a.size):
        out[k] = band_pass_update(state, a[k], coef)
    return out


@njit(cache=True)
def _run_stroke(
    x: np.ndarray, noise: np.ndarray, step: int, resolution: float, fs: float
) -> tuple[np.ndarray, np.ndarray]:
    state = np.zeros(STROKE_SIZE)
    xm = np.empty(x.size)
    vm = np.empty(x.size)
    held_x = 0.0
    held_v = 0.0
    for k in range(x.size):
        if k % step == 0:
            held_x, held_v = stroke_sensor_update(state, x[k], noise[k // step], resolution, fs)
        xm[k] = held_x
        vm[k] = held_v
    return xm, vm
