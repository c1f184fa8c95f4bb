"""One JSON sanitiser for every JSON file and ``--json`` output the toolkit writes."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from pathlib import PurePath
from typing import Any

__all__ = ["to_jsonable"]


def to_jsonable(value: Any) -> Any:
    """``value`` as strict JSON data (what :func:`json.dumps` accepts with ``allow_nan=False``).

    Mappings become dicts with string keys; lists, tuples and sets become lists; numpy
    scalars and arrays become Python numbers and (nested) lists; NaN and infinities
    become ``None``; paths become strings; dataclass instances become dicts of their
    fields. Anything else is returned unchanged.

    Examples
    --------
    >>> import numpy as np
    >>> from pathlib import Path
    >>> to_jsonable({"T": np.float64(1.5), 2: (np.nan, float("inf")), "p": Path("a/b")})
    {'T': 1.5, '2': [None, None], 'p': 'a/b'}
    >>> to_jsonable(np.array([[1, 2], [3, 4]]))
    [[1, 2], [3, 4]]
    """
    if isinstance(value, float):
        return float(value) if math.isfinite(value) else None  # np.float64 is a float
    if value is None or isinstance(value, str | int | bool):
        return value
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple | set | frozenset):
        return [to_jsonable(v) for v in value]
    if isinstance(value, PurePath):
        return str(value)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: to_jsonable(getattr(value, f.name)) for f in dataclasses.fields(value)}
    tolist = getattr(value, "tolist", None)  # numpy scalars and arrays, without importing numpy
    if callable(tolist) and hasattr(value, "dtype"):
        return to_jsonable(tolist())
    return value
