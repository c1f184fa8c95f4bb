"""Units and conventions of a study data set (CF-style ``units`` and ``long_name``).

Measures take their units from :data:`mrsuspension.engine.result.MEASURE_UNITS`; a
``[grid]`` coordinate from :data:`FIELD_UNITS` (the SI unit of the scenario field it
varies). Case coordinates (labels) and text fields (``damper.model``) carry no unit.

:func:`conventional` gives a data set the names xarray and netCDF users expect: a
dimension per grid field named without dots (``controller_gain``, its dotted field in
the coordinate's ``field`` attribute; :func:`dimension_name`), a vehicle's per-corner
measures along a ``corner`` dimension (``DLC`` over ``(..., "corner")`` instead of
``DLC.front_left``, ``DLC.front_right``, ...), and a ``long_name`` on every measure.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["FIELD_UNITS", "add_units", "conventional", "csv_headers", "dimension_name"]

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
    from mrsuspension.engine.vehicle_result import SEAT_MEASURES
    from mrsuspension.scenario import BODY_MEASURES

    for name in ds.data_vars:
        key = str(name)
        # a vehicle's body measure, or a corner's "<measure>.<corner>"
        unit = MEASURE_UNITS.get(key, MEASURE_UNITS.get(key.split(".", 1)[0]))
        if key in BODY_MEASURES:
            unit = BODY_MEASURES[key][1]
        if key in SEAT_MEASURES:
            unit = SEAT_MEASURES[key][0]
        if unit is not None:
            ds[name].attrs["units"] = unit
    for name in ds.coords:
        field = str(ds[name].attrs.get("field", name))
        parts = field.split(".")
        if len(parts) == 3:  # a per-corner field: damper.front_left.damping
            field = f"{parts[0]}.{parts[2]}"
        unit = MEASURE_UNITS.get(field) or FIELD_UNITS.get(field)
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


def dimension_name(field: str) -> str:
    """The data-set dimension of a study field: its dotted name with ``_`` for ``.``.

    Examples
    --------
    >>> dimension_name("controller.gain"), dimension_name("damper.front_left.damping")
    ('controller_gain', 'damper_front_left_damping')
    >>> dimension_name("policy")  # a case table's name: itself
    'policy'
    """
    return field.replace(".", "_")


def _measure_name(measure: str) -> str:
    """The ``long_name`` of a measure (a body RMS: of its signal)."""
    from mrsuspension.engine.result import MEASURE_NAMES
    from mrsuspension.engine.vehicle_result import BODY_MEASURES, BODY_SIGNALS, SEAT_MEASURES

    if measure in BODY_MEASURES:
        return f"rms {BODY_SIGNALS[BODY_MEASURES[measure][0]][1]}"
    if measure in SEAT_MEASURES:
        return SEAT_MEASURES[measure][1]
    return MEASURE_NAMES.get(measure, measure)


def conventional(ds: xr.Dataset) -> xr.Dataset:
    """A study data set with valid dimension names, a ``corner`` dimension and long names.

    * every per-corner measure ``"<measure>.<corner>"`` becomes one variable
      ``<measure>`` over ``(..., "corner")`` (a corner it was not kept for: NaN);
    * every dotted dimension or coordinate (``controller.gain``) is renamed by
      :func:`dimension_name` (``controller_gain``), with its field in the ``field``
      attribute and as ``long_name``;
    * every measure gets a ``long_name``.

    Idempotent: a data set already in this form (e.g. read back from the cache) is
    returned as it is; attributes (``units``, the study) are kept.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = add_units(xr.Dataset(
    ...     {"heave_ddot_rms": ("controller.gain", [1.0, 0.9]),
    ...      "DLC.front": ("controller.gain", [0.1, 0.2]),
    ...      "DLC.rear": ("controller.gain", [0.3, 0.4])},
    ...     coords={"controller.gain": [1.0, 2.0]}))
    >>> out = conventional(ds)
    >>> out["DLC"].dims, out["DLC"].sel(corner="rear").values.tolist()
    (('controller_gain', 'corner'), [0.3, 0.4])
    >>> out["controller_gain"].attrs["field"], out["DLC"].attrs["units"]
    ('controller.gain', '-')
    >>> out["heave_ddot_rms"].attrs["long_name"]
    'rms heave acceleration'
    >>> conventional(out).identical(out)
    True
    """
    import xarray as xr

    from mrsuspension.excitation import FULL_CAR_CORNERS, HALF_CAR_CORNERS

    known = (*FULL_CAR_CORNERS, *HALF_CAR_CORNERS)
    ds = ds.copy()  # the caller's attributes stay as they are
    per_corner: dict[str, dict[str, str]] = {}  # measure -> corner -> variable
    for name in ds.data_vars:
        base, dot, corner = str(name).rpartition(".")
        if dot and corner in known:
            per_corner.setdefault(base, {})[corner] = str(name)
    out = ds
    if per_corner:
        corners = list(dict.fromkeys(c for by in per_corner.values() for c in by))
        if "corner" in ds.dims:  # a data set half-converted: extend its corners
            corners = list(dict.fromkeys([*map(str, ds["corner"].values), *corners]))
        stacked = {}
        for base, by in per_corner.items():
            first = ds[next(iter(by.values()))]
            parts = [ds[by[c]] if c in by else xr.full_like(first, float("nan")) for c in corners]
            var = xr.concat(parts, dim="corner", coords="minimal", compat="override")
            var = var.transpose(*first.dims, "corner")
            var.attrs = dict(first.attrs)
            stacked[base] = var
        drop = [v for by in per_corner.values() for v in by.values()]
        out = ds.drop_vars(drop).assign_coords(corner=("corner", corners))
        out = out.assign(stacked)
        out["corner"].attrs["long_name"] = "wheel corner"
    renames = {str(n): dimension_name(str(n)) for n in out.variables if "." in str(n)}
    if renames:
        fields = {new: old for old, new in renames.items()}
        out = out.rename(renames)
        for new, old in fields.items():
            out[new].attrs.setdefault("field", old)
            out[new].attrs.setdefault("long_name", old)
    for name in out.data_vars:
        out[name].attrs.setdefault("long_name", _measure_name(str(name)))
    for name in ("frequency", "amplitude"):
        if name in out.coords:
            out[name].attrs.setdefault("long_name", _measure_name(name))
    return out
