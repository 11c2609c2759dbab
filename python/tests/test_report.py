"""The results saved, drawn and converted (issue 46): ``save(dir)`` writes exactly the
files of the command line's ``--out`` (byte for byte: both come from the presentation
crate ``stiction-report``), ``to_svg()`` its figures, ``to_pandas()`` cycles.csv's
columns, ``to_xarray()`` a map on its grid."""

from __future__ import annotations

import csv
import importlib
import io
import math
import os

import numpy as np
import pytest

import stiction


def _need(module):
    """The optional package a conversion needs: skipped where it is not installed, unless
    STICTION_REQUIRE_CONVERT=1 (CI installs pandas and xarray and sets it)."""
    if os.environ.get("STICTION_REQUIRE_CONVERT") == "1":
        importlib.import_module(module)
    else:
        pytest.importorskip(module)


def _files(folder):
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def _cli_out(cli, tmp_path, scene, *args):
    """The --out folder of `stiction ARGS --scene SCENE --out DIR` (the scene written as
    TOML), as {name: bytes}."""
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml())
    out = tmp_path / "cli"
    p = cli.run(*args, "--scene", path, "--out", out)
    assert p.returncode == 0, p.stderr
    return _files(out)


@pytest.fixture(scope="module")
def fast_switch(paper_switch):
    # the paper's switch, two cycles, in fast mode: curves, contact states, resistance
    return paper_switch.with_values({"cycles": 2, "accuracy": "fast"})


@pytest.fixture(scope="module")
def switch_run(fast_switch):
    return stiction.run(fast_switch)


def test_a_switch_saves_the_command_lines_files_byte_for_byte(cli, tmp_path, fast_switch, switch_run):
    expected = _cli_out(cli, tmp_path, fast_switch, "switch")
    assert sorted(expected) == ["curves.csv", "cycles.csv", "switch.json", "switch.svg"]
    written = switch_run.save(tmp_path / "py")
    assert sorted(p.rsplit("/", 1)[-1] for p in written) == sorted(expected)
    assert _files(tmp_path / "py") == expected
    # the figure alone is the file's
    assert switch_run.to_svg().encode() == expected["switch.svg"]
    assert switch_run.dynamics_svg() is None
    # what the command prints
    p = cli.run("switch", "--scene", tmp_path / "scene.toml")
    assert p.stdout.startswith(switch_run.table())


def test_a_switch_in_time_saves_its_dynamics_plot_too(cli, tmp_path, paper_switch):
    scene = paper_switch.with_values(
        {
            "cycles": 2,
            "accuracy": "fast",
            "points": 40,
            "contact.yield_modulus": "composite",
            "switch.impact_energy": None,
            "switch.k_s": 8.44e9,
            "switch.voltage": 60.0,
            "dynamics.areal_mass": 0.0246,
        }
    )
    expected = _cli_out(cli, tmp_path, scene, "switch")
    assert "dynamics.svg" in expected
    r = stiction.run(scene)
    r.save(tmp_path / "py")
    assert _files(tmp_path / "py") == expected
    assert r.dynamics_svg().encode() == expected["dynamics.svg"]


def test_save_replaces_the_folder_as_the_command_does(tmp_path, switch_run):
    out = tmp_path / "out"
    switch_run.save(out)
    (out / "switch.json").write_text("old")
    switch_run.save(out)
    switch_run.save(tmp_path / "again")
    assert (out / "switch.json").read_bytes() == (tmp_path / "again" / "switch.json").read_bytes()
    assert (out / "switch.json").read_text() != "old"
    # a folder holding anything else is refused, nothing written
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("mine")
    with pytest.raises(stiction.InputError, match="notes.txt"):
        switch_run.save(tmp_path / "other")
    assert sorted(p.name for p in (tmp_path / "other").iterdir()) == ["notes.txt"]


def test_per_cycle_has_cycles_csv_columns_and_values(tmp_path, switch_run):
    switch_run.save(tmp_path)
    text = (tmp_path / "cycles.csv").read_text()
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], [r for r in rows[1:] if r[0] != "elastic"]
    _need("pandas")
    df = switch_run.per_cycle.to_pandas()
    assert list(df.columns) == header
    assert len(df) == len(body) == len(switch_run.cycles)
    # the contact resistance under the hold, cycle by cycle, as cycles.csv writes it
    k = header.index("hold_contact_resistance_ohm")
    for row, got in zip(body, df["hold_contact_resistance_ohm"]):
        want = float(row[k]) if row[k] else math.nan
        assert (math.isnan(want) and math.isnan(got)) or want == got
    assert df["hold_contact_resistance_ohm"].notna().any()
    assert switch_run.per_cycle.hold_contact_resistance.dtype == float
    assert list(df["cycle"]) == [int(r[0]) for r in body]
    # whole numbers stay whole, as cycles.csv writes them
    assert df["cycle"].dtype.kind == "i" and switch_run.per_cycle.cycle.dtype == np.int64
    # the plain table converts column for column
    t = switch_run.loading.to_pandas()
    assert list(t.columns) == switch_run.loading.columns and len(t) == len(switch_run.loading)


def test_a_surface_and_an_asperity_draw_the_command_lines_plot(cli, tmp_path):
    for kind in ("surface", "asperity"):
        plot = tmp_path / f"{kind}.svg"
        p = cli.run(kind, "--plot", plot)
        assert p.returncode == 0, p.stderr
        r = stiction.run(stiction.Scene.paper(kind))
        assert r.to_svg().encode() == plot.read_bytes(), kind
        assert p.stdout.startswith(r.table())


@pytest.fixture(scope="module")
def spring(paper_switch):
    return paper_switch.with_values(
        {"switch.impact_energy": None, "switch.k_s": 8.44e9, "contact.yield_modulus": "composite"}
    )


def test_a_probability_run_saves_all_three_files_of_the_command(cli, tmp_path, spring):
    scatter = "switch.k_s=lognormal(1.25e10,1.3)"
    expected = _cli_out(
        cli, tmp_path, spring, "design", "probability", "--scatter", scatter, "--samples", "12", "--seed", "9",
        "--accuracy", "fast",
    )
    assert sorted(expected) == ["probability.json", "probability.svg", "samples.csv"]
    r = stiction.design_probability(spring, [scatter], samples=12, seed=9, accuracy="fast")
    r.save(tmp_path / "py")
    assert _files(tmp_path / "py") == expected
    assert r.to_svg().encode() == expected["probability.svg"]
    assert r.laws.yield_modulus == "composite"
    # P(stuck by cycle n) converts with its columns
    _need("pandas")
    assert list(r.by_cycle.to_pandas().columns) == r.by_cycle.columns


def test_a_map_saves_the_command_lines_files_and_converts_to_a_grid(cli, tmp_path, spring):
    vary = ["switch.k_s=4e9:4e10:log:3", "surface.sigma_s=5e-9:1.1e-8:lin:2"]
    args = ["design", "map", "--accuracy", "fast"]
    for v in vary:
        args += ["--vary", v]
    expected = _cli_out(cli, tmp_path, spring, *args)
    m = stiction.design_map(spring, vary, accuracy="fast")
    m.save(tmp_path / "py")
    assert _files(tmp_path / "py") == expected
    _need("xarray")
    ds = m.to_xarray()
    assert ds["pull_out_ratio"].dims == ("switch.k_s", "surface.sigma_s")
    assert ds["pull_out_ratio"].shape == (3, 2)
    assert np.allclose(ds["switch.k_s"].values, [4e9, 4e9 * 10**0.5, 4e10])
    assert ds["switch.k_s"].attrs["units"] == "Pa/m" and ds["surface.sigma_s"].attrs["units"] == "m"
    assert ds["largest_pull_out_pa"].attrs["units"] == "Pa"
    # point i of the map is cell i of the grid (the first field varies slowest)
    for p in m.points:
        i, j = divmod(p.index, 2)
        assert ds["pull_out_ratio"].values[i, j] == p.pull_out_ratio
        assert ds["status"].values[i, j] == p.status
    # every column of map.csv is a variable (or a coordinate)
    header = expected["map.csv"].decode().splitlines()[0].split(",")
    assert set(header) <= set(ds.variables), set(header) - set(ds.variables)
    assert ds["cycles_to_accommodation"].attrs["units"] == "count"


def test_a_map_over_words_has_the_words_as_coordinate(spring):
    _need("xarray")
    m = stiction.design_map(spring, ["contact.adhesion_law=maugis_kim,dmt"], accuracy="fast")
    ds = m.to_xarray()
    assert list(ds["contact.adhesion_law"].values) == ["maugis_kim", "dmt"]
    assert ds["pull_out_ratio"].dims == ("contact.adhesion_law",)


def test_a_contact_law_saves_the_command_lines_files(cli, tmp_path, paper_switch):
    scene = paper_switch.with_values({"accuracy": "fast", "contact.yield_modulus": "composite"})
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml())
    out = tmp_path / "cli"
    p = cli.run("law", "--scene", path, "--d-min", "7.6e-9:9.2e-9:5", "--out", out)
    assert p.returncode == 0, p.stderr
    # the same scene file (law.json names the file its law came from)
    r = stiction.tabulate_law(stiction.load_scene(path), d_min="7.6e-9:9.2e-9:5")
    r.save(tmp_path / "py")
    got, want = _files(tmp_path / "py"), _files(out)
    assert sorted(got) == ["law.csv", "law.json", "law.svg"]
    assert got == want
    assert r.to_svg().encode() == want["law.svg"]


def test_a_topography_saves_the_command_lines_files(cli, tmp_path):
    rng = np.random.default_rng(3)
    heights = tmp_path / "heights.txt"
    rows = "\n".join(" ".join(f"{v:.4f}" for v in row) for row in rng.normal(0, 5, (48, 48)))
    heights.write_text("# spacing = 20 nm\n# height_unit = nm\n" + rows + "\n")
    p = cli.run("topography", heights, "--out", tmp_path / "cli")
    assert p.returncode == 0, p.stderr
    r = stiction.topography(heights)
    r.save(tmp_path / "py")
    want = _files(tmp_path / "cli")
    assert sorted(want) == ["surface.toml", "topography.json", "topography.svg"]
    assert _files(tmp_path / "py") == want
    assert r.to_svg().encode() == want["topography.svg"]


def test_a_result_without_an_out_folder_says_so(switch_run):
    r = stiction.run(stiction.Scene.paper("surface"))
    with pytest.raises(stiction.InputError, match="no --out folder"):
        r._report.save("/nonexistent")
    assert switch_run == switch_run and r.to_svg().startswith("<svg")


def test_a_threshold_and_a_curve_print_the_command_lines_table(cli, paper_switch):
    # results whose commands print a table only: table() is that table, to_svg() says why not
    t = stiction.design_threshold(paper_switch, "surface.sigma_s", 2e-9, 1e-7, accuracy="fast")
    p = cli.run(
        "design", "threshold", "--vary", "surface.sigma_s", "--from", "2e-9", "--to", "1e-7",
        "--accuracy", "fast", "--format", "table",
    )
    assert p.returncode == 0, p.stderr
    assert t.table() and p.stdout == t.table()
    m = stiction.md_curve(0.7, points=40)
    p = cli.run("md", "--lambda", "0.7", "--points", "40", "--format", "table")
    assert p.returncode == 0, p.stderr
    assert m.table() and p.stdout == m.table()
    for r in (t, m):
        with pytest.raises(stiction.InputError, match="no figure"):
            r._report.to_svg()
        assert not hasattr(r, "to_svg") and not hasattr(r, "save")
