"""What a notebook echoes of the objects of the README's Python section: one line each
that says what the object is (the check's tally, the model's states, the vessel's DOFs,
joints and PTOs), not tens of kilobytes of every array and finding."""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pytest

import cummins
from cummins.check.report import SEVERITIES


@pytest.fixture(scope="module")
def tanker():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(cummins.demo_files() / "tanker.1")
        model = cummins.fit_radiation(ds)
        return ds, cummins.check(ds), model, cummins.vessel_from_hydrodb(ds, model)


def test_check_report_echoes_its_tally_and_prints_its_findings(tanker):
    _, report, _, _ = tanker
    text = repr(report)
    assert "\n" not in text and len(text) < 300  # the dataclass's echo: 17.8 kB
    counts = {s: sum(f.severity == s for f in report) for s in SEVERITIES}
    assert f"{len(report.findings)} findings (" in text
    for severity, n in counts.items():
        assert (f"{n} {severity}" in text) == (n > 0)
    assert f"worst {report.worst()!r}, ok={report.ok}" in text
    assert str(report) == report.to_text()


def test_model_and_vessel_echo_their_size_in_one_line(tanker):
    _, _, model, vessel = tanker
    for obj in (model, vessel):
        text = repr(obj)
        assert "\n" not in text and "array(" not in text and len(text) < 300
    assert f"{model.total_order} states" in repr(model)
    assert f"{len(model.couplings)} couplings, {len(model.blocks)} blocks" in repr(model)
    assert f"stable={model.is_stable()}" in repr(model)
    assert repr(vessel).startswith(f"Vessel({len(vessel.dofs)} DOFs Surge, Sway, Heave")
    assert f"radiation: {vessel.radiation.total_order} states" in repr(vessel)
    assert "PTOs" not in repr(vessel) and "motions free" not in repr(vessel)
    held = replace(vessel, constraint=np.eye(6)[:, 2:3])  # heave alone
    assert "1 motions free" in repr(held)
