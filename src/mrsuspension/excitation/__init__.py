"""Road excitations ``z_r(t)`` [m], positive up (MODEL_SPEC section 8).

==============  ===============================================================  ==========
kind            class                                                            equation
==============  ===============================================================  ==========
``"harmonic"``  :class:`Harmonic`, ``a sin(2 pi f t)``                            (3.36)
``"swept"``     :class:`SteppedSweep`, one :class:`Harmonic` per frequency at      (3.37)
                the two-stage amplitude :func:`two_stage_amplitude` (erratum 2)
``"pulse"``     :class:`RoundedPulse`, a rounded bump of height ``a``             (3.38)
``"road"``      :class:`RoadProfile`: a CSV file, :func:`iso8608` synthesis or a
                :func:`preset_road` (``"smooth"``, ``"medium-rough"``, ``"rough"``;
                each defined by a :class:`RoadSpectrum`, ``Gd(n0) (n/0.1)^-1``)
==============  ===============================================================  ==========

Every :class:`Excitation` gives ``displacement(t)``, ``velocity(t)`` and
``acceleration(t)`` (vectorised, exact), a default ``duration``, ``measure_window()``
and ``describe()``. Scenario files build them by name with :func:`make_excitation`.

Examples
--------
>>> from mrsuspension.excitation import make_excitation
>>> z = make_excitation("harmonic", frequency=1.5, amplitude=0.025)
>>> float(z.acceleration(0.5))  # -a (2 pi f)^2 sin(1.5 pi)
2.2206609...
>>> make_excitation("road", profile="rough", speed=100.0, scale=0.5).spectrum.level
6.75e-06
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError, did_you_mean, unknown_name
from mrsuspension.excitation.base import Excitation, FloatArray, positive
from mrsuspension.excitation.deterministic import (
    HIL_FREQUENCIES,
    HIL_TRANSITION_FREQUENCY,
    OMEGA0_REFERENCE,
    REFERENCE_SPEED_KMH,
    TRANSITION_FREQUENCY,
    Harmonic,
    RoundedPulse,
    SteppedSweep,
    log_frequencies,
    two_stage_amplitude,
)
from mrsuspension.excitation.road import (
    ISO8608_BAND,
    ISO8608_CLASSES,
    ISO8608_N0,
    PRESET_BAND,
    PRESET_ROADS,
    PRESET_WAVINESS,
    PresetRoad,
    RoadProfile,
    RoadSpectrum,
    SpatialPsd,
    iso8608,
    iso8608_psd,
    preset_road,
    synthesise_road,
)

__all__ = [
    "DEFAULT_SWEEP_POINTS",
    "EXCITATIONS",
    "EXCITATION_OPTIONS",
    "HIL_FREQUENCIES",
    "HIL_TRANSITION_FREQUENCY",
    "ISO8608_BAND",
    "ISO8608_CLASSES",
    "ISO8608_N0",
    "OMEGA0_REFERENCE",
    "PRESET_BAND",
    "PRESET_ROADS",
    "PRESET_WAVINESS",
    "REFERENCE_SPEED_KMH",
    "TRANSITION_FREQUENCY",
    "Excitation",
    "FloatArray",
    "Harmonic",
    "PresetRoad",
    "RoadProfile",
    "RoadSpectrum",
    "RoundedPulse",
    "SpatialPsd",
    "SteppedSweep",
    "iso8608",
    "iso8608_psd",
    "log_frequencies",
    "make_excitation",
    "preset_road",
    "synthesise_road",
    "two_stage_amplitude",
]

#: Excitation kinds by registry name (``[excitation] kind = ...`` in a scenario).
EXCITATIONS: dict[str, type[Excitation] | type[SteppedSweep]] = {
    "harmonic": Harmonic,
    "swept": SteppedSweep,
    "pulse": RoundedPulse,
    "road": RoadProfile,
}

#: number of log-spaced frequencies (0.5-15 Hz) of a sweep given without ``frequencies``
DEFAULT_SWEEP_POINTS = 30

#: The options :func:`make_excitation` accepts for each kind, with what they mean.
EXCITATION_OPTIONS: dict[str, dict[str, str]] = {
    "harmonic": {
        "frequency": "excitation frequency [Hz] (required)",
        "amplitude": "displacement amplitude [m] (required)",
    },
    "swept": {
        "amplitude": "low-frequency displacement amplitude a [m] (required)",
        "transition_frequency": "f_T [Hz], 2.1 by default (2.0 on the HiL rig)",
        "frequencies": f"list of frequencies [Hz]; {DEFAULT_SWEEP_POINTS} log-spaced in 0.5-15 Hz by default",
    },
    "pulse": {
        "amplitude": "bump height a [m] (required)",
        "severity": "severity mu, e.g. 1, 2, 3 (required)",
        "speed": "vehicle speed [km/h], 50 by default; sets w0 = 10.4 rad/s x speed/50",
        "omega0": "fundamental frequency w0 [rad/s]; overrides the speed scaling",
        "delay": "time before the pulse [s], 0.5 by default",
    },
    "road": {
        "profile": "preset name (smooth, medium-rough, rough) or a CSV file path",
        "iso_class": "ISO 8608 class A-H (instead of profile)",
        "seed": "random-phase seed of an ISO 8608 class (0 by default) or a preset (its own "
        "fixed seed by default; any seed gives the same PSD level)",
        "length": "ISO 8608 profile length [m], 500 by default",
        "spacing": "ISO 8608 point spacing [m], 0.3 by default",
        "speed": "vehicle speed [km/h], 50 by default",
        "scale": "elevation scale factor, 1 by default (HiL used 0.5 on the rough road)",
        "fade_in": "length [m] over which the profile fades in from zero, 0 by default",
        "distance_unit": "unit of the CSV distance column, m or mm",
        "elevation_unit": "unit of the CSV elevation column, m or mm",
    },
}

_REQUIRED = {
    "harmonic": ("frequency", "amplitude"),
    "swept": ("amplitude",),
    "pulse": ("amplitude", "severity"),
    "road": (),
}


def make_excitation(
    kind: str, *, base_dir: str | Path | None = None, **options: Any
) -> Excitation | SteppedSweep:
    """Build an excitation from its kind and scenario options (see :data:`EXCITATION_OPTIONS`).

    Parameters
    ----------
    kind : {"harmonic", "swept", "pulse", "road"}
        Excitation kind.
    base_dir : str or Path, optional
        Directory that a relative road ``profile`` path is taken from (e.g. the
        scenario file's folder); the working directory by default.
    **options
        The kind's options, as in a scenario's ``[excitation]`` table.

    Raises
    ------
    ValidationError
        Unknown kind or option (with a did-you-mean), missing required option, or an
        invalid value.

    Examples
    --------
    >>> make_excitation("pulse", amplitude=0.035, severity=3, speed=100.0).omega
    20.8
    >>> len(make_excitation("swept", amplitude=0.015))
    30
    >>> make_excitation("harmonic", frequncy=1.5, amplitude=0.025)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown option 'frequncy' for excitation 'harmonic'. Did you mean 'frequency'? Valid: amplitude, frequency.
    """
    if not isinstance(kind, str) or kind not in EXCITATIONS:
        raise unknown_name("excitation kind", str(kind), EXCITATIONS)
    valid = EXCITATION_OPTIONS[kind]
    for key in options:
        if key not in valid:
            names = sorted(valid)
            raise ValidationError(
                f"unknown option {key!r} for excitation {kind!r}.{did_you_mean(key, names)} "
                f"Valid: {', '.join(names)}."
            )
    for key in _REQUIRED[kind]:
        if key not in options:
            raise ValidationError(f"excitation {kind!r} needs {key!r}: {valid[key]}")
    if kind == "harmonic":
        return Harmonic(options["frequency"], options["amplitude"])
    if kind == "swept":
        freqs = options.get("frequencies")
        return SteppedSweep(
            tuple(log_frequencies(DEFAULT_SWEEP_POINTS)) if freqs is None else freqs,
            options["amplitude"],
            options.get("transition_frequency", TRANSITION_FREQUENCY),
        )
    if kind == "pulse":
        return RoundedPulse(
            options["amplitude"],
            options["severity"],
            omega0=options.get("omega0"),
            speed_kmh=options.get("speed", REFERENCE_SPEED_KMH),
            delay=options.get("delay", 0.5),
        )
    return _make_road(options, base_dir)


def _make_road(options: Mapping[str, Any], base_dir: str | Path | None) -> RoadProfile:
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
            road = preset_road(profile, speed, seed=options.get("seed"), fade_in=fade_in)
        else:
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
        if csv_only:
            raise ValidationError(
                f"excitation 'road': {', '.join(map(repr, csv_only))} only applies to a CSV file"
            )
        road = iso8608(
            options["iso_class"],
            length=options.get("length", 500.0),
            spacing=options.get("spacing", 0.3),
            seed=options.get("seed", 0),
            speed_kmh=speed,
            fade_in=fade_in,
        )
    scale = positive("scale", options.get("scale", 1.0), "", high=1e3)
    return road if scale == 1.0 else road.scaled(scale)
