"""Random roads: elevation profiles driven at a constant speed (model reference, section 8).

A :class:`RoadProfile` holds an elevation profile ``h(x)`` [m] over distance ``x`` [m]
and turns it into a time signal ``z_r(t) = h(x_0 + V t)`` through a C2 cubic spline, so
the road velocity ``V h'`` and acceleration ``V^2 h''`` are exact derivatives of the
displacement the vehicle sees. Profiles come from a measured file
(:meth:`RoadProfile.from_csv`), from synthesis of a power-law PSD
(:class:`RoadSpectrum`, :func:`synthesise_road`): an ISO 8608 class (:func:`iso8608`)
or one of the three presets (:func:`preset_road`) that stand in for the dissertation's
Canadian roads, each defined by its PSD level.
"""

from __future__ import annotations

import csv
import math
import re
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.errors import ValidationError, check_finite, did_you_mean, unknown_name
from mrsuspension.excitation.base import (
    Excitation,
    FloatArray,
    Option,
    grid_args,
    non_negative,
    positive,
    time_array,
)
from mrsuspension.excitation.deterministic import REFERENCE_SPEED_KMH

if TYPE_CHECKING:
    from scipy.interpolate import CubicSpline

__all__ = [
    "ISO8608_BAND",
    "ISO8608_CLASSES",
    "ISO8608_N0",
    "PRESET_BAND",
    "PRESET_IDENTIFIED",
    "PRESET_ROADS",
    "PRESET_SPECTRA",
    "PRESET_WAVINESS",
    "PresetRoad",
    "RoadBandWarning",
    "RoadProfile",
    "RoadSpectrum",
    "SpatialPsd",
    "band_spacing",
    "iso8608",
    "iso8608_psd",
    "preset_road",
    "synthesise_road",
]

#: ISO 8608 reference spatial frequency n0 [cycle/m]
ISO8608_N0 = 0.1
#: ISO 8608 classes: geometric mean of Gd(n0) [m^3] (model reference, section 8)
ISO8608_CLASSES: dict[str, float] = {
    "A": 16e-6,
    "B": 64e-6,
    "C": 256e-6,
    "D": 1024e-6,
    "E": 4096e-6,
    "F": 16384e-6,
    "G": 65536e-6,
    "H": 262144e-6,
}
#: spatial-frequency band [cycle/m] over which ISO 8608 defines the road spectrum
ISO8608_BAND = (0.011, 2.83)
#: fewest profile points a spline road accepts
MIN_POINTS = 4
#: A preset's spectrum (the ``spectrum`` option of a road): the model reference's
#: (:data:`PRESET_ROADS`, the default) or the one identified from the dissertation's road
#: numbers (:data:`PRESET_IDENTIFIED`, ``tools/identify_roads.py``)
PRESET_SPECTRA = ("reference", "identified")
#: By default a synthesised road's band ends at most at this fraction of the Nyquist
#: frequency ``1/(2 spacing)``: the cubic spline the wheel rides then keeps 98.6 % of the
#: amplitude at the band's top (0.5 of Nyquist) and more below (issue 27).
BAND_TOP_OF_NYQUIST = 0.5
#: A given spacing that puts the band's top above this fraction of the Nyquist frequency
#: is warned about (:class:`RoadBandWarning`): the spline keeps 96 % of the amplitude
#: there, less above, and nothing past the Nyquist frequency.
BAND_TOP_WARN = 0.6


class RoadBandWarning(UserWarning):
    """A synthesised road's point spacing cuts or filters the top of its declared band."""


def band_spacing(band_top: float) -> float:
    """Default point spacing [m] of a road synthesised up to ``band_top`` [cycle/m].

    The largest value of the 1-2-5 series (0.01, 0.02, 0.05, 0.1, ...) that puts the top
    of the band at most at :data:`BAND_TOP_OF_NYQUIST` of the Nyquist frequency
    ``1/(2 spacing)``, so the road the wheel rides (a cubic spline through the points)
    holds the whole band. ISO 8608's band (0.011-2.83 cycle/m) gives 0.05 m.

    Examples
    --------
    >>> band_spacing(2.83), band_spacing(2.0), band_spacing(10.0)
    (0.05, 0.1, 0.02)
    """
    top = positive("band_top", band_top, "cycle/m", high=1e3)
    limit = BAND_TOP_OF_NYQUIST / (2.0 * top)
    decade = 10.0 ** math.floor(math.log10(limit) + 1e-12)
    step = max(m for m in (1.0, 2.0, 5.0) if m * decade <= limit * (1 + 1e-12))
    return float(f"{step * decade:.12g}")


@dataclass(frozen=True)
class SpatialPsd:
    """One-sided spatial PSD of a road profile; unpacks as ``n, Gd = road.spatial_psd()``.

    Attributes
    ----------
    spatial_frequency : ndarray
        Spatial frequency ``n`` [cycle/m].
    density : ndarray
        Displacement PSD ``Gd(n)`` [m^3] (m^2 per cycle/m), as in ISO 8608.
    nperseg : int
        Welch segment length used (samples).
    """

    spatial_frequency: FloatArray
    density: FloatArray
    nperseg: int

    def __iter__(self) -> Iterator[FloatArray]:
        yield self.spatial_frequency
        yield self.density


@njit(cache=True)
def _spline_grid(
    breaks: np.ndarray,
    coefs: np.ndarray,
    speed: float,
    fade_in: float,
    step: float,
    t0: float,
    z: np.ndarray,
    v: np.ndarray,
) -> None:
    """``z = w h(x)``, ``v = V (w' h + w h')`` on ``x = x0 + V (t0 + k step)`` (:meth:`RoadProfile.sample_grid`).

    ``breaks``/``coefs``: the spline's piecewise-polynomial form (``coefs[j, i]`` multiplies
    ``(x - breaks[i])**(3 - j)``); outside the profile the end elevations and zero
    velocity. The first point's interval is found by bisection, the others by walking.
    """
    x0 = breaks[0]
    xend = breaks[-1]
    last = breaks.shape[0] - 2
    xs = min(max(x0 + speed * t0, x0), xend)
    lo = 0
    hi = last
    while lo < hi:  # the last breakpoint <= xs (the interval a walk from 0 would reach)
        mid = (lo + hi + 1) // 2
        if breaks[mid] <= xs:
            lo = mid
        else:
            hi = mid - 1
    i = lo
    for k in range(z.shape[0]):
        x = x0 + speed * (t0 + k * step)
        inside = x0 <= x <= xend
        xc = min(max(x, x0), xend)
        while i < last and xc >= breaks[i + 1]:
            i += 1
        s = xc - breaks[i]
        c0, c1, c2, c3 = coefs[0, i], coefs[1, i], coefs[2, i], coefs[3, i]
        h = ((c0 * s + c1) * s + c2) * s + c3
        dh = (3.0 * c0 * s + 2.0 * c1) * s + c2
        if fade_in > 0.0:  # the C2 ramp w(x) and the product rule, as in _derivatives
            u = min(max((xc - x0) / fade_in, 0.0), 1.0)
            w0 = u**3 * (10.0 - 15.0 * u + 6.0 * u * u)
            w1 = 30.0 * u * u * (1.0 - u) ** 2 / fade_in
            dh = w1 * h + w0 * dh
            h = w0 * h
        z[k] = h
        v[k] = dh * speed if inside else 0.0


@dataclass(frozen=True, eq=False)
class RoadProfile(Excitation):
    """An elevation profile driven at constant speed: ``z_r(t) = h(x_0 + V t)``.

    Parameters
    ----------
    distance : array_like
        Distance along the road ``x`` [m], strictly increasing, at least 4 points (any
        spacing).
    elevation : array_like
        Road elevation ``h(x)`` [m], positive up, finite, same length as ``distance``.
    speed_kmh : float, optional
        Vehicle speed ``V`` [km/h], 50 by default (the dissertation uses 50 and 100).
    fade_in : float, optional
        Length [m] over which the profile is faded in from zero with a C2 ramp
        (``6u^5 - 15u^4 + 10u^3``), so a run starting at rest does not begin with a
        step. 0 (no fade, the data as given) by default.
    source : str, optional
        Where the profile comes from (a file name, a preset, an ISO 8608 class...).
    spectrum : RoadSpectrum, optional
        The PSD a synthesised profile was drawn from (None for measured data).

    Notes
    -----
    The spline is :class:`scipy.interpolate.CubicSpline` (not-a-knot ends), twice
    continuously differentiable; velocity and acceleration are its derivatives times
    ``V`` and ``V^2``. Time 0 is the first profile point. Outside the profile
    (``t < 0`` or ``t > duration``) the road holds its end elevation, with zero velocity
    and acceleration. The profile's elevation at ``t = 0`` is generally not zero: start
    the vehicle on it (or use ``fade_in``).

    Examples
    --------
    >>> x = np.arange(0.0, 10.0, 0.5)
    >>> road = RoadProfile(x, 0.01 * np.sin(x), speed_kmh=36.0)  # V = 10 m/s
    >>> road.duration
    0.95
    >>> round(float(road.displacement(0.05)), 5)  # the profile at x = 0.5 m
    0.00479
    """

    distance: FloatArray
    elevation: FloatArray
    speed_kmh: float = REFERENCE_SPEED_KMH
    fade_in: float = 0.0
    source: str = "user data"
    spectrum: RoadSpectrum | None = None
    _spline: CubicSpline = field(init=False, repr=False, compare=False)
    #: the spline's breakpoints and coefficients, contiguous (for :meth:`sample_grid`)
    _pp: tuple[FloatArray, FloatArray] = field(init=False, repr=False, compare=False)

    name: ClassVar[str] = "road"
    measures_kind: ClassVar[str] = "road"
    options: ClassVar[tuple[Option, ...]] = (
        Option("profile", "string", "",
               "preset name (smooth, medium-rough, rough) or a CSV file path"),
        Option("iso_class", "string", "", "ISO 8608 class A-H (instead of profile)",
               choices=tuple("ABCDEFGH")),
        Option("seed", "integer", "",
               "random-phase seed of an ISO 8608 class (0 by default) or a preset (its own "
               "fixed seed by default; any seed gives the same PSD level)", low=0.0),
        Option("length", "number", "m", "ISO 8608 profile length [m], 500 by default",
               low=0.0, high=1e6, low_inclusive=False),
        Option("spacing", "number", "m",
               "ISO 8608 point spacing [m]; by default from the band (0.05 m: ISO's top "
               "2.83 cycle/m at half the Nyquist frequency)", low=0.0, low_inclusive=False),
        Option("speed", "number", "km/h", "vehicle speed [km/h], 50 by default",
               default=REFERENCE_SPEED_KMH, low=0.0, high=500.0, low_inclusive=False,
               keyword="speed_kmh"),
        Option("scale", "number", "",
               "elevation scale factor, 1 by default (HiL used 0.5 on the rough road)",
               low=0.0, high=1e3, low_inclusive=False),
        Option("fade_in", "number", "m",
               "length [m] over which the profile fades in from zero, 0 by default", low=0.0),
        Option("spectrum", "string", "",
               "a preset's spectrum: 'reference' (the model reference's n^-1 presets, by "
               "default) or 'identified' (fitted to the dissertation's road numbers, "
               "PRESET_IDENTIFIED)", choices=PRESET_SPECTRA),
        Option("level", "number", "m^3",
               "a preset's Gd(n0) [m^3] at n0 = 0.1 cycle/m, replacing its own",
               low=0.0, high=1.0, low_inclusive=False),
        Option("waviness", "number", "",
               "a preset's PSD slope w of Gd(n) ~ n^-w, replacing its own (1)",
               low=0.0, high=5.0),
        Option("band", "numbers", "cycle/m",
               "a preset's spatial-frequency band [n_min, n_max] [cycle/m], replacing its own"),
        Option("distance_unit", "string", "", "unit of the CSV distance column, m or mm",
               choices=("m", "mm")),
        Option("elevation_unit", "string", "", "unit of the CSV elevation column, m or mm",
               choices=("m", "mm")),
    )  # fmt: skip
    example_options: ClassVar[dict[str, Any]] = {"profile": "smooth"}
    #: the sampled profile, its label and PSD come from ``profile`` or ``iso_class``
    internal_parameters: ClassVar[tuple[str, ...]] = ("distance", "elevation", "source", "spectrum")

    def __post_init__(self) -> None:
        distance, elevation = _check_profile(
            self.distance,
            self.elevation,
            lambda i: f"index {i}",
            lambda i: f"road profile, index {i}",
        )
        distance.setflags(write=False)
        elevation.setflags(write=False)
        object.__setattr__(self, "distance", distance)
        object.__setattr__(self, "elevation", elevation)
        object.__setattr__(
            self, "speed_kmh", positive("speed_kmh", self.speed_kmh, "km/h", high=500.0)
        )
        length = float(distance[-1] - distance[0])
        object.__setattr__(self, "fade_in", non_negative("fade_in", self.fade_in, "m", high=length))
        if not isinstance(self.source, str):
            raise ValidationError(f"source must be a string; got {self.source!r}")
        if self.spectrum is not None and not isinstance(self.spectrum, RoadSpectrum):
            raise ValidationError(f"spectrum must be a RoadSpectrum or None; got {self.spectrum!r}")
        from scipy.interpolate import CubicSpline  # here: scipy loads with the first road

        spline = CubicSpline(distance, elevation)
        object.__setattr__(self, "_spline", spline)
        pp = (np.ascontiguousarray(spline.x), np.ascontiguousarray(spline.c))
        object.__setattr__(self, "_pp", pp)

    # -- construction ---------------------------------------------------------------
    @classmethod
    def from_options(
        cls, options: Mapping[str, Any], *, base_dir: str | Path | None = None
    ) -> RoadProfile:
        """A road from scenario options: a preset, a CSV file or an ISO 8608 class.

        Exactly one of ``profile`` (a preset name or a CSV path, relative paths taken
        from ``base_dir``) and ``iso_class``; see
        :data:`~mrsuspension.excitation.EXCITATION_OPTIONS` for the rest.

        Examples
        --------
        >>> RoadProfile.from_options({"iso_class": "C", "length": 100.0}).distance.size
        2001
        """
        return _road_from_options(options, base_dir)

    def to_options(self) -> dict[str, Any] | None:
        """None: a road's samples are not held by options (its ``source`` says where from)."""
        return None

    @classmethod
    def from_csv(
        cls,
        path: str | Path,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        columns: tuple[int | str, int | str] | None = None,
        distance_unit: str | None = None,
        elevation_unit: str | None = None,
        delimiter: str | None = None,
        fade_in: float = 0.0,
    ) -> RoadProfile:
        """Read a profile from a CSV file of distance and elevation.

        Blank lines and lines starting with ``#`` are skipped. A header line is optional;
        it is recognised by a field that is not a number. Delimiters ``,``, ``;``, tab or
        spaces are detected from the first data line.

        Parameters
        ----------
        path : str or Path
            The file.
        speed_kmh : float, optional
            Vehicle speed [km/h], 50 by default.
        columns : (int or str, int or str), optional
            Distance and elevation columns, by 0-based index or by header name. By
            default the header columns named ``distance...`` and ``elevation...`` if
            there are, else the first two columns.
        distance_unit, elevation_unit : {"m", "mm"}, optional
            Units of the columns. By default a unit in the header name (``"elevation
            [mm]"``, ``"distance (m)"``), else metres.
        delimiter : str, optional
            Field delimiter; detected by default.
        fade_in : float, optional
            See :class:`RoadProfile`.

        Raises
        ------
        ValidationError
            Missing file, malformed line (the message names it), NaN/inf, unsorted or
            repeated distance, fewer than 4 points, unknown unit or column.

        Examples
        --------
        >>> import tempfile, os
        >>> with tempfile.TemporaryDirectory() as d:
        ...     p = os.path.join(d, "road.csv")
        ...     _ = open(p, "w").write("distance [m],elevation [mm]\\n0,0\\n1,2\\n2,1\\n3,-1\\n")
        ...     road = RoadProfile.from_csv(p, speed_kmh=36.0)
        >>> road.elevation
        array([ 0.   ,  0.002,  0.001, -0.001])
        """
        from mrsuspension._inputs import read_text

        path = Path(path)
        if not path.is_file() and not path.is_dir():
            raise ValidationError(f"road profile file not found: {str(path)!r}")
        # recorded: a study's cache key holds the file's content
        text = read_text(path, "road profile file", encoding="utf-8-sig")
        where = f"road profile {path.name!r}"
        rows = [
            (k, line)
            for k, line in enumerate(text.splitlines(), start=1)
            if line.strip() and not line.lstrip().startswith("#")
        ]
        if not rows:
            raise ValidationError(f"{where} holds no data")
        if delimiter is None:
            delimiter = _detect_delimiter(rows[0][1])
        split = _splitter(delimiter)
        header: list[str] | None = None
        first = split(rows[0][1])
        if not all(_is_number(f) for f in first):
            header = first
            rows = rows[1:]
        i_dist, i_elev = _resolve_columns(columns, header, where)
        d_scale = _unit_scale("distance_unit", distance_unit, header, i_dist)
        e_scale = _unit_scale("elevation_unit", elevation_unit, header, i_elev)
        lines: list[int] = []
        dist: list[float] = []
        elev: list[float] = []
        for lineno, line in rows:
            fields = split(line)
            if len(fields) <= max(i_dist, i_elev):
                raise ValidationError(
                    f"{where}, line {lineno}: expected at least {max(i_dist, i_elev) + 1} "
                    f"columns, got {len(fields)}: {line.strip()!r}"
                )
            for label, i, out in (("distance", i_dist, dist), ("elevation", i_elev, elev)):
                try:
                    out.append(float(fields[i]))
                except ValueError:
                    raise ValidationError(
                        f"{where}, line {lineno}: {label} is not a number: {fields[i]!r}"
                    ) from None
            lines.append(lineno)
        distance, elevation = _check_profile(
            np.array(dist) * d_scale,
            np.array(elev) * e_scale,
            lambda i: f"line {lines[i]}",
            lambda i: f"{where}, line {lines[i]}",
            what=where,
        )
        return cls(distance, elevation, speed_kmh, fade_in=fade_in, source=str(path))

    def scaled(self, factor: float) -> RoadProfile:
        """A copy with every elevation multiplied by ``factor`` (> 0).

        The HiL tests drive the rough road at 50 %: ``preset_road("rough").scaled(0.5)``.
        A synthesised profile's ``spectrum`` scales with it (``Gd(n0)`` times
        ``factor^2``).

        Examples
        --------
        >>> half = preset_road("rough").scaled(0.5)
        >>> half.spectrum.level  # 2.7e-5 / 4
        6.75e-06
        """
        k = positive("factor", factor, "", high=1e3)
        spectrum = None if self.spectrum is None else self.spectrum.scaled(k)
        return replace(
            self,
            elevation=self.elevation * k,
            source=f"{self.source}, scaled x{k:g}",
            spectrum=spectrum,
        )

    def with_speed(self, speed_kmh: float) -> RoadProfile:
        """The same profile driven at another speed [km/h]."""
        return replace(self, speed_kmh=speed_kmh)

    def to_csv(self, path: str | Path) -> Path:
        """Write ``distance [m],elevation [m]`` with a header; :meth:`from_csv` reads it back."""
        path = Path(path)
        with path.open("w", newline="") as fh:
            writer = csv.writer(fh)
            writer.writerow(["distance [m]", "elevation [m]"])
            for x, h in zip(self.distance, self.elevation, strict=True):
                writer.writerow([repr(float(x)), repr(float(h))])
        return path

    # -- properties -----------------------------------------------------------------
    @property
    def speed(self) -> float:
        """Vehicle speed ``V`` [m/s]."""
        return self.speed_kmh / 3.6

    @property
    def length(self) -> float:
        """Profile length [m]."""
        return float(self.distance[-1] - self.distance[0])

    @property
    def spacing(self) -> float:
        """Median distance between profile points [m] (to 12 significant digits)."""
        return float(f"{np.median(np.diff(self.distance)):.12g}")

    @property
    def duration(self) -> float:
        """Time to drive the profile, ``length / V`` [s]."""
        return self.length / self.speed

    @property
    def peak_elevation(self) -> float:
        """Largest ``|h|`` over the profile points [m]."""
        return float(np.max(np.abs(self.elevation)))

    @property
    def rms_elevation(self) -> float:
        """RMS elevation of the profile points [m]."""
        return float(np.sqrt(np.mean(self.elevation**2)))

    def __repr__(self) -> str:
        psd = "" if self.spectrum is None else f", {self.spectrum.label()}"
        return (
            f"RoadProfile(source={self.source!r}, length={self.length:g} m, "
            f"{self.distance.size} points, speed_kmh={self.speed_kmh:g}{psd}, "
            f"rms {self.rms_elevation * 1e3:.3g} mm, peak {self.peak_elevation * 1e3:.3g} mm)"
        )

    # -- the time signal --------------------------------------------------------------
    def _derivatives(self, t: npt.ArrayLike, order: int) -> FloatArray:
        tt = time_array(t)
        x0 = float(self.distance[0])
        x = x0 + self.speed * tt
        inside = (x >= x0) & (x <= self.distance[-1])
        xc = np.clip(x, x0, self.distance[-1])
        h = [self._spline(xc, k) for k in range(order + 1)]
        if self.fade_in > 0.0:  # product rule with the C2 ramp w(x)
            u = np.clip((xc - x0) / self.fade_in, 0.0, 1.0)
            w = [
                u**3 * (10.0 - 15.0 * u + 6.0 * u * u),
                30.0 * u * u * (1.0 - u) ** 2 / self.fade_in,
                60.0 * u * (1.0 - u) * (1.0 - 2.0 * u) / self.fade_in**2,
            ]
            if order == 0:
                value = w[0] * h[0]
            elif order == 1:
                value = w[1] * h[0] + w[0] * h[1]
            else:
                value = w[2] * h[0] + 2.0 * w[1] * h[1] + w[0] * h[2]
        else:
            value = h[order]
        if order == 0:
            return np.asarray(value, dtype=float)
        return np.where(inside, value * self.speed**order, 0.0)

    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """``z_r(t) = h(x_0 + V t)`` [m] (the end elevations outside the profile)."""
        return self._derivatives(t, 0)

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """``(z_r, dz_r/dt)`` at ``start + k * step``, ``k < n``, in one compiled pass (~10x faster).

        The grid's distances increase, so the spline's interval is found by walking the
        breakpoints (after a bisection for the first point) instead of a search per
        point, and the elevation, its slope and the fade-in ramp come out of the same
        pass. Agrees with :meth:`displacement` and :meth:`velocity` to round-off (the
        cubic is evaluated in Horner form).

        Examples
        --------
        >>> road = preset_road("rough")
        >>> zr, vr = road.sample_grid(20001, 5e-5)
        >>> t = np.arange(20001) * 5e-5
        >>> bool(np.allclose(zr, road.displacement(t), rtol=0, atol=1e-15))
        True
        >>> bool(np.allclose(vr, road.velocity(t), rtol=1e-12, atol=1e-15))
        True
        >>> zr, vr = road.sample_grid(21, 5e-5, start=20.0)  # a HiL tick at 20 s
        >>> bool(np.allclose(zr, road.displacement(20.0 + np.arange(21) * 5e-5), rtol=0, atol=1e-15))
        True
        """
        n, step, start = grid_args(n, step, start)
        z = np.empty(n)
        v = np.empty(n)
        _spline_grid(
            self._pp[0],
            self._pp[1],
            self.speed,
            self.fade_in,
            step,
            start,
            z,
            v,
        )
        return z, v

    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """``dz_r/dt = V h'(x)`` [m/s] (zero outside the profile)."""
        return self._derivatives(t, 1)

    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """``d2z_r/dt2 = V^2 h''(x)`` [m/s^2] (zero outside the profile)."""
        return self._derivatives(t, 2)

    def elevation_at(self, x: npt.ArrayLike) -> FloatArray:
        """The spline profile ``h(x)`` [m] at distances ``x`` [m] (without fade-in)."""
        xx = check_finite("distance", x)
        return np.asarray(self._spline(xx), dtype=float)

    def spatial_psd(self, nperseg: int | None = None) -> SpatialPsd:
        """One-sided spatial PSD ``Gd(n)`` [m^3] of the profile (Welch, Hann, 50 % overlap).

        Profiles with uneven spacing are first resampled from the spline at the median
        spacing. ``nperseg`` defaults to the largest power of two of points spanning at
        most 153.6 m (512 points at 0.3 m spacing, 2048 at 0.05 m), or the whole profile
        if shorter. The mean is removed from every segment.

        Examples
        --------
        >>> road = iso8608("C", length=2000.0, seed=1)
        >>> n, gd = road.spatial_psd()
        >>> k = np.argmin(abs(n - 0.1))
        >>> bool(0.5 < gd[k] / 256e-6 < 2.0)  # Gd(0.1 cycle/m) of class C
        True
        """
        dx = self.spacing
        d = np.diff(self.distance)
        if np.allclose(d, dx, rtol=1e-6, atol=0.0):
            h = np.asarray(self.elevation, dtype=float)
        else:
            x = self.distance[0] + dx * np.arange(int(self.length / dx) + 1)
            h = np.asarray(self._spline(x), dtype=float)
        if nperseg is None:
            seg = min(h.size, max(MIN_POINTS, 2 ** math.floor(math.log2(153.6 / dx + 1e-9))))
        else:
            if isinstance(nperseg, bool) or not isinstance(nperseg, int | np.integer):
                raise ValidationError(f"nperseg must be an integer; got {nperseg!r}")
            if not MIN_POINTS <= nperseg <= h.size:
                raise ValidationError(
                    f"nperseg must be in [{MIN_POINTS}, {h.size}] (the profile's points); got {nperseg}"
                )
            seg = int(nperseg)
        from scipy.signal import welch

        n, gd = welch(h, fs=1.0 / dx, window="hann", nperseg=seg, noverlap=seg // 2)
        return SpatialPsd(np.asarray(n, dtype=float), np.asarray(gd, dtype=float), seg)

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, source, speed, length, spacing, points, peak/rms elevation, PSD.

        ``"spectrum"`` is the synthesised profile's :meth:`RoadSpectrum.describe` (its
        ``Gd(n0)``, waviness and band), None for measured data.
        """
        return {
            "kind": self.name,
            "source": self.source,
            "speed_kmh": self.speed_kmh,
            "length": self.length,
            "spacing": self.spacing,
            "points": int(self.distance.size),
            "peak_elevation": self.peak_elevation,
            "rms_elevation": self.rms_elevation,
            "fade_in": self.fade_in,
            "duration": self.duration,
            "spectrum": None if self.spectrum is None else self.spectrum.describe(),
        }


# -- checks and CSV helpers -------------------------------------------------------------
def _check_profile(
    distance: object,
    elevation: object,
    at: Callable[[int], str],
    prefix: Callable[[int], str],
    what: str = "road profile",
) -> tuple[FloatArray, FloatArray]:
    """Validate a profile; ``at(i)`` / ``prefix(i)`` name point ``i`` in messages."""
    arrays = []
    for label, value in (("distance", distance), ("elevation", elevation)):
        try:
            arr = np.array(value, dtype=float)
        except (TypeError, ValueError):
            raise ValidationError(
                f"{what}: {label} must be an array of numbers; got {value!r}"
            ) from None
        if arr.ndim != 1:
            raise ValidationError(f"{what}: {label} must be one-dimensional; got shape {arr.shape}")
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            i = int(bad[0])
            raise ValidationError(f"{prefix(i)}: {label} must be finite; got {arr[i]}")
        arrays.append(arr)
    d, h = arrays
    if d.size != h.size:
        raise ValidationError(
            f"{what}: distance and elevation must have the same length; got {d.size} and {h.size}"
        )
    if d.size < MIN_POINTS:
        raise ValidationError(
            f"{what} needs at least {MIN_POINTS} points for a cubic spline; got {d.size}"
        )
    step = np.diff(d)
    bad = np.flatnonzero(step <= 0.0)
    if bad.size:
        i = int(bad[0])
        if step[i] == 0.0:
            raise ValidationError(
                f"{what}: repeated distance {d[i]:g} m at {at(i)} and {at(i + 1)}; "
                "distance must be strictly increasing"
            )
        raise ValidationError(
            f"{what}: distance must be strictly increasing; {d[i + 1]:g} m at {at(i + 1)} "
            f"follows {d[i]:g} m at {at(i)}"
        )
    return d, h


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _detect_delimiter(line: str) -> str:
    for candidate in (",", ";", "\t"):
        if candidate in line:
            return candidate
    return " "


def _splitter(delimiter: str) -> Callable[[str], list[str]]:
    if delimiter == " ":
        return lambda line: line.split()
    return lambda line: [f.strip() for f in line.split(delimiter)]


_UNIT = re.compile(r"[\[(]\s*(mm|m)\s*[\])]", re.IGNORECASE)
_SCALES = {"m": 1.0, "mm": 1e-3}


def _resolve_columns(
    columns: Sequence[int | str] | None, header: list[str] | None, where: str
) -> tuple[int, int]:
    names = [_UNIT.sub("", h).strip().lower() for h in header] if header else []
    if columns is None:
        if names:
            dist = [i for i, n in enumerate(names) if n.startswith("distance")]
            elev = [i for i, n in enumerate(names) if n.startswith("elevation")]
            if dist and elev:
                return dist[0], elev[0]
        return 0, 1
    if isinstance(columns, str) or len(columns) != 2:
        raise ValidationError(
            f"columns must be a pair (distance column, elevation column); got {columns!r}"
        )
    out = []
    for label, col in zip(("distance", "elevation"), columns, strict=True):
        if isinstance(col, str):
            if header is None:
                raise ValidationError(
                    f"{where} has no header line, so column {col!r} cannot be found; "
                    "give 0-based column indices instead"
                )
            key = col.strip().lower()
            matches = [
                i for i, n in enumerate(names) if n == key or header[i].strip().lower() == key
            ]
            if not matches:
                raise unknown_name(f"{label} column in {where}", col, [h.strip() for h in header])
            out.append(matches[0])
        elif isinstance(col, int | np.integer) and not isinstance(col, bool) and col >= 0:
            out.append(int(col))
        else:
            raise ValidationError(
                f"{label} column must be a 0-based index or a header name; got {col!r}"
            )
    return out[0], out[1]


def _unit_scale(option: str, unit: str | None, header: list[str] | None, column: int) -> float:
    if unit is None:
        if header is not None and column < len(header):
            m = _UNIT.search(header[column])
            if m:
                return _SCALES[m.group(1).lower()]
        return 1.0
    if unit not in _SCALES:
        raise unknown_name(f"unit for {option}", str(unit), _SCALES)
    return _SCALES[unit]


# -- power-law spectra and their synthesis ------------------------------------------------
def _band(band: object) -> tuple[float, float]:
    """A checked spatial-frequency band ``(n_min, n_max)`` [cycle/m]."""
    if isinstance(band, str) or not isinstance(band, Sequence) or len(band) != 2:
        raise ValidationError(f"band must be a pair (n_min, n_max) [cycle/m]; got {band!r}")
    n_lo = positive("band[0]", band[0], "cycle/m", high=1e3)
    n_hi = positive("band[1]", band[1], "cycle/m", high=1e3)
    if n_hi <= n_lo:
        raise ValidationError(f"band must have n_max > n_min; got {band!r}")
    return n_lo, n_hi


@dataclass(frozen=True)
class RoadSpectrum:
    """A power-law road displacement PSD ``Gd(n) = Gd(n0) (n/n0)^-w`` over a band.

    ISO 8608's form (model reference, section 8): ISO classes have waviness ``w = 2``; the
    preset roads have ``w = 1`` (section 8(c)). Outside ``band`` the density is zero.

    Parameters
    ----------
    level : float
        ``Gd(n0)`` [m^3] (m^2 per cycle/m), in (0, 1].
    waviness : float, optional
        Exponent ``w`` in [0, 5]; the log-log slope of ``Gd(n)`` is ``-w``. 2 by default.
    band : (float, float), optional
        Spatial-frequency band ``(n_min, n_max)`` [cycle/m]; ISO 8608's 0.011-2.83.
    reference_frequency : float, optional
        ``n0`` [cycle/m], 0.1 (ISO 8608).

    Examples
    --------
    >>> s = RoadSpectrum(2.7e-5, waviness=1.0, band=(0.011, 2.0))
    >>> s.density([0.1, 1.0, 3.0])  # zero outside the band
    array([2.7e-05, 2.7e-06, 0.0e+00])
    >>> round(s.rms_elevation * 1e3, 2)  # sqrt(Gd(n0) n0 ln(2/0.011)) [mm]
    3.75
    >>> s.scaled(0.5).level  # elevations x0.5: PSD x0.25
    6.75e-06
    """

    level: float
    waviness: float = 2.0
    band: tuple[float, float] = ISO8608_BAND
    reference_frequency: float = ISO8608_N0

    def __post_init__(self) -> None:
        object.__setattr__(self, "level", positive("Gd(n0) level", self.level, "m^3", high=1.0))
        object.__setattr__(self, "waviness", non_negative("waviness", self.waviness, "", high=5.0))
        object.__setattr__(self, "band", _band(self.band))
        object.__setattr__(
            self,
            "reference_frequency",
            positive("reference_frequency", self.reference_frequency, "cycle/m", high=1e3),
        )

    def density(self, spatial_frequency: npt.ArrayLike) -> FloatArray:
        """``Gd(n)`` [m^3] at spatial frequencies ``n`` > 0 [cycle/m] (zero outside the band)."""
        n = check_finite("spatial_frequency", spatial_frequency)
        if np.any(n <= 0):
            raise ValidationError("spatial_frequency must be > 0 cycle/m")
        gd = self.level * (n / self.reference_frequency) ** -self.waviness
        inside = (n >= self.band[0]) & (n <= self.band[1])
        return np.asarray(np.where(inside, gd, 0.0), dtype=float)

    @property
    def rms_elevation(self) -> float:
        """``sqrt(integral of Gd(n) dn over the band)`` [m]: the rms of a road of this PSD."""
        lo, hi = self.band
        n0, w = self.reference_frequency, self.waviness
        if w == 1.0:
            var = self.level * n0 * math.log(hi / lo)
        else:
            var = self.level * n0**w * (hi ** (1.0 - w) - lo ** (1.0 - w)) / (1.0 - w)
        return math.sqrt(var)

    def scaled(self, factor: float) -> RoadSpectrum:
        """The spectrum of the elevations times ``factor`` (> 0): ``Gd(n0)`` times ``factor^2``."""
        k = positive("factor", factor, "", high=1e3)
        return replace(self, level=self.level * k * k)

    def describe(self) -> dict[str, Any]:
        """Plain data: ``Gd(n0)`` [m^3], waviness, band [cycle/m], ``n0``, rms [m]."""
        return {
            "level": self.level,
            "waviness": self.waviness,
            "band": list(self.band),
            "reference_frequency": self.reference_frequency,
            "rms_elevation": self.rms_elevation,
        }

    def label(self) -> str:
        """Short text: ``"Gd(n0) 2.7e-05 m^3, n^-1, 0.011-2 cycle/m"``."""
        return (
            f"Gd(n0) {self.level:.3g} m^3, n^-{self.waviness:g}, "
            f"{self.band[0]:g}-{self.band[1]:.4g} cycle/m"
        )


def synthesise_road(
    spectrum: RoadSpectrum,
    length: float = 500.0,
    spacing: float | None = None,
    seed: int = 0,
    speed_kmh: float = REFERENCE_SPEED_KMH,
    *,
    fade_in: float = 0.0,
    source: str | None = None,
) -> RoadProfile:
    """Synthesise a road of a given PSD as a sum of cosines with random phases.

    ``h(x) = sum_k sqrt(2 Gd(n_k) dn) cos(2 pi n_k x + phi_k)`` over the spatial
    frequencies ``n_k = k dn``, ``dn = 1/(N spacing)``, inside the spectrum's band and
    below the Nyquist frequency ``1/(2 spacing)``. The default spacing
    (:func:`band_spacing`) holds the whole band; a spacing that cuts or filters its top
    (band top above 0.6 of the Nyquist frequency) is warned about
    (:class:`RoadBandWarning`), and the profile's ``spectrum`` and ``source`` say which
    band it holds. The phases are uniform in
    ``[0, 2 pi)`` from ``numpy.random.default_rng(seed)``, so a seed gives the same road
    every time. The amplitudes do not depend on the seed: the profile's variance is
    ``sum_k Gd(n_k) dn`` and its periodogram is ``Gd(n_k)`` exactly for every seed (the
    profile is periodic over ``N spacing``); only the phases, and so the peaks, change.

    Parameters
    ----------
    spectrum : RoadSpectrum
        The target PSD ``Gd(n)``.
    length : float, optional
        Profile length [m] (rounded down to a whole number of ``spacing``), 500 m.
    spacing : float, optional
        Distance between points [m]; by default :func:`band_spacing` of the band's top.
    seed : int, optional
        Seed of the random phases (>= 0).
    speed_kmh : float, optional
        Vehicle speed [km/h].
    fade_in : float, optional
        See :class:`RoadProfile`.
    source : str, optional
        The profile's label; by default the spectrum and the seed.

    Returns
    -------
    RoadProfile
        With ``spectrum`` set to the spectrum it holds (the band cut at the Nyquist
        frequency).

    Examples
    --------
    >>> road = synthesise_road(RoadSpectrum(1e-5, waviness=1.0), seed=3)
    >>> road.spacing, road.spectrum.band  # ISO 8608's whole band
    (0.05, (0.011, 2.83))
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     coarse = synthesise_road(RoadSpectrum(1e-5, waviness=1.0), spacing=0.3)
    >>> coarse.spectrum.band, caught[0].category.__name__  # cut at 0.3 m's Nyquist
    ((0.011, 1.6666666666666667), 'RoadBandWarning')
    >>> a, b = road, synthesise_road(RoadSpectrum(1e-5, waviness=1.0), seed=4)
    >>> bool(np.isclose(a.rms_elevation, b.rms_elevation, rtol=1e-12))  # level: seed-free
    True
    """
    if source is not None and not isinstance(source, str):
        raise ValidationError(f"source must be a string; got {source!r}")

    def label(held: RoadSpectrum, seed: int, dx: float) -> str:
        return source or f"synthesised road, seed {seed}"

    return _synthesise(spectrum, length, spacing, seed, speed_kmh, fade_in, label)


def _synthesise(
    spectrum: RoadSpectrum,
    length: float,
    spacing: float | None,
    seed: int,
    speed_kmh: float,
    fade_in: float,
    label: Callable[[RoadSpectrum, int, float], str],
    *,
    what: str = "a synthesised road",
) -> RoadProfile:
    """:func:`synthesise_road`; ``label(held spectrum, seed, spacing)`` names its source.

    ``spacing`` None: :func:`band_spacing`. A given spacing that puts the band's top above
    :data:`BAND_TOP_WARN` of the Nyquist frequency warns (``what`` names the road), except
    for the presets, whose 0.3 m spacing is their definition (they pass ``what=""``).
    """
    if not isinstance(spectrum, RoadSpectrum):
        raise ValidationError(f"spectrum must be a RoadSpectrum; got {spectrum!r}")
    L = positive("length", length, "m", high=1e6)
    if spacing is None:  # the whole band, and at least MIN_POINTS points
        spacing = min(band_spacing(spectrum.band[1]), L / (MIN_POINTS - 1))
    dx = positive("spacing", spacing, "m", high=L / (MIN_POINTS - 1))
    if what and spectrum.band[1] > BAND_TOP_WARN * 0.5 / dx:
        _warn_band(what, spectrum.band, dx)
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ValidationError(f"seed must be an integer >= 0; got {seed!r}")
    n_lo, n_hi = spectrum.band
    points = math.floor(L / dx + 1e-9) + 1
    dn = 1.0 / (points * dx)
    k = np.arange(1, (points - 1) // 2 + 1)  # strictly below the Nyquist frequency
    n = k * dn
    keep = (n >= n_lo) & (n <= n_hi)
    if not np.any(keep):
        raise ValidationError(
            f"no spatial frequency of a {points * dx:g} m profile at {dx:g} m spacing lies in "
            f"the band {n_lo:g}-{n_hi:g} cycle/m (resolution {dn:g}, Nyquist {0.5 / dx:g})"
        )
    amp = np.sqrt(2.0 * spectrum.density(n[keep]) * dn)
    phase = np.random.default_rng(int(seed)).uniform(0.0, 2.0 * math.pi, size=int(keep.sum()))
    coefficients = np.zeros(points // 2 + 1, dtype=complex)
    coefficients[k[keep]] = 0.5 * points * amp * np.exp(1j * phase)
    # the inverse real FFT is the sum of the cosines at x_j = j dx
    elevation = np.asarray(np.fft.irfft(coefficients, n=points), dtype=np.float64)
    distance = np.asarray(dx * np.arange(points), dtype=np.float64)
    held = replace(spectrum, band=(n_lo, min(n_hi, 0.5 / dx)))
    return RoadProfile(
        distance,
        elevation,
        speed_kmh,
        fade_in=fade_in,
        source=label(held, int(seed), dx),
        spectrum=held,
    )


def _warn_band(what: str, band: tuple[float, float], dx: float) -> None:
    """:class:`RoadBandWarning`: ``dx`` cuts or filters the top of ``band``."""
    import warnings

    lo, hi = band
    nyquist = 0.5 / dx
    if hi > nyquist:
        effect = (
            f"cuts the band {lo:g}-{hi:g} cycle/m at its Nyquist frequency {nyquist:.4g} "
            f"cycle/m: the road holds {lo:g}-{nyquist:.4g} cycle/m only"
        )
    else:
        effect = (
            f"puts the top of the band {lo:g}-{hi:g} cycle/m at {hi / nyquist:.0%} of its "
            f"Nyquist frequency {nyquist:.4g} cycle/m, where the spline the wheel rides "
            "loses amplitude"
        )
    warnings.warn(
        f"{what} at {dx:g} m spacing {effect} (an ISO class C road at 0.3 m spacing gives "
        "a quarter car's rms tire force 7.5 % low at 50 km/h). Leave the spacing out "
        f"({band_spacing(hi):g} m for this band) or give at most "
        f"{BAND_TOP_WARN * 0.5 / hi:.3g} m, or narrow the band",
        RoadBandWarning,
        stacklevel=4,
    )


# -- ISO 8608 synthesis ----------------------------------------------------------------
def iso8608_psd(road_class: str, spatial_frequency: npt.ArrayLike) -> FloatArray:
    """ISO 8608 displacement PSD ``Gd(n) = Gd(n0) (n/n0)^-2`` [m^3] of a class (A-H).

    Examples
    --------
    >>> iso8608_psd("C", [0.1, 1.0])
    array([2.56e-04, 2.56e-06])
    """
    gd0 = ISO8608_CLASSES[_road_class(road_class)]
    n = check_finite("spatial_frequency", spatial_frequency)
    if np.any(n <= 0):
        raise ValidationError("spatial_frequency must be > 0 cycle/m")
    return np.asarray(gd0 * (n / ISO8608_N0) ** -2.0, dtype=float)


def _road_class(road_class: object) -> str:
    if not isinstance(road_class, str):
        raise ValidationError(f"road_class must be a letter A-H; got {road_class!r}")
    key = road_class.strip().upper()
    if key not in ISO8608_CLASSES:
        raise unknown_name("ISO 8608 road class", road_class, ISO8608_CLASSES)
    return key


def iso8608(
    road_class: str,
    length: float = 500.0,
    spacing: float | None = None,
    seed: int = 0,
    speed_kmh: float = REFERENCE_SPEED_KMH,
    *,
    band: tuple[float, float] = ISO8608_BAND,
    fade_in: float = 0.0,
) -> RoadProfile:
    """Synthesise a road of an ISO 8608 class (:func:`synthesise_road` with ``w = 2``).

    ``Gd(n) = Gd(n0) (n/n0)^-2`` with ``n0 = 0.1`` cycle/m and the class's geometric-mean
    ``Gd(n0)``, synthesised as a sum of cosines with random phases from ``seed`` (see
    :func:`synthesise_road`). The profile is periodic over its length; its PSD matches
    ``Gd(n)`` in the band. The default spacing, 0.05 m for ISO's band
    (:func:`band_spacing`), holds the whole band: a quarter car's rms responses match
    the closed form of a white-velocity road within 0.1 %. A coarser spacing that cuts
    or filters the top of the band warns (:class:`RoadBandWarning`); the profile's
    ``source`` states the band it holds.

    Parameters
    ----------
    road_class : str
        ISO 8608 class, ``"A"`` (very good) to ``"H"`` (very poor).
    length : float, optional
        Profile length [m] (rounded down to a whole number of ``spacing``), 500 m.
    spacing : float, optional
        Distance between points [m]; by default :func:`band_spacing` of the band's top
        (0.05 m for ISO's 2.83 cycle/m).
    seed : int, optional
        Seed of the random phases.
    speed_kmh : float, optional
        Vehicle speed [km/h].
    band : (float, float), optional
        Spatial-frequency band [cycle/m]; ISO 8608's 0.011-2.83 cycle/m by default.
    fade_in : float, optional
        See :class:`RoadProfile`.

    Examples
    --------
    >>> road = iso8608("C", seed=7)
    >>> road.distance.size, road.spacing, road.length
    (10001, 0.05, 500.0)
    >>> road.source
    'ISO 8608 class C, seed 7, band 0.011-2.83 cycle/m at 0.05 m spacing'
    >>> bool(np.array_equal(road.elevation, iso8608("C", seed=7).elevation))
    True
    >>> road.spectrum.level, road.spectrum.waviness
    (0.000256, 2.0)
    """
    key = _road_class(road_class)
    spectrum = RoadSpectrum(ISO8608_CLASSES[key], 2.0, band)

    def label(held: RoadSpectrum, seed: int, dx: float) -> str:
        lo, hi = held.band
        cut = f" (cut from {band[1]:g} by the spacing)" if hi < spectrum.band[1] else ""
        return f"ISO 8608 class {key}, seed {seed}, band {lo:g}-{hi:.4g} cycle/m{cut} at {dx:g} m spacing"

    return _synthesise(
        spectrum, length, spacing, seed, speed_kmh, fade_in, label, what=f"ISO 8608 class {key}"
    )


# -- presets -------------------------------------------------------------------------------
#: Waviness of the preset roads: the dissertation's DLC at 100 km/h is about 1.03 times
#: that at 50 km/h (0.142/0.138, 0.114/0.113), which an ``n^-1`` road gives (a temporal
#: PSD ``G(f) = Gd(f/V)/V`` independent of V); ISO's ``n^-2`` would halve it (model reference,
#: section 8(c)).
PRESET_WAVINESS = 1.0
#: The dissertation filtered its road data to 0-2 cycle/m (section 3.5.2); ISO 8608's
#: lower band limit 0.011 cycle/m keeps the synthesis finite. At 0.3 m spacing the
#: Nyquist frequency (1.67 cycle/m) lies inside that band and is where the content stops.
PRESET_BAND = (ISO8608_BAND[0], 2.0)
#: The dissertation's profiles: about 500 m at 0.3 m intervals (section 3.5.2)
PRESET_LENGTH = 500.0
PRESET_SPACING = 0.3


@dataclass(frozen=True)
class PresetRoad:
    """Recipe of a preset road: a power-law PSD, its band, a default seed, the geometry.

    The level ``Gd(n0)`` defines the road; the seed only draws the phases, so every seed
    gives a road of the same PSD and rms elevation (its peak varies a little).

    Attributes
    ----------
    name : str
        ``"smooth"``, ``"medium-rough"`` or ``"rough"``.
    level : float
        ``Gd(n0)`` [m^3] at ``n0 = 0.1`` cycle/m.
    seed : int
        Default seed of the random phases (every call gives the same road).
    description : str
        What the preset stands for.
    waviness : float
        Exponent ``w`` of ``Gd(n) = Gd(n0) (n/n0)^-w``: 1.
    band : (float, float)
        Spatial-frequency band [cycle/m]: 0.011-2.
    length, spacing : float
        Profile length and point spacing [m]: 500 and 0.3.

    Examples
    --------
    >>> p = PRESET_ROADS["rough"]
    >>> p.spectrum.label()
    'Gd(n0) 2.7e-05 m^3, n^-1, 0.011-2 cycle/m'
    """

    name: str
    level: float
    seed: int
    description: str
    waviness: float = PRESET_WAVINESS
    band: tuple[float, float] = PRESET_BAND
    length: float = PRESET_LENGTH
    spacing: float = PRESET_SPACING

    @property
    def spectrum(self) -> RoadSpectrum:
        """The target PSD (:class:`RoadSpectrum`)."""
        return RoadSpectrum(self.level, self.waviness, self.band)

    def profile(
        self,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        seed: int | None = None,
        fade_in: float = 0.0,
    ) -> RoadProfile:
        """The preset's road (see :func:`preset_road`)."""
        s = self.seed if seed is None else seed

        reference = PRESET_ROADS.get(self.name)
        own = reference is not None and reference.spectrum == self.spectrum
        shape = "" if own else f", spectrum {self.spectrum.label()}"

        def label(held: RoadSpectrum, seed: int, dx: float) -> str:
            return (
                f"preset {self.name!r} (stand-in for the dissertation's road), seed {seed}{shape}"
            )

        return _synthesise(
            self.spectrum, self.length, self.spacing, s, speed_kmh, fade_in, label, what=""
        )

    @property
    def rms_elevation(self) -> float:
        """RMS elevation [m] of the preset road (the same for every seed)."""
        return self.profile().rms_elevation

    @property
    def peak_elevation(self) -> float:
        """Largest ``|elevation|`` [m] of the road drawn with the default seed."""
        return self.profile().peak_elevation

    def describe(self) -> dict[str, Any]:
        """Plain data: the recipe, plus the realised rms and peak elevation [m]."""
        road = self.profile()
        return {
            "name": self.name,
            "level": self.level,
            "waviness": self.waviness,
            "band": list(self.band),
            "seed": self.seed,
            "length": road.length,
            "spacing": self.spacing,
            "rms_elevation": road.rms_elevation,
            "peak_elevation": road.peak_elevation,
            "description": self.description,
        }


#: The presets, by name. ``Gd(n0)`` of "rough" and "medium-rough" tuned against the
#: dissertation's DLCs (model reference, section 8; docs/excitations-and-measures.md, "Presets"):
#: rough 50 km/h, 30 s, cycle-rms estimator: passive 0.1 A 0.114 (0.111), passive 0 A
#: 0.137 (0.139), skyhook ACM 0.136 (0.138), inverse hi-lo 0.115 (0.113), sliding mode
#: 0.117 (0.112); medium-rough: skyhook 0.045 (0.045), inverse hi-lo 0.055 (0.056),
#: sliding mode 0.056 (0.054). The model reference's starting values were 3.9e-5 and 9.7e-6 m^3
#: (DLCs 1.20-1.25x and 1.3-1.6x too high). "smooth" has no DLC to tune against: it keeps
#: the model reference's 2.8e-6 m^3, whose road peaks at 4.0 mm like the dissertation's.
PRESET_ROADS: dict[str, PresetRoad] = {
    p.name: p
    for p in (
        PresetRoad("smooth", 2.8e-6, 86081, "stand-in for the smooth Canadian road"),
        PresetRoad("medium-rough", 4.2e-6, 86082, "stand-in for the medium-rough Canadian road"),
        PresetRoad("rough", 2.7e-5, 86083, "stand-in for the rough Canadian road"),
    )
}  # fmt: skip
#: The presets with the spectra identified from the dissertation's road numbers (its DLCs
#: at 50 and 100 km/h per controller, the rough/medium-rough PSD comparisons, the peak
#: elevations; ``tools/identify_roads.py``, docs/errata.md "Road spectra identified"): the
#: ``spectrum = "identified"`` option of a road, a stated reading of the findings
#: scorecard. The model reference fixes the presets' n^-1 shape (section 8(c)), so these
#: are not the default.
#: ``smooth`` has no road number to fit and keeps the reference's.
PRESET_IDENTIFIED: dict[str, PresetRoad] = {
    "smooth": PRESET_ROADS["smooth"],
    "medium-rough": replace(
        PRESET_ROADS["medium-rough"], level=4.06e-6, waviness=0.5, band=(0.05, 0.7)
    ),
    "rough": replace(PRESET_ROADS["rough"], level=1.07e-5, waviness=0.5, band=(0.011, 1.4)),
}


def preset_road(
    name: str,
    speed_kmh: float = REFERENCE_SPEED_KMH,
    *,
    seed: int | None = None,
    fade_in: float = 0.0,
    spectrum: str = "reference",
) -> RoadProfile:
    """One of the three preset roads, ``"smooth"``, ``"medium-rough"`` or ``"rough"``.

    **Stand-ins**: the dissertation's measured Canadian road profiles (section 3.5.2) are
    not available. Each preset is defined by its PSD, ``Gd(n) = Gd(n0) (n/0.1)^-1`` over
    0.011-2 cycle/m (model reference, section 8(c)), and synthesised by :func:`synthesise_road` as a
    500 m profile at 0.3 m spacing (content up to the 1.67 cycle/m Nyquist frequency).
    ``Gd(n0)`` is 2.8e-6, 4.2e-6 and 2.7e-5 m^3 (rough and medium-rough tuned against the
    dissertation's DLCs, see :data:`PRESET_ROADS`); rms elevation 1.19, 1.45 and 3.68 mm
    for any seed, peak 4.0, 5.1 and 15.7 mm with the default seeds (the dissertation's
    peaks: about 4, 7.5 and 15 mm).

    Parameters
    ----------
    name : str
        The preset.
    speed_kmh : float, optional
        Vehicle speed [km/h], 50 by default.
    seed : int, optional
        Seed of the random phases; the preset's own fixed seed by default (every call
        then returns the same profile bit for bit). Another seed gives another road of
        the same PSD level.
    fade_in : float, optional
        See :class:`RoadProfile`.
    spectrum : {"reference", "identified"}, optional
        The model reference's spectrum (:data:`PRESET_ROADS`, the default) or the one
        identified from the dissertation's road numbers (:data:`PRESET_IDENTIFIED`).

    Examples
    --------
    >>> road = preset_road("rough")
    >>> road.distance.size, road.spacing, road.spectrum.level
    (1667, 0.3, 2.7e-05)
    >>> round(road.rms_elevation * 1e3, 2), round(road.peak_elevation * 1e3, 1)  # mm
    (3.68, 15.7)
    >>> round(preset_road("rough", seed=1).rms_elevation * 1e3, 2)  # same level
    3.68
    >>> preset_road("medium-rough", speed_kmh=100.0).duration
    17.9928
    """
    if not isinstance(name, str) or name not in PRESET_ROADS:
        raise unknown_name("preset road", str(name), PRESET_ROADS)
    return _preset(name, spectrum).profile(speed_kmh, seed=seed, fade_in=fade_in)


def _preset(name: str, spectrum: object) -> PresetRoad:
    """The preset ``name`` with the spectrum of :data:`PRESET_SPECTRA` ``spectrum``."""
    if spectrum == "reference":
        return PRESET_ROADS[name]
    if spectrum == "identified":
        return PRESET_IDENTIFIED[name]
    raise ValidationError(
        f"preset spectrum {spectrum!r} is not valid; valid: {', '.join(PRESET_SPECTRA)}"
    )


# -- scenario options ----------------------------------------------------------------------
def _road_from_options(options: Mapping[str, Any], base_dir: str | Path | None) -> RoadProfile:
    """:meth:`RoadProfile.from_options`."""
    speed = options.get("speed", REFERENCE_SPEED_KMH)
    fade_in = options.get("fade_in", 0.0)
    has_profile = "profile" in options
    has_iso = "iso_class" in options
    if has_profile == has_iso:
        raise ValidationError(
            "excitation 'road' needs exactly one of 'profile' (a preset name: "
            f"{', '.join(PRESET_ROADS)}; or a CSV file path) and 'iso_class' (ISO 8608 A-H)"
        )
    iso_only = [k for k in ("length", "spacing") if k in options]
    csv_only = [k for k in ("distance_unit", "elevation_unit") if k in options]
    preset_only = [k for k in ("spectrum", "level", "waviness", "band") if k in options]
    if has_profile:
        if iso_only:
            raise ValidationError(
                f"excitation 'road': {', '.join(map(repr, iso_only))} only applies with 'iso_class'"
            )
        profile = options["profile"]
        if not isinstance(profile, str | Path):
            raise ValidationError(
                f"road profile must be a preset name or a file path; got {profile!r}"
            )
        if isinstance(profile, str) and profile in PRESET_ROADS:
            if csv_only:
                raise ValidationError(
                    f"excitation 'road': {', '.join(map(repr, csv_only))} only applies to a CSV file"
                )
            preset = _preset(profile, options.get("spectrum", "reference"))
            changes: dict[str, Any] = {k: options[k] for k in ("level", "waviness") if k in options}
            if "band" in options:
                changes["band"] = _band(options["band"])
            if changes:
                preset = replace(preset, **changes)
                preset.spectrum  # noqa: B018 - checks the changed spectrum at once
            road = preset.profile(speed, seed=options.get("seed"), fade_in=fade_in)
        else:
            if preset_only:
                raise ValidationError(
                    f"excitation 'road': {', '.join(map(repr, preset_only))} only applies to "
                    f"a preset profile ({', '.join(PRESET_ROADS)})"
                )
            if "seed" in options:
                raise ValidationError(
                    "excitation 'road': 'seed' only applies with 'iso_class' or a preset profile"
                )
            path = Path(profile)
            if base_dir is not None and not path.is_absolute():
                path = Path(base_dir) / path
            if not path.exists() and path.suffix == "" and len(path.parts) == 1:
                # a bare word: most likely a misspelt preset name
                raise ValidationError(
                    f"unknown road profile {str(profile)!r}: not a preset and no such file."
                    f"{did_you_mean(str(profile), PRESET_ROADS)} Presets: {', '.join(PRESET_ROADS)}."
                )
            road = RoadProfile.from_csv(
                path,
                speed,
                distance_unit=options.get("distance_unit"),
                elevation_unit=options.get("elevation_unit"),
                fade_in=fade_in,
            )
    else:
        if csv_only or preset_only:
            what = "a CSV file" if csv_only else f"a preset profile ({', '.join(PRESET_ROADS)})"
            raise ValidationError(
                f"excitation 'road': {', '.join(map(repr, csv_only or preset_only))} only "
                f"applies to {what}"
            )
        iso_class = options["iso_class"]
        if not isinstance(iso_class, str) or iso_class.strip().upper() not in ISO8608_CLASSES:
            error = unknown_name("ISO 8608 road class", str(iso_class), ISO8608_CLASSES)
            raise ValidationError(f"iso_class: {error}")
        road = iso8608(
            iso_class,
            length=options.get("length", 500.0),
            spacing=options.get("spacing"),
            seed=options.get("seed", 0),
            speed_kmh=speed,
            fade_in=fade_in,
        )
    scale = positive("scale", options.get("scale", 1.0), "", high=1e3)
    return road if scale == 1.0 else road.scaled(scale)
