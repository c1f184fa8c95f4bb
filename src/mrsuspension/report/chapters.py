"""The report's chapter registry: every chapter of ``mrsus reproduce`` in one place.

A chapter is one module of :mod:`mrsuspension.report` exposing ``CHAPTER``, a
:class:`~mrsuspension.report.toolkit.Chapter` (what it needs built in the report's process
pool, and how it writes its section). :data:`CHAPTERS` names the modules by chapter
number; they are imported on first use, so importing the registry stays cheap. Adding a
chapter is one module plus one line here. :data:`SECTIONS` are the report's other
sections (the findings scorecard, "Beyond the dissertation", "Beyond the quarter car"
and "Benchmark of semi-active laws"), and :func:`choices` /
:func:`parse_chapters` give what ``mrsus reproduce --chapters`` accepts.

Chapter 7 (:mod:`mrsuspension.report.ch7`, the HiL-against-offline comparisons of
``mrsus hil validate``) is not a chapter of the reproduced report: it needs a rig.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable

from mrsuspension.errors import ValidationError, did_you_mean
from mrsuspension.report.toolkit import Chapter

__all__ = ["CHAPTERS", "SECTIONS", "chapter", "choices", "parse_chapters", "resolve"]

#: Chapter number -> module under ``mrsuspension.report`` exposing ``CHAPTER``
CHAPTERS: dict[int, str] = {
    2: "ch2",
    3: "ch3",
    4: "ch4",
    5: "ch5",
    6: "ch6",
}
#: The report's sections that are not chapters (findings first, beyond last on the page)
SECTIONS: tuple[str, ...] = ("findings", "beyond", "vehicles", "benchmark")


def chapter(number: int) -> Chapter:
    """The registered chapter ``number``.

    Raises
    ------
    ValidationError
        For a chapter that is not registered.

    Examples
    --------
    >>> entry = chapter(4)
    >>> entry.number, list(entry.jobs(True).figures), entry.figures[0].number
    (4, ['chapter4'], '4.1')
    """
    if number not in CHAPTERS:
        raise ValidationError(
            f"chapter {number} is not available; available: {', '.join(choices())}"
        )
    module = importlib.import_module(f"mrsuspension.report.{CHAPTERS[number]}")
    entry: Chapter = module.CHAPTER
    if entry.number != number:
        raise ValidationError(  # a registry slip, caught on first use
            f"report.chapters.CHAPTERS[{number}] names {CHAPTERS[number]!r}, "
            f"whose CHAPTER is chapter {entry.number}"
        )
    return entry


def choices() -> tuple[str, ...]:
    """What ``--chapters`` accepts: the registered chapter numbers, then :data:`SECTIONS`.

    Examples
    --------
    >>> choices()
    ('2', '3', '4', '5', '6', 'findings', 'beyond', 'vehicles', 'benchmark')
    """
    return (*(str(n) for n in sorted(CHAPTERS)), *SECTIONS)


def resolve(selection: Iterable[int | str] | None) -> tuple[list[int], set[str]]:
    """The chapters (sorted) and sections of a selection (None: everything).

    Raises
    ------
    ValidationError
        For an unknown chapter or section, or an empty selection.

    Examples
    --------
    >>> resolve([4, "2", "beyond"])
    ([2, 4], {'beyond'})
    >>> numbers, sections = resolve(None)
    >>> numbers, sorted(sections)
    ([2, 3, 4, 5, 6], ['benchmark', 'beyond', 'findings', 'vehicles'])
    """
    if selection is None:
        return sorted(CHAPTERS), set(SECTIONS)
    numbers: set[int] = set()
    sections: set[str] = set()
    for item in selection:
        text = str(item).strip().lower()
        if text in SECTIONS:
            sections.add(text)
        elif text.isdigit() and int(text) in CHAPTERS:
            numbers.add(int(text))
        else:
            raise ValidationError(
                f"chapter {item} is not available; available: {', '.join(choices())}."
                + did_you_mean(text, choices())
            )
    if not numbers and not sections:
        raise ValidationError("no chapters selected")
    return sorted(numbers), sections


def parse_chapters(text: str) -> list[int | str]:
    """A ``--chapters`` value: comma-separated chapter numbers and section names.

    For the ``mrsus reproduce`` command; the choices come from the registry.

    Raises
    ------
    ValidationError
        Naming the option, the item and the valid choices.

    Examples
    --------
    >>> parse_chapters("2, 4,findings")
    [2, 4, 'findings']
    >>> parse_chapters("9")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --chapters: unknown chapter '9'. Give chapter numbers (2, 3, 4, 5, 6), 'findings' and/or 'beyond' and/or 'vehicles' and/or 'benchmark', comma-separated.
    """
    out: list[int | str] = []
    for item in (c.strip() for c in text.split(",")):
        if not item:
            continue
        if item.lower() in SECTIONS:
            out.append(item.lower())
        elif item.isdigit() and int(item) in CHAPTERS:
            out.append(int(item))
        else:
            raise ValidationError(
                f"--chapters: unknown chapter {item!r}.{did_you_mean(item.lower(), choices())} "
                f"Give chapter numbers ({_numbers()}), {_sections()}, comma-separated."
            )
    if not out:
        raise ValidationError(
            f"--chapters needs at least one chapter number ({_numbers()}), {_sections()}"
        )
    return out


def _numbers() -> str:
    return ", ".join(str(n) for n in sorted(CHAPTERS))


def _sections() -> str:
    return " and/or ".join(f"'{s}'" for s in SECTIONS)
