"""Road excitations ``z_r(t)`` [m], positive up (model reference, section 8).

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

from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError, did_you_mean, unknown_name
from mrsuspension.excitation.base import Configurable, Excitation, FloatArray, Option
from mrsuspension.excitation.deterministic import (
    DEFAULT_SWEEP_POINTS,
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
    PRESET_IDENTIFIED,
    PRESET_ROADS,
    PRESET_SPECTRA,
    PRESET_WAVINESS,
    PresetRoad,
    RoadBandWarning,
    RoadProfile,
    RoadSpectrum,
    SpatialPsd,
    band_spacing,
    iso8608,
    iso8608_psd,
    preset_road,
    synthesise_road,
)
from mrsuspension.excitation.wheels import (
    CORNER_LAYOUTS,
    FULL_CAR_CORNERS,
    HALF_CAR_CORNERS,
    SIDES,
    Pothole,
    WheelRoads,
    isotropic_coherence,
)

__all__ = [
    "CORNER_LAYOUTS",
    "DEFAULT_SWEEP_POINTS",
    "EXCITATIONS",
    "EXCITATION_OPTIONS",
    "FULL_CAR_CORNERS",
    "HALF_CAR_CORNERS",
    "HIL_FREQUENCIES",
    "HIL_TRANSITION_FREQUENCY",
    "ISO8608_BAND",
    "ISO8608_CLASSES",
    "ISO8608_N0",
    "OMEGA0_REFERENCE",
    "PRESET_BAND",
    "PRESET_IDENTIFIED",
    "PRESET_ROADS",
    "PRESET_SPECTRA",
    "PRESET_WAVINESS",
    "REFERENCE_SPEED_KMH",
    "SIDES",
    "TRANSITION_FREQUENCY",
    "Configurable",
    "Excitation",
    "FloatArray",
    "Harmonic",
    "Option",
    "Pothole",
    "PresetRoad",
    "RoadBandWarning",
    "RoadProfile",
    "RoadSpectrum",
    "RoundedPulse",
    "SpatialPsd",
    "SteppedSweep",
    "WheelRoads",
    "band_spacing",
    "iso8608",
    "iso8608_psd",
    "isotropic_coherence",
    "log_frequencies",
    "make_excitation",
    "preset_road",
    "synthesise_road",
    "two_stage_amplitude",
]

#: The registered excitation kinds: each class declares its ``name``, ``options`` and
#: ``measures_kind`` (:class:`Configurable`); everything below is derived from them. A new
#: kind is a class in its own module plus a line here.
_KINDS: tuple[type[Excitation] | type[SteppedSweep], ...] = (
    Harmonic,
    SteppedSweep,
    RoundedPulse,
    RoadProfile,
)

#: Excitation kinds by registry name (``[excitation] kind = ...`` in a scenario).
EXCITATIONS: dict[str, type[Excitation] | type[SteppedSweep]] = {c.name: c for c in _KINDS}

#: The options :func:`make_excitation` accepts for each kind, with what they mean.
EXCITATION_OPTIONS: dict[str, dict[str, str]] = {
    kind: {o.name: o.doc for o in cls.options} for kind, cls in EXCITATIONS.items()
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
    for opt in EXCITATIONS[kind].options:
        if opt.required and opt.name not in options:
            raise ValidationError(f"excitation {kind!r} needs {opt.name!r}: {opt.doc}")
    return EXCITATIONS[kind].from_options(options, base_dir=base_dir)
