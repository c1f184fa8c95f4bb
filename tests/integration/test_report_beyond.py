"""The report's "Beyond the dissertation" section (``mrsus reproduce --chapters beyond``)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from _helpers import raises_validation
from mrsuspension.cli import app
from mrsuspension.report import build_report
from mrsuspension.report.beyond import WEIGHTS


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("beyond")
    build_report(out, chapters=["beyond"], quick=True)
    return out


def test_section_figures_table_and_optimiser(report: Path) -> None:
    index = (report / "index.html").read_text()
    assert "Beyond the dissertation" in index
    assert "Chapter 2" not in index
    manifest = json.loads((report / "manifest.json").read_text())
    assert manifest["chapters"] == {}
    section = manifest["beyond"]
    assert [f["number"] for f in section["figures"]] == ["B.1", "B.2"]
    for slug in ("fig_B_1", "fig_B_2"):
        assert f"beyond/{slug}.png" in index
        assert (report / "beyond" / f"{slug}.png").stat().st_size > 5000
    with (report / "beyond" / "tradeoff_points.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == section["tables"][0]["rows"] >= 15
    assert {r["controller"] for r in rows} >= {"passive", "skyhook hi-lo ACM", "ideal skyhook"}
    assert any(r["front a_s-DLC"] == "yes" for r in rows)
    opt = section["optimiser"]
    assert 1.0 <= opt["best"]["controller.gain"] <= 3000.0
    ratios = [opt["measures"][m] / opt["reference"][m] for m in WEIGHTS]
    expected = sum(w * r for w, r in zip(WEIGHTS.values(), ratios, strict=True)) / sum(
        WEIGHTS.values()
    )
    assert opt["objective"] == pytest.approx(expected)
    saved = json.loads((report / "beyond" / "optimization.json").read_text())
    assert saved["best"] == opt["best"]


def test_unknown_chapter_names() -> None:
    raises_validation(lambda: build_report("unused", chapters=[9]), "chapter 9", "beyond")
    res = CliRunner().invoke(app, ["reproduce", "--chapters", "2,beyonf", "--out", "unused"])
    assert res.exit_code == 2
    assert "unknown chapter 'beyonf'" in res.stderr
