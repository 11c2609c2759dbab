"""Calibration of eq 13: curves made by the model with the paper's constants are fitted back
from a perturbed start, the same as by `stiction calibrate` on the same file."""

from __future__ import annotations

import numpy as np
import pytest

import stiction

PAPER_C1 = [0.22, 0.6242, 0.092]
PAPER_C2 = [10.0, 10.0, 5.0]


@pytest.fixture(scope="module")
def fe_columns():
    """FE-like curves of the paper's Ru asperity: loading and unloading at 17, 34, 51 nm."""
    a = stiction.Asperity(stiction.Scene.paper("asperity"))
    cols = {"delta_max_m": [], "delta_m": [], "force_n": [], "branch": []}
    for dmax in (17e-9, 34e-9, 51e-9):
        loading = np.linspace(0.1 * dmax, dmax, 12)
        _, jump_out = a.jumps(dmax)
        unloading = np.linspace(dmax, jump_out + 0.05 * (dmax - jump_out), 12)
        for branch, delta, force in (
            ("loading", loading, a.force(loading)),
            ("unloading", unloading, a.force(unloading, dmax, "retract")),
        ):
            cols["delta_max_m"] += [dmax] * len(delta)
            cols["delta_m"] += list(delta)
            cols["force_n"] += list(force)
            cols["branch"] += [branch] * len(delta)
    return cols


@pytest.fixture(scope="module")
def start_scene():
    s = stiction.Scene.paper("asperity")
    s.set("contact.effective_radius.c1", [0.3, 0.5, 0.12])
    s.set("contact.effective_radius.c2", [8.0, 12.0, 4.0])
    return s


def test_the_fit_recovers_the_papers_constants(fe_columns, start_scene):
    r = stiction.calibrate(start_scene, fe_columns, fit="all")
    assert isinstance(r, stiction.CalibrationResult)
    assert r.converged
    assert np.allclose(r.c1, PAPER_C1, rtol=1e-4)
    assert np.allclose(r.c2, PAPER_C2, rtol=1e-3)
    assert r.data_points == 72 and len(r.points) == 72
    assert np.allclose(r.points.model_force, r.points.force, rtol=1e-6, atol=1e-12)
    assert "[contact.effective_radius]" in r.scene_fragment


def test_the_fit_is_the_command_lines(cli, tmp_path, fe_columns, start_scene):
    csv = tmp_path / "fe.csv"
    rows = zip(*(fe_columns[c] for c in ("delta_max_m", "delta_m", "force_n", "branch")))
    csv.write_text("delta_max_m,delta_m,force_n,branch\n" + "".join(f"{float(a)!r},{float(b)!r},{float(c)!r},{d}\n" for a, b, c, d in rows))
    scene = tmp_path / "start.toml"
    scene.write_text(start_scene.to_toml())
    expected = cli.json("calibrate", "--fe", csv, "--scene", scene, "--fit", "all", "--format", "json")
    from_file = stiction.calibrate(scene, csv, fit="all")
    from_columns = stiction.calibrate(start_scene, fe_columns, fit="all")
    assert list(from_file.c1) == expected["c1"] and list(from_file.c2) == expected["c2"]
    assert list(from_columns.c1) == expected["c1"]
    assert from_file.residual_rms_n == expected["residual_rms_n"]
    assert from_file.fe_file == str(csv)


def test_bad_data_and_selections_are_input(tmp_path, start_scene, fe_columns):
    bad = tmp_path / "bad.csv"
    bad.write_text("delta_max_m,delta_m,force_n,branch\n2e-8,1e-8,x,loading\n")
    with pytest.raises(stiction.InputError, match="line 2, column force_n"):
        stiction.calibrate(start_scene, bad)
    with pytest.raises(stiction.InputError, match="fit"):
        stiction.calibrate(start_scene, fe_columns, fit="c3")
    with pytest.raises(stiction.InputError, match="branch"):
        stiction.calibrate(start_scene, {"delta_max_m": [1e-8], "delta_m": [1e-9], "force_n": [1e-6]})
    # columns of unequal length would be cut to the shortest and misaligned (a fit that
    # "converges" on wrong rows): refused with each column's length
    short = {k: list(v) for k, v in fe_columns.items()}
    short["force_n"] = short["force_n"][:-1]
    with pytest.raises(stiction.InputError, match="differ in length"):
        stiction.calibrate(start_scene, short)
