"""User-defined control laws in plain Python: :func:`law`.

A law is a function of the measured signals (:mod:`mrsuspension.control.signals`, by
parameter name) and of its options (parameters with defaults: numbers, or vectors and
matrices given as lists) returning the drive current [A] (``output="current"``) or a
target force [N] (``output="force"``, tracked through the damper's inverse model like
the inverse-model laws; it then needs the dissertation's symmetric damper). Decorated
with :func:`law` it becomes a :class:`~mrsuspension.control.base.Controller` class:
calling it with option values gives the controller, which runs wherever a built-in law
runs (``Simulation``, ``VehicleSimulation`` at every corner, sweeps, studies, the
optimiser and the HiL loop).

How it runs: the engine's kernels are compiled once for every law. A law is an address
(a C entry ``double law(double *signals, double *options, int64 n)``) in the law's
parameter vector (:data:`~mrsuspension.control.kernel.P_USER_FN`), called by the step at
every control sample.

* **numba path**: when the function compiles with ``numba.njit`` (in nopython mode), the
  entry is a numba ``cfunc`` calling it: no Python in the loop. Compiling a law takes
  about a second, once per process (not cached on disk: the entry is generated).
* **Python path**: otherwise (or with ``numba=False``) the entry is a ctypes callback
  into Python, about a microsecond per call plus the function's own time
  (:meth:`UserLaw.cost`, ``benchmarks/bench_user_law.py``). An exception in the function
  stops the run and is raised by the engine (:func:`raise_failure`).

A parameter named ``s`` (not a signal name) takes every signal as a named tuple
(``s.z_s_dot``). :func:`load_law` finds a law by ``"module:function"`` or
``"path/to/file.py:function"`` (a scenario's ``[controller] law``).

Examples
--------
>>> @law
... def my_skyhook(z_s_dot, v_d, high=0.5):
...     return high if z_s_dot * v_d < 0.0 else 0.0
>>> ctl = my_skyhook(high=0.3)
>>> ctl.high, my_skyhook.output, [o.name for o in my_skyhook.describe_options()]
(0.3, 'current', ['high'])
"""

from __future__ import annotations

import collections
import ctypes
import dataclasses
import hashlib
import importlib
import importlib.util
import inspect
import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension._numba_cache import INLINED
from mrsuspension.control import kernel as CK
from mrsuspension.control.base import Controller, ControlOption, option
from mrsuspension.control.signals import NS, S_T, SIGNAL_NAMES, SIGNALS
from mrsuspension.errors import MRSuspensionError, ValidationError, did_you_mean

__all__ = [
    "FAILED",
    "OUTPUTS",
    "LawEntry",
    "UserLaw",
    "check_loop_budget",
    "is_law_spec",
    "law",
    "load_law",
    "raise_failure",
]

#: what a law returns: the drive current [A] or a target force [N]
OUTPUTS = {
    "current": CK.C_USER_CURRENT,
    "force": CK.C_USER_FORCE,
    "active": CK.C_USER_ACTIVE,
}
#: a Python law's exceptions in this process, raised by the engine after the step
#: (:func:`raise_failure`); empty while all is well
FAILED: list[tuple[str, BaseException]] = []
#: share of a HiL tick a Python law may take (the step, the rig and the recorder need
#: the rest)
LOOP_SHARE = 0.5
#: every signal by name, as a named tuple (a law's parameter ``s``)
Signals = collections.namedtuple("Signals", SIGNAL_NAMES)  # type: ignore[misc]

_CFUNC_SIG: Any = None  # numba's signature of the entry (built on first use)
_CTYPES_ENTRY = ctypes.CFUNCTYPE(
    ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
    ctypes.c_int64,
)  # fmt: skip


@dataclass(frozen=True)
class LawEntry:
    """A law's compiled entry in this process.

    Attributes
    ----------
    address : int
        The entry's address (written into the parameter vector).
    path : str
        ``"numba"`` or ``"python"``.
    compile_seconds : float
        Time to build the entry (numba: the compile).
    reason : str
        Why the numba path was not taken ("" on the numba path).
    keep : object
        The cfunc or ctypes callback (kept alive as long as the entry).
    """

    address: int
    path: str
    compile_seconds: float
    reason: str
    keep: Any = dataclasses.field(repr=False, compare=False)


_ENTRIES: dict[type, LawEntry] = {}


def raise_failure() -> None:
    """Raise the first exception a Python law raised in this process (and forget them).

    Called by the engine after a kernel call; the run stopped at the failing step (the
    law's current was NaN).
    """
    if not FAILED:
        return
    name, exc = FAILED[0]
    FAILED.clear()
    if not isinstance(exc, Exception):  # KeyboardInterrupt, SystemExit: as they are
        raise exc
    raise MRSuspensionError(f"control law {name!r} raised {type(exc).__name__}: {exc}") from exc


@dataclass(frozen=True)
class UserLaw(Controller):
    """Base of the laws :func:`law` makes (one subclass per function; its fields are the
    function's options)."""

    law: ClassVar[str] = "user"
    code: ClassVar[int] = CK.C_USER_CURRENT
    #: ``"current"`` or ``"force"``
    output: ClassVar[str] = "current"
    #: the function (its parameters: signals, then options)
    function: ClassVar[Callable[..., float]]
    #: per parameter: ("signal", slot), ("signals", -1) or ("option", name)
    inputs: ClassVar[tuple[tuple[str, Any], ...]] = ()
    #: ``hook(plant, **options) -> {option: value}`` of :meth:`for_plant`, or None
    plant_hook: ClassVar[Callable[..., dict[str, Any]] | None] = None
    #: numba path (None: when it compiles; False: always Python)
    use_numba: ClassVar[bool | None] = None
    #: the options' declarations given to :func:`law` (unit, range, symbol by option)
    meta: ClassVar[dict[str, dict[str, Any]] | None] = None
    #: values of the law's memory (its parameter ``memory``), after its options
    memory_size: ClassVar[int] = 0

    @classmethod
    def option_names(cls) -> tuple[str, ...]:
        """The options in the order they are packed after the entry's address."""
        return tuple(v for k, v in cls.inputs if k == "option")

    @classmethod
    def entry(cls) -> LawEntry:
        """The compiled entry in this process (built on first use: numba, else Python)."""
        got = _ENTRIES.get(cls)
        if got is None:
            got = _build_entry(cls)
            _ENTRIES[cls] = got
        return got

    @classmethod
    def path(cls) -> str:
        """``"numba"`` or ``"python"``: how the law runs in this process."""
        return cls.entry().path

    @classmethod
    def cost(cls, calls: int | None = None) -> float:
        """Measured time of one call of the law from the kernel [s] (median of 5 runs).

        Examples
        --------
        >>> @law
        ... def zero(v_d):
        ...     return 0.0
        >>> zero.cost() < 1e-3
        True
        """
        entry = cls.entry()
        params = cls().params(1.0)
        sig = np.zeros(NS)
        opt = np.ascontiguousarray(params[CK.P_USER_FN + 1 :])
        t0 = time.perf_counter()
        _bench(entry.address, sig, opt, 10)
        first = max((time.perf_counter() - t0) / 10, 1e-9)
        n = calls or int(min(max(0.01 / first, 10), 1e6))  # about 10 ms a run
        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            _bench(entry.address, sig, opt, n)
            times.append((time.perf_counter() - t0) / n)
        raise_failure()
        return float(np.median(times))

    def _tail(self) -> npt.NDArray[np.float64]:
        address = type(self).entry().address
        parts = [np.array([float(address)])]
        parts += [np.asarray(getattr(self, n), dtype=float).ravel() for n in self.option_names()]
        parts.append(np.zeros(type(self).memory_size))  # the memory, zero at the start
        return np.concatenate(parts)

    def option_slots(self) -> dict[str, slice]:
        """Where each option lies in :meth:`params` (after the entry's address)."""
        out: dict[str, slice] = {}
        at = CK.P_USER_FN + 1
        for name in self.option_names():
            n = int(np.asarray(getattr(self, name), dtype=float).size)
            out[name] = slice(at, at + n)
            at += n
        return out

    def for_plant(self, plant: Any) -> Controller:
        """The law attached to ``plant``: the options its ``for_plant`` hook derives."""
        hook = type(self).plant_hook
        if hook is None:
            return self
        values = hook(plant, **{n: getattr(self, n) for n in self.option_names()})
        if not isinstance(values, dict):
            raise ValidationError(
                f"control law {self.law!r}: its for_plant hook must return a dict of option "
                f"values; got {values!r}"
            )
        bad = [k for k in values if k not in self.option_names()]
        if bad:
            raise ValidationError(
                f"control law {self.law!r}: its for_plant hook set {bad[0]!r}, not an option "
                f"(options: {', '.join(self.option_names()) or 'none'})"
            )
        return dataclasses.replace(self, **values) if values else self

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickled as its class (when importable by name, a decorated function) or its
        function and :func:`law` arguments, with its options (for process pools)."""
        cls = type(self)
        module = sys.modules.get(cls.__module__)
        ref: Any = cls
        if module is None or getattr(module, cls.__qualname__, None) is not cls:
            ref = (
                cls.function, cls.output, cls.use_numba, cls.plant_hook, cls.law, cls.meta,
                cls.memory_size,
            )  # fmt: skip
        return (_rebuild, (ref, {n: getattr(self, n) for n in self.option_names()}))

    def describe(self) -> dict[str, Any]:
        """Plain data: the law's name (``module:function``) and its options (lists).

        Examples
        --------
        >>> @law(output="force")
        ... def lin(x_d, k=(1.0, 2.0)):
        ...     return k[0] * x_d
        >>> lin().describe()["k"]
        [1.0, 2.0]
        """
        out: dict[str, Any] = {"law": self.law}
        for n in self.option_names():
            v = getattr(self, n)
            out[n] = np.asarray(v, dtype=float).tolist() if isinstance(v, tuple) else v
        return out


def _rebuild(ref: Any, options: dict[str, Any]) -> UserLaw:
    """A pickled law (:meth:`UserLaw.__reduce__`)."""
    if isinstance(ref, type):
        cls = ref
    else:
        fn, output, numba, hook, name, meta, memory = ref
        cls = law(fn, output=output, numba=numba, for_plant=hook, options=meta, memory=memory)
        cls.law = name
    made: UserLaw = cls(**options)
    return made


_CLASSES: dict[tuple[Any, ...], type[UserLaw]] = {}
#: names a law's options cannot take (the law class's own attributes)
_RESERVED = frozenset(n for n in dir(UserLaw) if not n.startswith("__"))


def _inputs(
    fn: Callable[..., Any],
    name: str,
    meta: dict[str, dict[str, Any]] | None = None,
    memory: int = 0,
) -> tuple[list[tuple[str, Any]], list[Any]]:
    """The function's parameters as inputs, and its options' dataclass fields (declared
    with ``meta[option]``: :func:`~mrsuspension.control.base.option`'s keywords)."""
    inputs: list[tuple[str, Any]] = []
    fields: list[Any] = []
    meta = dict(meta or {})
    params = inspect.signature(fn).parameters
    unknown = [k for k in meta if k not in params or params[k].default is params[k].empty]
    if unknown:
        raise ValidationError(
            f"control law {name!r}: options={{{unknown[0]!r}: ...}} declares no option of "
            "the function (an option is a parameter with a default)"
        )
    for p in inspect.signature(fn).parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            raise ValidationError(
                f"control law {name!r}: parameter {p.name!r} must be a signal or an option "
                "with a default, not *args or **kwargs"
            )
        if p.name == "memory" and p.default is p.empty:
            if memory <= 0:
                raise ValidationError(
                    f"control law {name!r}: parameter 'memory' needs law(memory=n), the "
                    "number of values the law keeps between calls"
                )
            inputs.append(("memory", memory))
            continue
        if p.default is p.empty:
            if p.name in SIGNALS:
                inputs.append(("signal", SIGNALS[p.name].slot))
            elif p.name == "s":
                inputs.append(("signals", -1))
            else:
                raise ValidationError(
                    f"control law {name!r}: parameter {p.name!r} is not a signal and has no "
                    f"default (an option needs one).{did_you_mean(p.name, SIGNALS)} "
                    f"Signals: {', '.join(SIGNALS)}; or 's' for all of them"
                )
            continue
        if p.name in _RESERVED:
            raise ValidationError(
                f"control law {name!r}: option {p.name!r} would hide the law's own "
                f"{p.name!r}; rename it (reserved: {', '.join(sorted(_RESERVED))})"
            )
        if p.name in SIGNALS or p.name == "s":
            raise ValidationError(
                f"control law {name!r}: {p.name!r} names a signal, it cannot be an option "
                "with a default"
            )
        default = p.default
        if isinstance(default, bool) or not isinstance(
            default, int | float | list | tuple | np.ndarray
        ):
            raise ValidationError(
                f"control law {name!r}: option {p.name!r} must default to a number or to a "
                f"vector or matrix of numbers (a list); got {default!r}"
            )
        declared = meta.get(p.name, {})
        if isinstance(default, int | float):
            spec = option(float(default), **declared)
        else:
            arr = np.asarray(default, dtype=float)
            if arr.ndim not in (1, 2) or arr.size == 0:
                raise ValidationError(
                    f"control law {name!r}: option {p.name!r} must be a non-empty vector or "
                    f"matrix; got shape {arr.shape}"
                )
            checked = ControlOption(p.name, None, shape=arr.shape, **declared).check(arr)
            spec = option(checked, shape=arr.shape, **declared)
        inputs.append(("option", p.name))
        fields.append((p.name, Any, spec))
    return inputs, fields


def law(
    fn: Callable[..., float] | None = None,
    *,
    output: str = "current",
    for_plant: Callable[..., dict[str, Any]] | None = None,
    numba: bool | None = None,
    options: dict[str, dict[str, Any]] | None = None,
    memory: int = 0,
) -> Any:
    """Make a control law of a plain Python function (a :class:`UserLaw` class).

    Parameters
    ----------
    fn : callable
        ``fn(<signals>, <options>) -> float``: parameters without a default are signals
        by name (:data:`~mrsuspension.control.signals.SIGNALS`; ``s``: all of them as a
        named tuple), parameters with a default are the law's options (a number, or a
        list for a vector or a list of lists for a matrix: the default's shape is the
        option's).
    output : {"current", "force", "active"}
        What ``fn`` returns: the drive current [A] (clipped to ``[0, max_current]``), a
        target force [N] through the damper's inverse model, or (``"active"``) a force
        [N] applied as it is by an ideal actuator in place of the damper (a reference
        such as the active LQR; the damper model is not used).
    for_plant : callable, optional
        ``for_plant(plant, **options) -> {option: value}``: options derived from the
        quarter car (or the vehicle's corner) the law is attached to, e.g. gains from a
        Riccati solve (:meth:`~mrsuspension.control.base.Controller.for_plant`).
    numba : bool, optional
        None (default): the numba path when ``fn`` compiles with ``numba.njit``, else
        Python; False: always Python.
    options : dict, optional
        Declarations of the options by name: the keywords of
        :func:`~mrsuspension.control.base.option` (``unit``, ``low``, ``high``,
        ``symbol``, ``label``...), checked on construction and shown by
        ``describe_options()``.
    memory : int, optional
        The number of values the law keeps between calls (an estimator's state): its
        parameter ``memory`` is then a writable float array of that length, zero at the
        first control sample of a run (``time`` = 0) and kept from call to call, one per
        corner.

    Returns
    -------
    type
        The law's class: ``my_law(**options)`` is a controller.

    Raises
    ------
    ValidationError
        A parameter that is neither a signal nor an option with a default, or a bad
        ``output``.
    """
    if output not in OUTPUTS:
        raise ValidationError(f"law output must be 'current', 'force' or 'active'; got {output!r}")

    def make(f: Callable[..., float]) -> type[UserLaw]:
        if not callable(f):
            raise ValidationError(f"law needs a function; got {f!r}")
        if not isinstance(memory, int) or isinstance(memory, bool) or memory < 0:
            raise ValidationError(f"law memory must be a whole number >= 0; got {memory!r}")
        key = (f, output, numba, for_plant, repr(sorted((options or {}).items())), memory)
        known = _CLASSES.get(key)
        if known is not None:  # one class (one compiled entry) per function and arguments
            return known
        name = f"{f.__module__}:{f.__qualname__}"
        inputs, fields = _inputs(f, name, options, memory)
        cls = dataclasses.make_dataclass(
            f.__name__,
            fields,
            bases=(UserLaw,),
            frozen=True,
            namespace={
                "law": name,
                "code": OUTPUTS[output],
                "output": output,
                "needs_inverse": output == "force",
                "force_source": CK.F_TARGET if output == "active" else CK.F_MODEL,
                "meta": dict(options) if options else None,
                "memory_size": memory,
                "function": staticmethod(f),
                "inputs": tuple(inputs),
                "plant_hook": staticmethod(for_plant) if for_plant is not None else None,
                "use_numba": numba,
                "__doc__": f.__doc__ or f"User-defined control law {name}.",
            },
        )
        cls.__module__ = f.__module__
        cls.__qualname__ = f.__qualname__
        _CLASSES[key] = cls
        return cls

    return make(fn) if fn is not None else make


# -- the entries ---------------------------------------------------------------------------
def _memory_at(cls: type[UserLaw]) -> int:
    """Where the law's memory starts among its options' values (after them)."""
    defaults = cls()
    return sum(int(np.asarray(getattr(defaults, n), dtype=float).size) for n in cls.option_names())


def _arguments(cls: type[UserLaw], sig: str, opt: str, python: bool) -> str:
    """The call's argument list, reading signals from ``sig`` and options from ``opt``."""
    args = []
    at = 0
    defaults = cls()
    for kind, value in cls.inputs:
        if kind == "memory":
            start = _memory_at(cls)
            args.append(f"{opt}[{start}:{start + value}]")  # a writable view
            continue
        if kind == "signal":
            args.append(f"{sig}[{value}]")
        elif kind == "signals":
            if python:
                args.append(f"_S(*{sig}[0:{NS}])")
            else:
                args.append("_S(" + ", ".join(f"{sig}[{i}]" for i in range(NS)) + ")")
        else:
            arr = np.asarray(getattr(defaults, value), dtype=float)
            if arr.ndim == 0:
                args.append(f"{opt}[{at}]")
            else:
                span = f"{opt}[{at}:{at + arr.size}]"
                if python:
                    span = f"_np.array({span})"
                if arr.ndim == 2:
                    span += f".reshape(({arr.shape[0]}, {arr.shape[1]}))"
                args.append(span)
            at += arr.size
    return ", ".join(args)


def _numba_entry(cls: type[UserLaw]) -> tuple[Any, int]:
    global _CFUNC_SIG
    from numba import carray, cfunc, types

    if _CFUNC_SIG is None:
        _CFUNC_SIG = types.float64(
            types.CPointer(types.float64), types.CPointer(types.float64), types.int64
        )
    reset = ""
    if cls.memory_size:  # the memory is zero at the first control sample of a run
        start = _memory_at(cls)
        reset = (
            f"    if sig[{S_T}] == 0.0:\n"
            f"        for k in range({start}, {start + cls.memory_size}):\n"
            "            opt[k] = 0.0\n"
        )
    src = (
        "def _entry(s, o, n):\n"
        f"    sig = carray(s, ({NS},))\n"
        "    opt = carray(o, (n,))\n"
        f"{reset}"
        f"    return float(_fn({_arguments(cls, 'sig', 'opt', python=False)}))\n"
    )
    space: dict[str, Any] = {
        "carray": carray,
        "_fn": njit(error_model="numpy")(cls.function),
        "_S": Signals,
    }
    exec(compile(src, f"<control law {cls.law}>", "exec"), space)
    entry = cfunc(_CFUNC_SIG, error_model="numpy")(space["_entry"])
    return entry, int(entry.address or 0)


def _python_entry(cls: type[UserLaw]) -> tuple[Any, int]:
    view = ""
    opt = "o"
    if cls.memory_size:  # the options as a writable view: the memory is kept in place
        start = _memory_at(cls)
        view = (
            "        opt = _np.ctypeslib.as_array(o, (n,))\n"
            f"        if s[{S_T}] == 0.0:\n"
            f"            opt[{start}:{start + cls.memory_size}] = 0.0\n"
        )
        opt = "opt"
    src = (
        "def _entry(s, o, n):\n"
        "    try:\n"
        f"{view}"
        f"        return float(_fn({_arguments(cls, 's', opt, python=True)}))\n"
        "    except BaseException as exc:\n"
        "        _FAILED.append((_name, exc))\n"
        "        return _nan\n"
    )
    space: dict[str, Any] = {
        "_fn": cls.function,
        "_S": Signals,
        "_np": np,
        "_FAILED": FAILED,
        "_name": cls.law,
        "_nan": math.nan,
    }
    exec(compile(src, f"<control law {cls.law}>", "exec"), space)
    callback = _CTYPES_ENTRY(space["_entry"])
    return callback, int(ctypes.cast(callback, ctypes.c_void_p).value or 0)


def _build_entry(cls: type[UserLaw]) -> LawEntry:
    t0 = time.perf_counter()
    reason = "numba=False" if cls.use_numba is False else ""
    if cls.use_numba is not False:
        try:
            keep, address = _numba_entry(cls)
        except Exception as exc:
            reason = f"{type(exc).__name__}: {str(exc).strip().splitlines()[0][:200]}"
        else:
            return _checked(LawEntry(address, "numba", time.perf_counter() - t0, "", keep))
    keep, address = _python_entry(cls)
    return _checked(LawEntry(address, "python", time.perf_counter() - t0, reason, keep))


def _checked(entry: LawEntry) -> LawEntry:
    if not 0 < entry.address < 2**53:  # exact in the float64 parameter vector
        raise MRSuspensionError(
            f"a control law's entry address {entry.address:#x} does not fit a float64 exactly"
        )
    return entry


@njit(cache=True, **INLINED)
def _bench(addr: int, sig: np.ndarray, opt: np.ndarray, n: int) -> float:
    """``n`` calls of the law at ``addr`` (the time at ``S_T`` moving), as the step calls it."""
    acc = 0.0
    for k in range(n):
        sig[S_T] = k * 1e-4
        acc += CK.call_law(addr, sig, opt)  # type: ignore[call-arg]
    return acc


# -- finding a law by name -----------------------------------------------------------------
def is_law_spec(name: object) -> bool:
    """Whether ``name`` names a user law (``"module:function"``, ``"file.py:function"``).

    Examples
    --------
    >>> is_law_spec("my_module:my_law"), is_law_spec("skyhook-hilo")
    (True, False)
    """
    return isinstance(name, str) and ":" in name


def load_law(spec: str, *, base: Path | None = None) -> type[UserLaw]:
    """The law named ``spec``: ``"module:function"`` (importable) or
    ``"path/to/file.py:function"`` (relative to ``base``, default the working directory).

    A plain function (not decorated with :func:`law`) becomes a current law.

    Raises
    ------
    ValidationError
        A module or file that cannot be imported, no such function, or a bad signature.

    Examples
    --------
    >>> load_law("mrsuspension.control.user:is_law_spec")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: control law 'mrsuspension.control.user:is_law_spec': parameter 'name' is not a signal and has no default (an option needs one). Signals: z_s, z_s_dot, z_u, z_u_dot, z_s0, z_s0_dot, z_s_ddot, z_u_ddot, x_d, v_d, F_d, i_d, v_m, time, heave, pitch, roll, heave_dot, pitch_dot, roll_dot, heave_ddot, pitch_ddot, roll_ddot, corner; or 's' for all of them
    """
    where, _, attr = spec.rpartition(":")
    if not where or not attr:
        raise ValidationError(
            f"control law {spec!r} must be 'module:function' or 'path/to/file.py:function'"
        )
    if where.endswith(".py"):
        path = Path(where) if base is None or Path(where).is_absolute() else base / where
        if not path.is_file():
            raise ValidationError(f"control law {spec!r}: no file {str(path)!r}")
        digest = hashlib.sha256(str(path.resolve()).encode()).hexdigest()[:12]
        mod_name = f"mrsuspension_law_{path.stem}_{digest}"
        module = sys.modules.get(mod_name)
        if module is None:
            loader = importlib.util.spec_from_file_location(mod_name, path)
            if loader is None or loader.loader is None:
                raise ValidationError(f"control law {spec!r}: cannot import {str(path)!r}")
            module = importlib.util.module_from_spec(loader)
            sys.modules[mod_name] = module
            try:
                loader.loader.exec_module(module)
            except Exception as exc:
                del sys.modules[mod_name]
                raise ValidationError(
                    f"control law {spec!r}: importing {str(path)!r} failed: "
                    f"{type(exc).__name__}: {exc}"
                ) from None
    else:
        try:
            module = importlib.import_module(where)
        except Exception as exc:
            raise ValidationError(
                f"control law {spec!r}: cannot import module {where!r} "
                f"({type(exc).__name__}: {exc})"
            ) from None
    found = getattr(module, attr, None)
    if found is None:
        names = [n for n in dir(module) if not n.startswith("_")]
        raise ValidationError(
            f"control law {spec!r}: {where!r} has no {attr!r}.{did_you_mean(attr, names)}"
        )
    if isinstance(found, type) and issubclass(found, UserLaw):
        if where.endswith(".py"):  # its module is private: the law is known by its spec
            found.law = spec
        return found
    if isinstance(found, type) or not callable(found):
        raise ValidationError(
            f"control law {spec!r}: {attr!r} is not a function or a law made with "
            f"mrsuspension.control.law; got {found!r}"
        )
    made: type[UserLaw] = law(found)
    made.law = spec
    return made


def check_loop_budget(simulation: Any, calls_per_tick: int, period: float) -> None:
    """Refuse a Python law too slow for a loop at ``period`` [s].

    ``calls_per_tick``: engine steps per tick (each calls the law once per corner).

    Raises
    ------
    ValidationError
        When the Python laws' measured cost per tick is above :data:`LOOP_SHARE` of the
        period (the message states the cost).
    """
    sims = (
        [simulation.corner_simulation(c) for c in simulation.corners]
        if hasattr(simulation, "corner_simulation")
        else [simulation]
    )
    laws = [type(s.controller) for s in sims if isinstance(s.controller, UserLaw)]
    python = [cls for cls in laws if cls.path() == "python"]
    if not python:
        return
    costs = {cls: cls.cost() for cls in set(python)}
    total = sum(costs[cls] for cls in python) * calls_per_tick
    if total > LOOP_SHARE * period:
        cls = python[0]
        why = cls.entry().reason or "not compiled"
        raise ValidationError(
            f"control law {cls.law!r} runs in Python ({why}) at {costs[cls] * 1e6:.1f} us "
            f"per call: {len(python)} corner(s) x {calls_per_tick} steps per tick = "
            f"{total * 1e6:.0f} us, above {LOOP_SHARE:.0%} of the {period * 1e6:.0f} us "
            "tick; make it compile with numba (numbers and arrays only) or lower the loop "
            "rate or the steps per tick (a larger model_dt)"
        )
