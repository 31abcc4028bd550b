"""A PTO's damping as an axis of a batch study (``grid: {pto_damping: [..]}``), against
the analytic optimum of one floating body in heave.

The WaveBot (WEC-Sim_Applications' WAMIT run, 858 kg in fresh water) heaving alone on a
PTO to the ground: in a regular wave of frequency ω the mean power at the damping c is
½ c ω² |X|², X = F / (C − ω²(m + A) + iω(B + c)) from the data's A(ω), B(ω), F(ω) and
C, largest at c = √(B² + (ω(m + A) − C/ω)²) (the optimum of a purely resistive load,
Falnes (2002)); in a sea of spectrum S the mean power is ∫ 2 S ½ c ω² |X|² dω.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.mechanics import PTO, MechanicalSystem
from cummins.seakeeping.frequency_domain import motion_rao, pto_rao
from cummins.seakeeping.waves import wave_spectrum
from cummins.studies.batch import case_ids, case_statistics, gather_results, prepare_study
from cummins.studies.pto_sweep import case_system
from cummins.studies.study import Study, StudyError, load_study

MASS = 858.415  # kg: rho V of the WaveBot at rho = 1000 (freely floating)
WAVEBOT = "WEC-Sim_Applications/wamit_WaveBot/waveBotBuoy.out"


@pytest.fixture(scope="module")
def wavebot(corpus):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(corpus / WAVEBOT, rho=1000)
    return cummins.with_inertia(
        ds, mass=[MASS], center_of_gravity=[[0, 0, 0]], radii_of_gyration=[[0.3, 0.3, 0.3]]
    )


def _heave(ds):
    pair = {"influenced_dof": "Heave", "radiating_dof": "Heave"}
    return (
        ds.added_mass.sel(pair).values,
        ds.radiation_damping.sel(pair).values,
        float(ds.hydrostatic_stiffness.sel(pair)),
        ds.excitation_force.sel(influenced_dof="Heave").isel(wave_direction=0).values,
    )


def _analytic_power(c, w, a, b, restoring, force):
    """½ c ω² |X|² per unit wave amplitude squared, W/m²."""
    x = force / (restoring - w**2 * (MASS + a) + 1j * w * (b + c))
    return 0.5 * c * w**2 * np.abs(x) ** 2


def _optimum(w, a, b, restoring):
    """c = √(B² + (ω(m + A) − C/ω)²): the resistive load of largest power."""
    return np.sqrt(b**2 + (w * (MASS + a) - restoring / w) ** 2)


SYSTEM = MechanicalSystem(dofs=("Heave",), ptos=(PTO(dofs=("Heave", "ground"), damping=1.0),))


@pytest.mark.parametrize("period", [2.0, 2.5, 3.2])
def test_regular_wave_power_and_optimum_against_the_analytic_heave_solution(wavebot, period):
    """At a data frequency: the frequency domain's power at the analytic optimum equals
    ½ c ω² |X|², and the best of a fine list of dampings (5 % apart, as a sweep sets them,
    :func:`case_system`) brackets it."""
    a, b, restoring, force = _heave(wavebot)
    k = int(np.argmin(np.abs(wavebot.omega.values - 2 * np.pi / period)))
    w = float(wavebot.omega.values[k])
    best = _optimum(w, a[k], b[k], restoring)
    dampings = best * np.geomspace(0.2, 5.0, 67)  # 5 % apart, B_opt not on the list
    powers = []
    for c in [best, *dampings]:
        system = case_system(SYSTEM, "pto1", float(c), None)
        rao = motion_rao(wavebot, [w], [0.0], system=system)
        powers.append(float(pto_rao(rao, wavebot, system).pto_power.squeeze()))
    expected = _analytic_power(best, w, a[k], b[k], restoring, force[k])
    assert powers[0] == pytest.approx(expected, rel=1e-6)  # measured 1e-12
    i = int(np.argmax(powers[1:]))
    assert 0 < i < dampings.size - 1  # far from the ends of the list
    assert dampings[i - 1] < best < dampings[i + 1]
    assert max(powers[1:]) <= powers[0] * (1 + 1e-9)  # nothing on the list beats B_opt


def _study(ds_path, dampings, **keys):
    grid = {"heading": [0], "hs": [0.1, 0.2], "tp": [2.0, 3.0], "pto_damping": dampings}
    return Study(
        data=ds_path,
        analysis="rao",
        rho=1000,
        mass=MASS,
        center_of_gravity=[0, 0, 0],
        radii_of_gyration=[0.3, 0.3, 0.3],
        n_omega=456,  # the data's frequencies, 0.9 to 10 rad/s by 0.02
        system={"dofs": ["Heave"], "ptos": [{"dofs": ["Heave", "ground"], "damping": 1000}]},
        grid=grid,
        scatter={"hs": [0.1, 0.2], "tp": [2.0, 3.0], "probability": [[0.4, 0.3], [0.2, 0.1]]},
        **keys,
    )


def _run(study):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        context, digest = prepare_study(study)
        values = [case_statistics(context, c) for c in study.all_cases]
    ids = case_ids(study, digest)
    results = gather_results(
        study, values, ids, context.labels, ptos=context.ptos, units=context.units
    )
    results.attrs.update(context.radiation_model)  # as run_study
    return results


def test_a_sweep_study_gives_the_analytic_power_and_the_best_damping(corpus, wavebot):
    """A frequency-domain study sweeping the damping on a fine list (41 values, 12 %
    apart): every case's mean power is ∫ 2 S ½ c ω² |X|² dω of the analytic solution
    (the data's A, B, F on the study's frequencies), the best damping per sea state and
    for the scatter diagram bracket the optimum of that integral, and in the JONSWAP sea
    of T_p the optimum lies near the regular wave's at ω_p (the sea's power is spread
    over frequencies: measured 0.6 to 1.6 times)."""
    from scipy.optimize import minimize_scalar

    dampings = np.geomspace(300, 30000, 41)
    results = _run(_study(corpus / WAVEBOT, dampings.tolist()))
    assert results.pto_damping.attrs["units"] == "N s/m"
    a, b, restoring, force = _heave(wavebot)
    w = np.linspace(float(wavebot.omega[0]), float(wavebot.omega[-1]), 456)
    data_w = wavebot.omega.values
    a, b = np.interp(w, data_w, a), np.interp(w, data_w, b)
    force = np.interp(w, data_w, force.real) + 1j * np.interp(w, data_w, force.imag)

    def sea_power(c, hs, tp):
        s = wave_spectrum("jonswap", hs, tp)(w)
        return np.trapezoid(2 * s * _analytic_power(c, w, a, b, restoring, force), w)

    site = np.zeros(dampings.size)
    for hs, tp, p in ((0.1, 2.0, 0.4), (0.1, 3.0, 0.3), (0.2, 2.0, 0.2), (0.2, 3.0, 0.1)):

        def negative(x, hs=hs, tp=tp):
            return -sea_power(math.exp(x), hs, tp)

        expected = np.array([sea_power(c, hs, tp) for c in dampings])
        computed = results.pto_mean_power.sel(heading=0, hs=hs, tp=tp, pto="pto1").values
        np.testing.assert_allclose(computed, expected, rtol=1e-4)  # measured 2e-6
        site += p * expected
        optimum = minimize_scalar(
            negative,
            bounds=(math.log(300), math.log(30000)),
            method="bounded",
        )
        c_ref = math.exp(optimum.x)
        best = float(results.pto_damping_best.sel(heading=0, hs=hs, tp=tp))
        i = int(np.flatnonzero(dampings == best)[0])
        assert dampings[i - 1] < c_ref < dampings[i + 1]
        assert not bool(results.pto_damping_best_at_edge.sel(heading=0, hs=hs, tp=tp))
        assert float(results.pto_mean_power_best.sel(heading=0, hs=hs, tp=tp)) == pytest.approx(
            expected[i], rel=1e-4
        )
        k = int(np.argmin(np.abs(w - 2 * np.pi / tp)))
        assert 0.4 < c_ref / _optimum(w[k], a[k], b[k], restoring) < 2.5
    np.testing.assert_allclose(results.pto_mean_power_site.sel(heading=0).values, site, rtol=1e-4)
    assert float(results.pto_damping_site_best.sel(heading=0)) == dampings[int(np.argmax(site))]


def test_a_list_that_stops_short_of_the_optimum_says_so(corpus):
    """Dampings all below the optimum: the best is the list's largest, flagged at its
    edge (the optimum may lie beyond), per sea state and for the site."""
    results = _run(_study(corpus / WAVEBOT, [30.0, 100.0, 300.0]))
    assert (results.pto_damping_best == 300.0).all()
    assert results.pto_damping_best_at_edge.all()
    assert bool(results.pto_damping_site_best_at_edge.sel(heading=0))


def test_a_time_domain_sweep_runs_one_vessel_per_damping_in_one_sea(corpus):
    """``simulate`` with a sweep: each case runs its own damping (one radiation model for
    all, recorded) in the same realisation of the sea (one derived seed for every damping:
    the dampings are compared on the same waves), so the runs' mean powers follow the
    frequency domain's by one factor, the realisation's (10 minutes, 150 components:
    measured 0.947, 0.950, 0.953)."""
    grid = {"heading": [0], "hs": [0.2], "tp": [2.0], "pto_damping": [1000.0, 3000.0, 10000.0]}
    common = {
        "rho": 1000,
        "mass": MASS,
        "center_of_gravity": [0, 0, 0],
        "radii_of_gyration": [0.3, 0.3, 0.3],
        "system": {"dofs": ["Heave"], "ptos": [{"dofs": ["Heave", "ground"]}]},
        "grid": grid,
    }
    data = corpus / WAVEBOT
    simulated = _run(
        Study(data=data, analysis="simulate", duration=600, dt=0.05, components=150, **common)
    )
    frequency = _run(Study(data=data, analysis="rao", n_omega=456, **common))
    assert len(set(simulated.seed_used.values.ravel().tolist())) == 1
    ratio = simulated.pto_mean_power.squeeze().values / frequency.pto_mean_power.squeeze().values
    assert np.all(np.abs(ratio - 1) < 0.15)  # one realisation of the sea
    assert ratio.max() / ratio.min() < 1.03  # the same one for every damping: 1.007
    assert float(simulated.pto_damping_best.squeeze()) == 3000.0
    assert simulated.attrs["radiation_model_sweep"].startswith("one radiation model")


# --------------------------------------------------------------------------- YAML, CLI

STUDY = """\
data: waveBotBuoy.out
analysis: rao
rho: 1000
mass: 858.415
center_of_gravity: [0, 0, 0]
radii_of_gyration: [0.3, 0.3, 0.3]
n_omega: 200
system:
  dofs: [Heave]
  ptos: [{{dofs: [Heave, ground], damping: 1000}}]
grid: {{heading: [0], hs: [0.1, 0.2], tp: [2, 3], {sweep}}}
scatter: {{hs: [0.1, 0.2], tp: [2, 3], probability: [[0.4, 0.3], [0.2, 0.1]]}}
"""


@pytest.fixture
def folder(corpus, tmp_path):
    (tmp_path / "waveBotBuoy.out").symlink_to(corpus / WAVEBOT)
    return tmp_path


def test_cli_sweep_prints_the_best_damping_and_report_shows_it(folder):
    """``cummins batch`` of a YAML sweep: the results hold the pto_damping dimension, the
    best damping per sea state and for the site; the end of the output tables them with
    tank-scale powers in W (not 2.1e-02 kW); ``cummins report`` has the sweep's section."""
    (folder / "sweep.yaml").write_text(
        STUDY.format(sweep="pto_damping: [300, 1000, 3000, 10000]"), encoding="utf-8"
    )
    out = folder / "sweep.nc"
    runner = CliRunner()
    result = runner.invoke(
        main, ["batch", str(folder / "sweep.yaml"), "-o", str(out), "--workers", "1"]
    )
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "mean absorbed power 1.085 W to 28.23 W" in text  # W below 1 kW
    assert "Best PTO damping [N s/m] (mean power), heading 0 deg" in text
    assert "│ 0.2 │ 3e+03 (21.4 W) │ 1e+04* (28.2 W) │" in text
    assert "best 3e+03 N s/m, 10.75 W" in text
    with xr.open_dataset(out, engine="h5netcdf") as results:
        assert results.pto_mean_power.dims == ("heading", "hs", "tp", "pto_damping", "pto")
        assert results.pto_damping.attrs["units"] == "N s/m"
        assert results.pto_damping_site_best.values.tolist() == [3000.0]  # per heading
    page = folder / "sweep.html"
    result = runner.invoke(main, ["report", str(out), "-o", str(page)])
    assert result.exit_code == 0, result.output
    html = page.read_text(encoding="utf-8")
    assert "PTO damping sweep" in html and "3e+03 (21.4 W)" in html
    assert "Best single damping for the site: 3e+03 N s/m, 10.75 W" in html


def _refused_in_one_line(folder, text: str, message: str) -> None:
    """The study ``text`` is refused by ``cummins batch`` with exit status 2 and one line
    holding ``message``, before any case runs."""
    (folder / "bad.yaml").write_text(text, encoding="utf-8")
    result = CliRunner().invoke(
        main, ["batch", str(folder / "bad.yaml"), "-o", str(folder / "bad.nc")]
    )
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and message in lines[0], result.output
    assert not (folder / "bad.nc.parts").exists()


@pytest.mark.parametrize(
    ("sweep", "system", "message"),
    [
        ("pto_damping: [300, -1000]", None, "grid.pto_damping: -1000 is negative"),
        ("pto_damping: []", None, "grid.pto_damping: no values (an empty list)"),
        (
            "pto_damping: [300]",
            "system:\n  dofs: [Heave]\n",
            "grid.pto_damping: the study has no PTO to sweep",
        ),
        ("pto_damping: [300]", "", "grid.pto_damping: the study has no PTO to sweep"),
        ("pto_damping: {pto9: [300]}", None, "grid.pto_damping: no PTO 'pto9'; the PTOs are pto1"),
        (
            "pto_stiffness: {a: [1]}, pto_damping: {pto1: [300]}",
            None,
            "grid: pto_damping and pto_stiffness name different PTOs",
        ),
    ],
)
def test_bad_sweeps_are_refused_in_one_line_naming_the_key(folder, sweep, system, message):
    text = STUDY.format(sweep=sweep)
    if system is not None:
        head, _, rest = text.partition("system:\n")
        text = head + system + "grid:" + rest.split("grid:", 1)[1]
    _refused_in_one_line(folder, text, message)


def test_several_ptos_need_the_swept_one_named(corpus):
    """Two PTOs: a plain list is refused (which PTO?), ``{name: [..]}`` sets that one's
    damping and keeps the other's."""
    system = {
        "ptos": [
            {"dofs": ["Heave", "ground"], "damping": 10, "name": "pa"},
            {"dofs": ["Heave", "ground"], "damping": 20, "name": "pb"},
        ]
    }
    grid = {"heading": [0], "hs": [1], "tp": [2]}
    with pytest.raises(StudyError, match=r"grid.pto_damping: the system has 2 PTOs \(pa, pb\)"):
        Study(data="x.out", system=system, grid={**grid, "pto_damping": [1, 2]})
    study = Study(data="x.out", system=system, grid={**grid, "pto_damping": {"pb": [5, 7]}})
    assert study.swept_pto == "pb" and study.dims[-1] == "pto_damping"
    swept = case_system(study.system, study.swept_pto, 7.0, None)
    assert [p.damping for p in swept.ptos] == [10.0, 7.0]


def test_the_example_study_shows_the_sweep(tmp_path):
    """``--example`` shows the sweep key in a comment, and the study it writes still runs
    as before (its case ids do not change: a sweep's values enter only when given)."""
    from cummins.studies.study import Case, example_study_text

    assert "# pto_damping: [" in example_study_text()
    assert "pto_damping" not in Case(180, 2, 8).parameters()
    (tmp_path / "study.yaml").write_text(example_study_text(str(cummins.demo_files() / "tanker.1")))
    assert load_study(tmp_path / "study.yaml").swept_pto is None


def test_limits_with_a_sweep_are_judged_per_damping(corpus):
    """With limits, the damping is a design choice, not a realisation of the sea: the
    operability and the limiting H_s are given per damping (more damping, less heave:
    the limiting H_s grows with it), the axis keeps its units, and the report's
    operability and limiting-H_s figures are drawn."""
    from cummins.cli.html_report import batch_sections
    from cummins.studies.operability import limiting_hs, operability

    study = _study(corpus / WAVEBOT, [300.0, 3000.0, 30000.0], limits={"Heave": "0.05 m"})
    results = _run(study)
    assert results.pto_damping.attrs["units"] == "N s/m"
    op = operability(results)
    assert set(op.dims) == {"heading", "pto_damping"}
    lim = limiting_hs(results).sel(heading=0, tp=2.0)
    assert lim.dims == ("pto_damping",) and bool((lim.diff("pto_damping") > 0).all())
    titles = [s.title for s in batch_sections(results)]
    assert "Operability" in titles and "PTO damping sweep" in titles


# --------------------------------------------------------------------------- a list of cases

LIST_STUDY = {
    "analysis": "rao",
    "rho": 1000,
    "mass": MASS,
    "center_of_gravity": [0, 0, 0],
    "radii_of_gyration": [0.3, 0.3, 0.3],
    "n_omega": 200,
    "system": {"dofs": ["Heave"], "ptos": [{"dofs": ["Heave", "ground"], "damping": 1000}]},
}


def test_a_list_of_cases_carries_its_pto_values_as_a_grid_does(corpus):
    """``cases:`` with ``pto_damping`` (and ``pto_stiffness``) per case — refused as an
    unknown key before — runs each case with its values: its mean power is the grid's at
    the same sea state and values (the same solution, to rounding), a case without them
    runs and is recorded at the PTO's own (1000 N s/m, stiffness 0), the results record
    both per case with the units of the PTO, and the best damping, which needs a grid,
    is said not computed in one attribute instead of failing."""
    data = corpus / WAVEBOT
    grid = {"heading": [0], "hs": [0.1, 0.2], "tp": [2.0, 3.0], "pto_damping": [300.0, 1000.0]}
    reference = _run(Study(data=data, grid=grid, **LIST_STUDY))
    stiff = _run(Study(data=data, grid={**grid, "pto_stiffness": [500.0]}, **LIST_STUDY))
    cases = [
        {"heading": 0, "hs": 0.2, "tp": 2, "pto_damping": 300},
        {"heading": 0, "hs": 0.1, "tp": 3, "pto_damping": 1000, "pto_stiffness": 500},
        {"heading": 0, "hs": 0.2, "tp": 3},  # the PTO's own values
        {"heading": 0, "hs": 0.1, "tp": 2, "pto_damping": 300, "probability": 1},
    ]
    results = _run(Study(data=data, cases=cases, **LIST_STUDY))
    assert results.pto_damping.dims == ("case",)
    assert results.pto_damping.values.tolist() == [300.0, 1000.0, 1000.0, 300.0]
    assert results.pto_stiffness.values.tolist() == [0.0, 500.0, 0.0, 0.0]
    assert results.pto_damping.attrs["units"] == "N s/m"
    assert results.pto_stiffness.attrs["units"] == "N/m"
    expected = [
        reference.sel(hs=0.2, tp=2.0, pto_damping=300.0),
        stiff.sel(hs=0.1, tp=3.0, pto_damping=1000.0, pto_stiffness=500.0),
        reference.sel(hs=0.2, tp=3.0, pto_damping=1000.0),
        reference.sel(hs=0.1, tp=2.0, pto_damping=300.0),
    ]
    for k, one in enumerate(expected):
        np.testing.assert_allclose(
            results.pto_mean_power.isel(case=k).values,
            one.pto_mean_power.squeeze("heading").values,
            rtol=1e-9,
        )
        np.testing.assert_allclose(
            results.significant_amplitude.isel(case=k).values,
            one.significant_amplitude.squeeze("heading").values,
            rtol=1e-9,
        )
    # the stiffness changes the answer: the case ran it, not the grid's 0
    assert (
        abs(
            float(expected[1].pto_mean_power.squeeze())
            / float(reference.pto_mean_power.sel(hs=0.1, tp=3.0, pto_damping=1000.0).squeeze())
            - 1
        )
        > 1e-3
    )
    assert "pto_damping_best" not in results
    assert results.attrs["pto_damping_best_note"].startswith("best PTO damping not computed")


def test_a_list_study_prints_and_reports_what_it_cannot_summarise(folder):
    """``cummins batch`` of a YAML list with ``pto_damping``: exit 0, the best damping's
    note in one line, the report's power table lists each case's damping and says the
    same."""
    text = STUDY.format(sweep="").split("grid:")[0] + (
        "cases:\n"
        "  - {heading: 0, hs: 0.2, tp: 2, pto_damping: 300}\n"
        "  - {heading: 0, hs: 0.2, tp: 2, pto_damping: {pto1: 3000}}\n"
    )
    (folder / "list.yaml").write_text(text, encoding="utf-8")
    out, page = folder / "list.nc", folder / "list.html"
    runner = CliRunner()
    result = runner.invoke(main, ["batch", str(folder / "list.yaml"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    notes = [line for line in result.output.splitlines() if "best PTO damping" in line]
    assert len(notes) == 1 and "the cases are a list" in notes[0], result.output
    result = runner.invoke(main, ["report", str(out), "-o", str(page)])
    assert result.exit_code == 0, result.output
    html = page.read_text(encoding="utf-8")
    assert "best PTO damping not computed: the cases are a list" in html
    assert "<th>pto_damping</th>" in html


@pytest.mark.parametrize(
    ("cases", "system", "message"),
    [
        (
            "[{heading: 0, hs: 1, tp: 2, pto_damping: 300}, "
            "{heading: 0, hs: 1, tp: 2, pto_damping: -1000}]",
            None,
            "cases[1].pto_damping: -1000 is negative",
        ),
        (
            "[{heading: 0, hs: 1, tp: 2}, {heading: 0, hs: 1, tp: 2, pto_damping: 300}]",
            "system:\n  dofs: [Heave]\n",
            "cases[1].pto_damping: the study has no PTO to sweep",
        ),
        (
            "[{heading: 0, hs: 1, tp: 2, pto_damping: 300}]",
            "",
            "cases[0].pto_damping: the study has no PTO to sweep",
        ),
        (
            "[{heading: 0, hs: 1, tp: 2, pto_damping: {pto9: 300}}]",
            None,
            "cases[0].pto_damping: no PTO 'pto9'; the PTOs are pto1",
        ),
        (
            "[{heading: 0, hs: 1, tp: 2, pto_damping: {pto1: [300]}}]",
            None,
            "cases[0].pto_damping: [300] is not a number",
        ),
        (
            "[{heading: 0, hs: 1, tp: 2, pto_damping: {pto1: 3, pto2: 4}}]",
            None,
            "cases[0].pto_damping: name one PTO and its values, e.g. pto_damping: {pto1: value}",
        ),
    ],
)
def test_bad_list_cases_are_refused_in_one_line_naming_the_case(folder, cases, system, message):
    text = STUDY.format(sweep="").split("grid:")[0] + f"cases: {cases}\n"
    if system is not None:
        head, _, rest = text.partition("system:\n")
        text = head + system + "cases:" + rest.split("cases:", 1)[1]
    _refused_in_one_line(folder, text, message)


def test_a_list_with_several_ptos_names_the_one_it_sets():
    """Two PTOs: a case's plain value is refused (which PTO?), ``{name: value}`` sets that
    one (the other keeps its own), a case naming another PTO or one leaving the name out
    beside cases that give it are refused, each naming its case."""
    system = {
        "ptos": [
            {"dofs": ["Heave", "ground"], "damping": 10, "name": "pa"},
            {"dofs": ["Heave", "ground"], "damping": 20, "name": "pb"},
        ]
    }
    sea = {"heading": 0, "hs": 1, "tp": 2}
    with pytest.raises(StudyError, match=r"cases\[0\].pto_damping: the system has 2 PTOs"):
        Study(data="x.out", system=system, cases=[{**sea, "pto_damping": 1}])
    study = Study(data="x.out", system=system, cases=[sea, {**sea, "pto_damping": {"pb": 7}}])
    assert study.swept_pto == "pb"
    assert [c.pto_damping for c in study.cases] == [20.0, 7.0]  # pb's own, then 7
    swept = case_system(study.system, study.swept_pto, study.cases[1].pto_damping, None)
    assert [p.damping for p in swept.ptos] == [10.0, 7.0]
    with pytest.raises(StudyError, match=r"cases\[1\]: names the PTO 'pa', cases\[0\] names 'pb'"):
        Study(
            data="x.out",
            system=system,
            cases=[{**sea, "pto_damping": {"pb": 7}}, {**sea, "pto_stiffness": {"pa": 1}}],
        )
    with pytest.raises(StudyError, match=r"cases\[1\].pto_damping: the system has 2 PTOs .*as the"):
        Study(
            data="x.out",
            system=system,
            cases=[{**sea, "pto_damping": {"pb": 7}}, {**sea, "pto_damping": 8}],
        )
    again = replace(study, name="again")  # dataclasses.replace re-checks the cases: the same
    assert again.swept_pto == "pb" and again.cases == study.cases
