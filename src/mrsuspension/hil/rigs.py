"""The rig registry: every rig kind a ``--rig`` spec can name, and :func:`make_rig`.

Each kind in :data:`RIGS` declares its spec syntax, a one-line description, whether
``mrsus rig-emulator`` can serve it, and how to build it; the command-line help and the
error messages are derived from the registry, so adding a rig kind touches this file
only. Importing this module is cheap (the rigs' own modules load when a rig is built).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from mrsuspension._docs import doc
from mrsuspension.errors import MRSuspensionError, ValidationError

if TYPE_CHECKING:
    from mrsuspension.hil.rig import Rig

__all__ = ["RIGS", "RigKind", "make_rig", "normalise_rig_spec", "rig_kind", "rig_syntax"]


@dataclass(frozen=True)
class RigKind:
    """One kind of rig a ``--rig`` spec can name.

    Parameters
    ----------
    name : str
        Registry key.
    syntax : str
        The spec as a user writes it (``simulated``, ``udp://HOST:PORT``).
    description : str
        One line for help texts.
    local : bool
        Built in this process (so ``mrsus rig-emulator`` can serve it); a network rig is
        not.
    matches : callable
        ``matches(spec)`` for a stripped, lower-cased spec.
    build : callable
        ``build(spec, damper)`` returns the :class:`~mrsuspension.hil.rig.Rig`.
    """

    name: str
    syntax: str
    description: str
    local: bool
    matches: Callable[[str], bool]
    build: Callable[[str, Any], Rig]


def _simulated(spec: str, damper: Any) -> Rig:
    from mrsuspension.hil.rig import SimulatedRig

    return SimulatedRig(damper=damper)


def _ideal(spec: str, damper: Any) -> Rig:
    from mrsuspension.hil.rig import ideal_rig

    return ideal_rig(damper)


def _udp(spec: str, damper: Any) -> Rig:
    """A :class:`~mrsuspension.hil.network.UdpRig` checked with a heartbeat first (the
    served rig carries its own damper)."""
    from mrsuspension.hil.network import UdpRig

    udp = UdpRig.from_spec(spec, reset_timeout=0.5)
    try:
        udp.ping()
    except MRSuspensionError as exc:
        raise ValidationError(f"--rig {spec}: {exc}; is `mrsus rig-emulator` running?") from exc
    finally:
        udp.close()
    return udp


#: the rig kinds, by name
RIGS: dict[str, RigKind] = {
    kind.name: kind
    for kind in (
        RigKind(
            "simulated",
            "simulated",
            f"simulated rig: actuator, current driver and A/D quantisation ({doc('hil')})",
            True,
            lambda s: s == "simulated",
            _simulated,
        ),
        RigKind(
            "ideal",
            "ideal",
            "ideal simulated rig: perfect actuator and driver, no quantisation",
            True,
            lambda s: s == "ideal",
            _ideal,
        ),
        RigKind(
            "udp",
            "udp://HOST:PORT",
            "a rig served over UDP (e.g. `mrsus rig-emulator`), pinged before use",
            False,
            lambda s: s.startswith("udp://"),
            _udp,
        ),
    )
}


def rig_syntax(local_only: bool = False) -> str:
    """The accepted specs joined by `` | `` (for help texts).

    Examples
    --------
    >>> rig_syntax()
    'simulated | ideal | udp://HOST:PORT'
    >>> rig_syntax(local_only=True)
    'simulated | ideal'
    """
    return " | ".join(k.syntax for k in RIGS.values() if k.local or not local_only)


def rig_kind(
    spec: str, *, option: str = "--rig", kinds: Sequence[RigKind] | None = None
) -> RigKind:
    """The registered kind a spec names.

    Raises
    ------
    ValidationError
        Naming ``option``, the spec and the valid specs when no kind matches.

    Examples
    --------
    >>> rig_kind("Ideal").name
    'ideal'
    >>> rig_kind("bench")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown --rig 'bench'; valid: simulated, ideal, udp://HOST:PORT
    """
    choices = list(RIGS.values()) if kinds is None else list(kinds)
    low = spec.strip().lower()
    for kind in choices:
        if kind.matches(low):
            return kind
    valid = ", ".join(k.syntax for k in choices)
    raise ValidationError(f"unknown {option} {spec!r}; valid: {valid}")


def normalise_rig_spec(spec: str) -> str:
    """A spec stripped, lower-cased except for a network address (not checked).

    Examples
    --------
    >>> normalise_rig_spec(" Simulated ")
    'simulated'
    >>> normalise_rig_spec("udp://Rig-A:9870")
    'udp://Rig-A:9870'
    """
    spec = spec.strip()
    return spec if rig_kind(spec).name == "udp" else spec.lower()


def make_rig(spec: str, damper: Any) -> Rig:
    """A rig from its ``--rig`` spec carrying ``damper``.

    ``simulated`` and ``ideal`` build a :class:`~mrsuspension.hil.rig.SimulatedRig` (or
    its ideal preset); ``udp://HOST:PORT`` a :class:`~mrsuspension.hil.network.UdpRig`
    (the served rig carries its own damper), checked with a heartbeat first.

    Raises
    ------
    ValidationError
        For an unknown spec, a bad address or a network rig that does not answer.

    Examples
    --------
    >>> from mrsuspension.dampers import WangSymmetric
    >>> rig = make_rig("ideal", WangSymmetric())
    >>> type(rig).__name__
    'SimulatedRig'
    >>> rig.close()
    """
    spec = spec.strip()
    return rig_kind(spec).build(spec, damper)
