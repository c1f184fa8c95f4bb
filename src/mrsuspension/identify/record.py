"""Time-domain damper records: any motion, any coil input, one uniformly sampled record.

A :class:`TimeRecord` holds what a rig logs when it drives a damper with band-limited
random displacement and switches the coil current (or the driver's command voltage) at
random: time, displacement, velocity, force and the coil input, all in SI. There are no
cycles to cut; :mod:`mrsuspension.identify.timedomain` integrates a model over it.

The coil input is either a current [A] or a voltage [V]. A model driven by current
(Bingham, the dissertation's) needs the driver's gain [A/V] to use a voltage column; a
model driven by voltage (Spencer's) takes it as is.

:func:`read_record` reads a file with :func:`~mrsuspension.identify.readers.read_test`
(delimited text or ``.mat``), adds the coil input roles ``u`` / ``voltage`` and the units
``V`` / ``mV`` of :data:`COIL_UNITS`, and checks the data: NaN rows (bridged below
:data:`MAX_NAN_FRACTION`, refused above), time running backwards, a missing coil input, a
force or displacement column in an implausible unit.

Examples
--------
>>> import numpy as np
>>> t = np.arange(0.0, 1.0, 1e-3)
>>> rec = TimeRecord.from_arrays(t, 0.01 * np.sin(2 * np.pi * t), force=100 * np.cos(2 * np.pi * t),
...                              coil=np.full(t.size, 2.25), coil_unit="V")
>>> rec.sample_rate, rec.coil_unit, round(float(rec.velocity[500]), 4)
(1000.0, 'V', -0.0628)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError
from mrsuspension.identify.preprocess import smooth_derivative
from mrsuspension.identify.readers import ROLE_ALIASES, TestDataError, read_test

__all__ = [
    "COIL_UNITS",
    "MAX_NAN_FRACTION",
    "TimeRecord",
    "read_record",
]

FloatArray = npt.NDArray[np.float64]
CoilUnit = Literal["A", "V"]

#: Units of a voltage coil input (lower case) and their factor to volts. Currents use the
#: readers' table (``A``, ``mA``).
COIL_UNITS: dict[str, float] = {"v": 1.0, "mv": 1e-3}
#: Largest share of rows with a NaN that is bridged (linear interpolation) rather than
#: refused: a few isolated dropouts are common in rig logs; more means a broken channel.
MAX_NAN_FRACTION = 0.02
#: Default smoothing window of a derived velocity [s]: a cubic Savitzky-Golay derivative
#: over 5 ms passes (-3 dB) about 1.25/(5 ms) = 250 Hz, well above a 0-50 Hz excitation.
VELOCITY_WINDOW = 0.005
#: Plausible force swings of a damper test [N] (peak deviation from the median): a small
#: seat damper's ~10 N to a 200 kN seismic damper; outside, the column is almost surely
#: in another unit (kN read as N, mN...).
FORCE_RANGE = (10.0, 2e5)
#: Plausible peak strokes [m] (0.05 mm to 1 m).
STROKE_RANGE = (5e-5, 1.0)

_COIL_TOKENS = ("u", "voltage", "volt", "command", "coil", "input")


@dataclass(frozen=True)
class TimeRecord:
    """One uniformly sampled damper record in SI units.

    Attributes
    ----------
    time, displacement, velocity, force : ndarray
        Time [s], stroke [m] (compression positive), velocity [m/s], force [N].
    coil : ndarray
        Coil input: current [A] or command voltage [V] (``coil_unit``).
    coil_unit : {"A", "V"}
        What ``coil`` is.
    gain : float or None
        Driver gain [A/V] mapping a voltage input to coil current (None: not known).
    acceleration : ndarray
        Derived from the velocity (smoothing derivative); the dissertation's model uses
        its sign.
    source : str
        File name or generator.
    notes : tuple of str
        What the reader did (columns, units, NaN rows, derived signals).
    """

    time: FloatArray
    displacement: FloatArray
    velocity: FloatArray
    force: FloatArray
    coil: FloatArray
    coil_unit: CoilUnit
    acceleration: FloatArray
    gain: float | None = None
    source: str = "arrays"
    notes: tuple[str, ...] = field(default=())

    @classmethod
    def from_arrays(
        cls,
        time: npt.ArrayLike,
        displacement: npt.ArrayLike,
        force: npt.ArrayLike,
        coil: npt.ArrayLike | None,
        *,
        velocity: npt.ArrayLike | None = None,
        coil_unit: str = "A",
        gain: float | None = None,
        source: str = "arrays",
        velocity_window: float = VELOCITY_WINDOW,
        notes: tuple[str, ...] = (),
    ) -> TimeRecord:
        """Check arrays in SI units and build a record (velocity derived when not given).

        Raises
        ------
        ValidationError
            Naming the signal and what is wrong (length, NaN, time order, no coil input,
            implausible unit).
        """
        name = Path(source).name
        if coil is None:
            raise TestDataError(
                f"{name}: the record has no coil input; give the coil current [A] or the "
                "driver's command voltage [V] as a column, e.g. --columns t,x,v,F,u --units "
                "s,m,m/s,N,V (a model needs to know when the damper was energised)"
            )
        unit = str(coil_unit).upper()
        if unit not in ("A", "V"):
            raise ValidationError(f"coil_unit must be 'A' or 'V'; got {coil_unit!r}")
        if gain is not None and not (math.isfinite(gain) and gain > 0):
            raise ValidationError(f"gain (driver A/V) must be > 0; got {gain}")
        signals: dict[str, FloatArray] = {
            "time": np.asarray(time, dtype=float).ravel(),
            "displacement": np.asarray(displacement, dtype=float).ravel(),
            "force": np.asarray(force, dtype=float).ravel(),
            "coil": np.broadcast_to(np.asarray(coil, dtype=float), np.shape(time)).ravel(),
        }
        if velocity is not None:
            signals["velocity"] = np.asarray(velocity, dtype=float).ravel()
        n = signals["time"].size
        for role, arr in signals.items():
            if arr.size != n:
                raise TestDataError(f"{name}: {role} has {arr.size} samples but time has {n}")
        out_notes = list(notes)
        signals = _bridge_nan(name, signals, out_notes)
        t = signals["time"]
        if t.size < 64:
            raise TestDataError(f"{name}: the record has {t.size} samples; at least 64 are needed")
        steps = np.diff(t)
        back = np.flatnonzero(steps <= 0)
        if back.size:
            k = int(back[0])
            raise TestDataError(
                f"{name}: time is not increasing at data row {k + 2} (t = {t[k + 1]:.6g} s "
                f"after {t[k]:.6g} s; {back.size} place{'s' if back.size > 1 else ''}); "
                "sort or split the record"
            )
        dt = float(np.median(steps))
        if float(np.max(np.abs(steps - dt))) > 0.01 * dt:
            grid = t[0] + dt * np.arange(math.floor((t[-1] - t[0]) / dt + 1e-9) + 1)
            signals = {r: np.interp(grid, t, a) for r, a in signals.items() if r != "time"}
            signals["time"] = grid
            out_notes.append(
                f"time steps vary ({steps.min() * 1e3:.4g}-{steps.max() * 1e3:.4g} ms): "
                f"resampled onto a uniform {dt * 1e3:.4g} ms grid"
            )
        _check_plausible(name, signals)
        window = max(5, round(velocity_window / dt))
        if "velocity" not in signals:
            signals["velocity"] = smooth_derivative(signals["displacement"], dt, window)
            out_notes.append(
                f"velocity derived from the displacement (cubic Savitzky-Golay, "
                f"{window | 1} samples = {(window | 1) * dt * 1e3:.3g} ms)"
            )
        accel = smooth_derivative(signals["velocity"], dt, window)
        return cls(
            time=np.ascontiguousarray(signals["time"]),
            displacement=np.ascontiguousarray(signals["displacement"]),
            velocity=np.ascontiguousarray(signals["velocity"]),
            force=np.ascontiguousarray(signals["force"]),
            coil=np.ascontiguousarray(signals["coil"]),
            coil_unit="A" if unit == "A" else "V",
            acceleration=np.ascontiguousarray(accel),
            gain=gain,
            source=str(source),
            notes=tuple(out_notes),
        )

    # -- derived quantities -----------------------------------------------------------
    @property
    def dt(self) -> float:
        """Sampling period [s]."""
        return float(self.time[1] - self.time[0])

    @property
    def sample_rate(self) -> float:
        """Sampling rate [Hz] (rounded to 1e-6 Hz)."""
        return round(1.0 / self.dt, 6)

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return float(self.time[-1] - self.time[0] + self.dt)

    def __len__(self) -> int:
        return int(self.time.size)

    def coil_current(self, model: str = "this model") -> FloatArray:
        """The coil input as current [A] (a voltage needs the driver's ``gain``).

        Raises
        ------
        ValidationError
            For a voltage input without a gain.
        """
        if self.coil_unit == "A":
            return self.coil
        if self.gain is None:
            raise ValidationError(
                f"{model} is driven by current but the record's coil input is a voltage [V] "
                "and no driver gain was given; pass --gain A_PER_V (gain=...) or give the "
                "current column in A"
            )
        return self.coil * self.gain

    def coil_voltage(self, volts_per_amp: float) -> FloatArray:
        """The coil input as command voltage [V] (a current through ``volts_per_amp``)."""
        if self.coil_unit == "V":
            return self.coil
        return self.coil * volts_per_amp

    def segment(self, start: int, stop: int) -> TimeRecord:
        """Samples ``start:stop`` as a record (signals are views)."""
        return replace(
            self,
            time=self.time[start:stop],
            displacement=self.displacement[start:stop],
            velocity=self.velocity[start:stop],
            force=self.force[start:stop],
            coil=self.coil[start:stop],
            acceleration=self.acceleration[start:stop],
        )

    def save(self, path: str | Path, units: str = "s,m,m/s,N") -> Path:
        """Write the record as CSV with a header, in SI or in ``units`` (time, stroke,
        velocity, force; the coil input keeps its own unit).

        Examples
        --------
        >>> import tempfile, pathlib, numpy as np
        >>> t = np.arange(0.0, 0.2, 1e-3)
        >>> rec = TimeRecord.from_arrays(t, 1e-3 * np.sin(40 * t), 50 * np.sin(40 * t), 0.0 * t)
        >>> p = rec.save(pathlib.Path(tempfile.mkdtemp()) / "r.csv", units="s,cm,cm/s,N")
        >>> back = read_record(p, columns="t,x,v,F,i", units="s,cm,cm/s,N,A")
        >>> bool(np.allclose(back.displacement, rec.displacement, rtol=1e-9))
        True
        """
        from mrsuspension.identify.readers import UNITS

        path = Path(path)
        names = [u.strip() for u in units.split(",")]
        if len(names) != 4:
            raise ValidationError(f"units: give four units (t, x, v, F); got {units!r}")
        factors = []
        for role, unit in zip(("time", "displacement", "velocity", "force"), names, strict=True):
            dim, factor = UNITS.get(unit.lower(), ("", 0.0))
            if dim != role:
                raise ValidationError(f"units: {unit!r} is not a unit of {role}")
            factors.append(factor)
        cols = [self.time, self.displacement, self.velocity, self.force]
        table = np.column_stack([c / f for c, f in zip(cols, factors, strict=True)] + [self.coil])
        head = (
            f"time [{names[0]}],displacement [{names[1]}],velocity [{names[2]}],"
            f"force [{names[3]}],coil [{self.coil_unit}]"
        )
        np.savetxt(path, table, delimiter=",", header=head, comments="", fmt="%.10g")
        return path


def _bridge_nan(
    name: str, signals: dict[str, FloatArray], notes: list[str]
) -> dict[str, FloatArray]:
    """Drop rows holding a NaN/inf (bridged by interpolation later) or refuse."""
    bad = np.zeros(signals["time"].size, dtype=bool)
    for arr in signals.values():
        bad |= ~np.isfinite(arr)
    if not bad.any():
        return signals
    count, n = int(bad.sum()), bad.size
    first = int(np.flatnonzero(bad)[0])
    worst = max(signals, key=lambda role: int(np.sum(~np.isfinite(signals[role]))))
    if count > MAX_NAN_FRACTION * n:
        raise TestDataError(
            f"{name}: {count} of {n} rows ({100 * count / n:.1f} %) hold NaN or empty values "
            f"(first at data row {first + 1}, in {worst}); at most "
            f"{100 * MAX_NAN_FRACTION:g} % are bridged: clean or cut the record"
        )
    keep = ~bad
    out = {role: arr[keep] for role, arr in signals.items()}
    notes.append(
        f"{count} row{'s' if count > 1 else ''} with NaN dropped ({100 * count / n:.2f} %, "
        f"first at data row {first + 1}); the gaps are bridged by linear interpolation"
    )
    return out


def _check_plausible(name: str, signals: dict[str, FloatArray]) -> None:
    """A force or stroke column in a wrong unit shows as an implausible magnitude."""
    f = signals["force"]
    peak = float(np.max(np.abs(f - np.median(f)))) if f.size else 0.0
    lo, hi = FORCE_RANGE
    if peak < lo:
        raise TestDataError(
            f"{name}: the force varies by only {peak:.3g} N, implausible for a damper test "
            f"({lo:g} N to {hi:g} N); is the column in kN? (e.g. --units s,mm,mm/s,kN)"
        )
    if peak > hi:
        raise TestDataError(
            f"{name}: the force varies by {peak:.3g} N, implausible for a damper test "
            f"({lo:g} N to {hi:g} N); is the column in mN or in a unit the reader took for N? "
            "Give its unit with --units (N, kN, lbf)"
        )
    x = signals["displacement"]
    stroke = float(np.max(np.abs(x - np.median(x))))
    lo, hi = STROKE_RANGE
    if stroke > hi:
        raise TestDataError(
            f"{name}: the displacement varies by {stroke:.3g} m, implausible for a damper "
            f"({lo * 1e3:g} mm to {hi:g} m); is the column in mm or cm? (e.g. --units s,mm,...)"
        )
    if stroke < lo:
        raise TestDataError(
            f"{name}: the displacement varies by only {stroke * 1e3:.3g} mm; is the column "
            "in m while the header or --units says mm, or is the record idle?"
        )


def _split_coil(
    columns: str | None, units: str | None
) -> tuple[str | None, str | None, float, str | None]:
    """Map the coil roles (``u``, ``voltage``) onto the readers' current role.

    Returns the readers' columns and units texts, the coil factor to SI, and the coil
    unit (``"A"``, ``"V"`` or None: not said).
    """
    coil_unit: str | None = None
    factor = 1.0
    cols_out = columns
    if columns is not None:
        tokens = []
        for tok in columns.split(","):
            key, sep, rest = tok.partition("=")
            bare = key.strip().lstrip("-").lower()
            if bare in _COIL_TOKENS:
                sign = "-" if key.strip().startswith("-") else ""
                key = f"{sign}i"
                if bare in ("voltage", "volt"):
                    coil_unit = "V"
            tokens.append(key + sep + rest)
        cols_out = ",".join(tokens)
    units_out = units
    if units is not None:
        tokens = []
        for tok in units.split(","):
            key, sep, value = tok.partition("=")
            unit = (value if sep else key).strip().lower()
            role = key.strip().lower() if sep else None
            if unit in COIL_UNITS:
                if role is not None and role not in ("i", "current", *_COIL_TOKENS):
                    raise ValidationError(
                        f"--units: {unit!r} is a unit of the coil voltage, not of {role}"
                    )
                coil_unit, factor = "V", COIL_UNITS[unit]
                tokens.append("i=A")  # readers: no conversion; a header unit is overridden
                continue
            if unit in ("a", "ma") and (role is None or role in ("i", "current", *_COIL_TOKENS)):
                coil_unit = "A"
                tokens.append(f"i={unit}")
                continue
            tokens.append(tok)
        units_out = ",".join(tokens)
    return cols_out, units_out, factor, coil_unit


def _columns_from_header(path: Path) -> tuple[str, str | None] | None:
    """Positional roles from a text header naming a coil column (``voltage``, ``coil [V]``).

    The readers match time, stroke, velocity and force by name but know no coil input;
    this finds the header line (the line above the first row of numbers) and returns the
    roles (``_`` for unknown names) and the coil unit named in the header, or None when
    no header column is a coil input.
    """
    if path.suffix.lower() == ".mat" or not path.is_file():
        return None
    header: list[str] | None = None
    with path.open(encoding="utf-8-sig", errors="replace") as fh:
        for _, line in zip(range(200), fh, strict=False):
            text = line.strip()
            if not text or text.startswith(("#", "%", "//")):
                continue
            delim = next((d for d in ("\t", ";", ",") if d in text), None)
            fields = [f.strip() for f in (text.split(delim) if delim else text.split())]
            try:
                [float(f) for f in fields if f]
            except ValueError:
                header = fields
                continue
            break
    if not header:
        return None
    from mrsuspension.identify.readers import split_name_unit

    alias = {a: r for r, names in ROLE_ALIASES.items() for a in names}
    short = {"time": "t", "displacement": "x", "velocity": "v", "acceleration": "a",
             "force": "F", "current": "i"}  # fmt: skip
    roles, coil_unit = [], None
    for name in header:
        key, unit = split_name_unit(name)
        if key in _COIL_TOKENS and coil_unit is None:
            roles.append("u")
            coil_unit = unit or ("V" if key in ("voltage", "volt") else None)
        else:
            role = alias.get(key) or alias.get(key.replace("_", ""))
            roles.append(short[role] if role and short[role] not in roles else "_")
    if coil_unit is None and "u" not in roles:
        return None
    return ",".join(roles), coil_unit


def read_record(
    path: str | Path,
    columns: str | None = None,
    units: str | None = None,
    *,
    gain: float | None = None,
    velocity_window: float = VELOCITY_WINDOW,
) -> TimeRecord:
    """Read a time-domain record (delimited text or ``.mat``) into SI units.

    Parameters
    ----------
    path : str or Path
        The record (any layout :func:`~mrsuspension.identify.readers.read_test` reads).
    columns : str, optional
        Column roles, e.g. ``"t,x,v,F,u"``; ``u`` (or ``voltage``, ``i``) is the coil
        input. Named form: ``"t=Time,x=Disp,F=Load,u=Cmd"``.
    units : str, optional
        Units, e.g. ``"s,cm,cm/s,N,V"``: ``V``/``mV`` make the coil input a voltage,
        ``A``/``mA`` a current (default: current in A; a ``voltage`` column: V).
    gain : float, optional
        Driver gain [A/V] from command voltage to coil current.
    velocity_window : float
        Smoothing window [s] of a derived velocity (default 5 ms).

    Returns
    -------
    TimeRecord

    Raises
    ------
    TestDataError
        No coil input, too many NaN rows, time running backwards, implausible units.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "r.txt"
    >>> rows = [f"{k / 1000} {np.sin(k / 50):.6f} {200 * np.cos(k / 50):.3f} 2.25" for k in range(200)]
    >>> _ = p.write_text("\\n".join(rows))
    >>> rec = read_record(p, columns="t,x,F,u", units="s,cm,N,V", gain=0.2222)
    >>> rec.coil_unit, round(float(rec.coil_current()[0]), 3), round(float(rec.displacement[50]), 5)
    ('V', 0.5, 0.00841)
    """
    if columns is None:
        found = _columns_from_header(Path(path))
        if found is not None:
            columns = found[0]
            if found[1] and found[1].lower() in (*COIL_UNITS, "a", "ma"):
                units = f"{units},u={found[1]}" if units else f"u={found[1]}"
    cols, unit_text, factor, coil_unit = _split_coil(columns, units)
    raw = read_test(path, cols, unit_text)
    name = Path(path).name
    if raw.displacement is None:
        raise TestDataError(
            f"{name}: a time-domain fit needs the displacement (found: {', '.join(raw.roles)}); "
            "models with springs and internal states use the stroke, not only the velocity"
        )
    coil = raw.current
    if coil is not None:
        coil = np.asarray(coil, dtype=float) * factor
    if coil_unit is None and coil is not None:
        coil_unit = "A"
    notes = list(raw.notes)
    if coil is not None:
        notes.append(
            f"coil input: {'command voltage [V]' if coil_unit == 'V' else 'current [A]'}"
            + (f", driver gain {gain:g} A/V" if gain is not None else "")
        )
    return TimeRecord.from_arrays(
        raw.time,
        raw.displacement,
        raw.force,
        coil,
        velocity=raw.velocity,
        coil_unit=coil_unit or "A",
        gain=gain,
        source=str(path),
        velocity_window=velocity_window,
        notes=tuple(notes),
    )
