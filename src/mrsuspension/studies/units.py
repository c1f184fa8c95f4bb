"""Units of a study data set: ``units`` attributes for measures and coordinates.

Measures take theirs from :data:`mrsuspension.engine.result.MEASURE_UNITS`; a ``[grid]``
coordinate from :data:`FIELD_UNITS` (the SI unit of the scenario field it varies). Case
coordinates (labels) and text fields (``damper.model``) carry no unit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["FIELD_UNITS", "add_units", "csv_headers"]

#: SI unit of the numeric scenario fields a study can vary ("-": dimensionless).
FIELD_UNITS: dict[str, str] = {
    "vehicle.sprung_mass": "kg",
    "vehicle.unsprung_mass": "kg",
    "vehicle.suspension_stiffness": "N/m",
    "vehicle.tire_stiffness": "N/m",
    "vehicle.tire_damping": "N s/m",
    "vehicle.skyhook_damping": "N s/m",
    # the half and full car's body fields (vehicle/body.py)
    "vehicle.pitch_inertia": "kg m^2",
    "vehicle.roll_inertia": "kg m^2",
    "vehicle.cg_to_front": "m",
    "vehicle.cg_to_rear": "m",
    "vehicle.front_track": "m",
    "vehicle.rear_track": "m",
    **{
        f"vehicle.{axle}_{name}": unit
        for axle in ("front", "rear")
        for name, unit in (
            ("unsprung_mass", "kg"),
            ("suspension_stiffness", "N/m"),
            ("tire_stiffness", "N/m"),
            ("tire_damping", "N s/m"),
            ("anti_roll_stiffness", "N m/rad"),
        )
    },
    "damper.max_current": "A",
    "damper.force_gain": "-",
    "damper.v_min": "m/s",
    "damper.v_max": "m/s",
    "damper.damping": "N s/m",
    "controller.current": "A",
    "controller.skyhook_damping": "N s/m",
    "controller.passive_damping": "N s/m",
    "controller.damping": "N s/m",
    "controller.c_s": "N s/m",
    "controller.c_0": "N s/m",
    "controller.nominal_mass": "kg",
    "controller.m_s0": "kg",
    "controller.heave": "N s/m",
    "controller.pitch": "N m s/rad",
    "controller.roll": "N m s/rad",
    "controller.low_current": "A",
    "controller.high_current": "A",
    "sensing.tau": "s",
    "sensing.corner": "Hz",
    "sensing.zeta": "-",
    "sensing.fs": "Hz",
    "sensing.stroke_fs": "Hz",
    "sensing.stroke_resolution": "m",
    "sensing.stroke_noise": "m",
    "excitation.frequency": "Hz",
    "excitation.amplitude": "m",
    "excitation.transition_frequency": "Hz",
    "excitation.delay": "s",
    "excitation.length": "m",
    "excitation.spacing": "m",
    "simulation.dt": "s",
    "simulation.duration": "s",
    "simulation.output_rate": "Hz",
}


def add_units(ds: xr.Dataset) -> xr.Dataset:
    """Set the ``units`` attribute of every measure and numeric coordinate it knows.

    Parameters
    ----------
    ds : xarray.Dataset
        A study data set (measures as variables; grid fields, cases and ``frequency``
        as coordinates). Changed in place and returned.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(
    ...     {"T_as": ("vehicle.sprung_mass", [1.2, 1.1])},
    ...     coords={"vehicle.sprung_mass": [300.0, 400.0]},
    ... )
    >>> ds = add_units(ds)
    >>> ds["T_as"].attrs["units"], ds["vehicle.sprung_mass"].attrs["units"]
    ('-', 'kg')
    """
    from mrsuspension.engine.result import MEASURE_UNITS
    from mrsuspension.scenario import BODY_MEASURES

    for name in ds.data_vars:
        key = str(name)
        # a vehicle's body measure, or a corner's "<measure>.<corner>"
        unit = MEASURE_UNITS.get(key, MEASURE_UNITS.get(key.split(".", 1)[0]))
        if key in BODY_MEASURES:
            unit = BODY_MEASURES[key][1]
        if unit is not None:
            ds[name].attrs["units"] = unit
    for name in ds.coords:
        field = str(name)
        parts = field.split(".")
        if len(parts) == 3:  # a per-corner field: damper.front_left.damping
            field = f"{parts[0]}.{parts[2]}"
        unit = MEASURE_UNITS.get(str(name)) or FIELD_UNITS.get(field)
        if unit is not None and ds[name].dtype.kind in "fiu":
            ds[name].attrs["units"] = unit
    return ds


def csv_headers(ds: xr.Dataset) -> dict[str, str]:
    """Column name -> ``"name [unit]"`` for every variable and coordinate of ``ds`` with a
    ``units`` attribute (the CSV writer's headers; text columns keep their names).

    Examples
    --------
    >>> import xarray as xr
    >>> ds = add_units(xr.Dataset(
    ...     {"T_as": ("controller.current", [1.2, 1.1])},
    ...     coords={"controller.current": [0.0, 0.2]},
    ... ))
    >>> csv_headers(ds)
    {'T_as': 'T_as [-]', 'controller.current': 'controller.current [A]'}
    """
    names = [*map(str, ds.data_vars), *map(str, ds.coords)]
    return {n: f"{n} [{ds[n].attrs['units']}]" for n in names if "units" in ds[n].attrs}
