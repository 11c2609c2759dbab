"""The contact law for FE codes: tabulated by the package exactly as `stiction law`
tabulates it, evaluated (vectorised) exactly as `stiction law eval` evaluates it."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

import stiction

GRID = "9e-9:5e-9:6"


def test_the_tabulation_is_the_command_lines_law_json(cli, tmp_path, law_file):
    out = tmp_path / "law"
    p = cli.run("law", "--d-min", GRID, "--points", "24", "--out", out)
    assert p.returncode == 0, p.stderr
    assert law_file.read_text() == (out / "law.json").read_text()


def test_the_tabulation_summary():
    r = stiction.tabulate_law(stiction.Scene.paper("switch"), d_min=GRID, points=24)
    assert isinstance(r, stiction.LawResult) and isinstance(r.law, stiction.ContactLaw)
    assert r.branches == 6 and r.histories.rule == f"uniform {GRID}"
    assert np.allclose(r.law.d_min_grid, np.linspace(5e-9, 9e-9, 6), rtol=1e-12)
    assert r.summary.d_min.shape == (6,) and (r.summary.pull_out_pressure < 0).all()
    assert r.law.length_scale == r.sigma_s == 7.78e-9
    # as data: the summary alone, JSON-ready (the law's own JSON is r.law.to_json())
    import json

    d = r.to_dict()
    assert "law" not in d and json.loads(json.dumps(d))["branches"] == 6


POINTS = [
    # d, d_min (None: virgin), path
    (10e-9, 8.44e-9, "retract"),
    (10e-9, 8.44e-9, "approach"),
    (6.5e-9, 6e-9, "retract"),
    (12e-9, None, "approach"),
    (7e-9, 8e-9, "retract"),  # below d_min: the history deepens
    (30e-9, 5.5e-9, "retract"),
]


@pytest.mark.parametrize("d, d_min, path", POINTS)
def test_evaluate_equals_law_eval(cli, law_file, d, d_min, path):
    args = ["law", "eval", "--law", law_file, "--d", repr(d), "--path", path, "--format", "json"]
    if d_min is not None:
        args += ["--d-min", repr(d_min)]
    expected = cli.json(*args)
    e = stiction.ContactLaw.load(law_file).evaluate(d, d_min, path)
    assert e.pressure == expected["pressure"]
    assert e.tangent == expected["tangent"]
    assert e.d_min == expected["d_min"]
    assert str(e.path) == expected["path"]


def test_evaluate_is_vectorised(law_file):
    law = stiction.ContactLaw.load(law_file)
    rng = np.random.default_rng(7)
    d = rng.uniform(5e-9, 25e-9, 500).reshape(20, 25)
    d_min = rng.uniform(5e-9, 9e-9, 500).reshape(20, 25)
    for path in ("approach", "retract"):
        v = law.evaluate(d, d_min, path)
        assert v.pressure.shape == (20, 25) and v.retract.dtype == bool
        for i in range(0, 500, 37):
            s = law.evaluate(float(d.flat[i]), float(d_min.flat[i]), path)
            assert (v.pressure.flat[i], v.tangent.flat[i], v.d_min.flat[i]) == (s.pressure, s.tangent, s.d_min)
    # one path per point, and a virgin surface by default
    paths = np.where(np.arange(500) % 2 == 0, "approach", "retract").reshape(20, 25)
    mixed = law.evaluate(d, d_min, paths)
    assert mixed.pressure[0, 1] == law.evaluate(d[0, 1], d_min[0, 1], "retract").pressure
    virgin = law.evaluate(d[0])
    assert np.array_equal(virgin.pressure, law.evaluate(d[0], math.inf).pressure)
    # deepening: d below d_min is the virgin envelope, the history becomes d
    deep = law.evaluate([6e-9], [8e-9], "retract")
    assert deep.d_min[0] == 6e-9 and deep.path[0] == "approach"
    assert deep.pressure[0] == law.virgin_pressure(6e-9)[0]


def test_follow_walks_a_history(law_file):
    law = stiction.ContactLaw.load(law_file)
    d = np.concatenate([np.linspace(20e-9, 6e-9, 30), np.linspace(6e-9, 20e-9, 30)])
    e, state = law.follow(d)
    assert e.d_min[-1] == 6e-9 and state["d_min"] == 6e-9 and state["retract"]
    # the retraction follows the retract branch of the deepest point
    back = law.evaluate(d[30:], 6e-9, "retract")
    assert np.array_equal(e.pressure[31:], back.pressure[1:])
    # the state as returned continues the walk; a key it does not have (`path` for
    # `retract`) would be ignored and the law followed from another history: refused
    first, mid = law.follow(d[:30])
    rest, _ = law.follow(d[30:], mid)
    assert np.array_equal(np.concatenate([first.pressure, rest.pressure]), e.pressure)
    with pytest.raises(stiction.InputError, match="path"):
        law.follow(1e-8, {"d_min": 6e-9, "path": "retract"})


def test_laws_round_trip_bit_for_bit(tmp_path, law_file):
    law = stiction.ContactLaw.load(law_file)
    law.save(tmp_path / "again.json")
    assert (tmp_path / "again.json").read_text() == law_file.read_text()
    copy = pickle.loads(pickle.dumps(law))
    assert copy.to_json() == law.to_json()
    assert stiction.ContactLaw.from_json(law.to_json()).d_min_range == law.d_min_range


def test_law_errors(tmp_path, law_file):
    law = stiction.ContactLaw.load(law_file)
    with pytest.raises(stiction.InputError, match="path"):
        law.evaluate(1e-8, 8e-9, "sideways")
    with pytest.raises(stiction.InputError, match="d_min"):
        law.evaluate([1e-8, 2e-8], [8e-9, 8e-9, 8e-9])
    with pytest.raises(stiction.StictionError):
        law.evaluate(1e-9, 8e-9)  # below every tabulated history
    (tmp_path / "x.json").write_text("{}")
    with pytest.raises(stiction.InputError):
        stiction.ContactLaw.load(tmp_path / "x.json")
    with pytest.raises(stiction.InputError, match="asperity scene"):
        stiction.tabulate_law(stiction.Scene.paper("asperity"))
    with pytest.raises(stiction.InputError, match="tolerance"):
        stiction.tabulate_law(stiction.Scene.paper("switch"), tolerance=1.0)
