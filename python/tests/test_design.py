"""Design thresholds and maps: the command line's, to the byte; shards and their merge; the
same map on a Dask cluster of worker processes (and on a process pool)."""

from __future__ import annotations

import json
import os
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import stiction

# a spring-driven switch: 2 x 3 points that close, do not close, or leave the domain
VARY = ["switch.voltage=20:3000:log:3", "surface.sigma_s=3e-9:5e-8:log:2"]


@pytest.fixture(scope="module")
def spring_scene():
    return stiction.Scene.paper("switch").with_values({"switch.impact_energy": None, "switch.k_s": 1e10})


@pytest.fixture(scope="module")
def cli_map(cli, spring_scene, tmp_path_factory):
    d = tmp_path_factory.mktemp("cli")
    scene = d / "spring.toml"
    scene.write_text(spring_scene.to_toml())
    out = d / "map"
    args = ["design", "map", "--scene", scene, "--accuracy", "fast", "--out", out]
    for v in VARY:
        args += ["--vary", v]
    p = cli.run(*args)
    assert p.returncode == 0, p.stderr
    return {name: (out / name).read_text() for name in ("map.json", "map.csv", "map.svg")}


@pytest.fixture(scope="module")
def local_map(spring_scene):
    return stiction.design_map(spring_scene, VARY, accuracy="fast")


def test_the_map_is_the_command_lines(cli_map, local_map):
    assert local_map.to_json() == cli_map["map.json"]
    assert local_map.to_csv() == cli_map["map.csv"]
    assert local_map.to_svg() == cli_map["map.svg"]


def test_map_points_are_typed(local_map):
    m = local_map
    assert isinstance(m, stiction.DesignMap) and len(m.points) == 6
    statuses = [p.status for p in m.points]
    assert statuses == ["does_not_close", "does_not_close", "ok", "ok", "out_of_domain", "out_of_domain"]
    ok = m.points[2]
    assert isinstance(ok, stiction.MapPoint)
    assert ok.closes is True and ok.sticks is True and ok.pull_out_ratio > 1
    assert m.points[0].closes is False and m.points[0].pull_out_ratio == 0.0 and m.points[0].sticks is False
    assert m.points[4].pull_out_ratio is None and "switch.impact_energy" in m.points[4].detail
    assert np.array_equal(m.column("pull_out_ratio")[:4], [p.pull_out_ratio for p in m.points[:4]])
    assert np.isnan(m.column("pull_out_ratio")[4])
    assert m.values_of("surface.sigma_s").tolist() == [3e-9, 5e-8] * 3
    assert json.loads(m.to_json())["points"][2]["pull_out_ratio"] == ok.pull_out_ratio


def test_the_contract_example_needs_a_spring_driven_scene(paper_switch, spring_scene):
    with pytest.raises(stiction.InputError, match="scene's drive"):
        stiction.design_map(paper_switch, ["switch.k_s=1e9:1e11:log:8"], accuracy="fast")
    m = stiction.design_map(spring_scene, "switch.k_s=1e9:1e11:log:3", accuracy="fast")
    assert [p.values["switch.k_s"] for p in m.points][::2] == [1e9, 1e11]
    assert all(p.closes and p.sticks for p in m.points)


def test_bad_grids_are_input(paper_switch):
    with pytest.raises(stiction.InputError, match="FROM:TO:lin|log:N"):
        stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log"])
    with pytest.raises(stiction.InputError, match="known field"):
        stiction.design_map(paper_switch, ["surface.sigma=2e-9:1e-7:log:3"])
    with pytest.raises(stiction.InputError, match="shard"):
        stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:3"], shard="3/2")


def test_shards_merge_into_the_whole_map(tmp_path, spring_scene, local_map):
    parts = [stiction.design_map(spring_scene, VARY, accuracy="fast", shard=f"{k}/2") for k in (1, 2)]
    assert [len(p.points) for p in parts] == [3, 3] and parts[0].shard["k"] == 1
    assert stiction.design_merge(parts).to_json() == local_map.to_json()
    for i, p in enumerate(parts):
        p.save(tmp_path / f"part-{i}")
    merged = stiction.design_merge([tmp_path / "part-1" / "map.json", tmp_path / "part-0" / "map.json"])
    assert merged.to_json() == local_map.to_json()
    assert stiction.read_map(tmp_path / "part-0" / "map.json").to_json() == parts[0].to_json()


def test_the_threshold_is_the_command_lines(cli, paper_switch):
    t = stiction.design_threshold(paper_switch, "surface.sigma_s", 2e-9, 1e-7, accuracy="fast")
    expected = cli.json(
        "design", "threshold", "--vary", "surface.sigma_s", "--from", "2e-9", "--to", "1e-7",
        "--accuracy", "fast", "--format", "json",
    )
    got = t.to_dict()
    got.pop("warnings")
    assert got == expected
    assert t.critical_value == pytest.approx(4.494e-8, rel=1e-3) and t.free_side == "above"
    assert t.laws.yield_modulus == "as_printed" and t.scene["contact"]["reload"] == "as_printed"
    assert t.scan.status[0] == "ok" and t.scan.value[0] == 2e-9


def test_guards_of_the_points_are_counted(paper_switch):
    soft = paper_switch.with_values({"contact.yield_stress": 3e8})
    m = stiction.design_map(soft, ["surface.sigma_s=3e-9:5e-8:log:2"], accuracy="fast")
    assert not m.validity.holds
    assert {w.code for w in m.warnings} >= {"adhesion_yields_asperity", "beyond_fit_range"}
    # the validity guards at both points (estimate_above_target, a note, may come from one)
    invalid = [w for w in m.warnings if w.code in {"adhesion_yields_asperity", "beyond_fit_range"}]
    assert len(invalid) == 2 and all(w.message.startswith("2 of 2 design points") for w in invalid)
    assert all(p.validity_holds is False for p in m.points)


# ---------------------------------------------------------------- on a cluster


@pytest.fixture(scope="module")
def dask_client():
    if os.environ.get("STICTION_REQUIRE_DASK") == "1":
        import dask.distributed  # noqa: F401  (CI installs it: a missing one fails)
    distributed = pytest.importorskip("dask.distributed")
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def test_the_dask_map_is_the_command_lines(dask_client, spring_scene, cli_map, local_map):
    assert len(dask_client.scheduler_info()["workers"]) == 2
    m = stiction.design_map(spring_scene, VARY, accuracy="fast", client=dask_client)
    assert m.to_json() == cli_map["map.json"]
    assert m.to_csv() == cli_map["map.csv"]
    assert m == local_map


def test_the_dask_map_counts_the_workers_guards(dask_client, paper_switch):
    soft = paper_switch.with_values({"contact.yield_stress": 3e8})
    vary = ["surface.sigma_s=3e-9:5e-8:log:2"]
    here = stiction.design_map(soft, vary, accuracy="fast")
    there = stiction.design_map(soft, vary, accuracy="fast", client=dask_client)
    assert there.to_json() == here.to_json()
    assert [w.code for w in there.warnings] == [w.code for w in here.warnings]
    assert there.validity == here.validity


def test_a_shard_on_dask_and_a_process_pool(dask_client, spring_scene, local_map):
    part = stiction.design_map(spring_scene, VARY, accuracy="fast", client=dask_client, shard="2/2")
    assert part.to_json() == stiction.design_map(spring_scene, VARY, accuracy="fast", shard="2/2").to_json()
    with ProcessPoolExecutor(2) as pool:
        m = stiction.design_map(spring_scene, VARY, accuracy="fast", client=pool)
    assert m.to_json() == local_map.to_json()


def test_threshold_with_a_resistance_requirement_reports_the_window():
    """`require` as `--require`: the design window lies between the resistance crossing
    (more voltage, lower resistance) and the stiction crossing (free below)."""
    s = stiction.Scene.paper("switch").with_values(
        {
            "switch.impact_energy": None,
            "switch.k_s": 3e11,
            "switch.voltage": 300.0,
            "contact.yield_modulus": "composite",
        }
    )
    t = stiction.design_threshold(s, "switch.voltage", 100.0, 500.0, accuracy="fast",
                                  require="contact_resistance<4e-6")
    req = t.requirement
    assert len(req["crossings"]) == 1
    lo, hi = req["window"][0]
    assert lo == pytest.approx(req["crossings"][0]["value"], rel=1e-3)
    assert hi == pytest.approx(t.critical_value, rel=1e-3)


# ---------------------------------------------------------------- laws as an axis

LAW_VARY = ["contact.plasticity_law=etsion_kadin,kogut_etsion", "switch.k_s=5e9:4e10:log:3"]


@pytest.fixture(scope="module")
def law_scene(spring_scene):
    """The spring-driven switch with E* in eq 1, where the paper's spring is near the
    stiction boundary and the two plasticity laws put it on either side."""
    return spring_scene.with_values({"contact.yield_modulus": "composite"})


@pytest.fixture(scope="module")
def law_map(law_scene):
    return stiction.design_map(law_scene, LAW_VARY, accuracy="fast")


def test_a_law_axis_returns_the_words_and_is_the_command_lines(cli, law_scene, law_map, tmp_path):
    m = law_map
    assert [p.values["contact.plasticity_law"] for p in m.points] == ["etsion_kadin"] * 3 + ["kogut_etsion"] * 3
    assert m.values_of("contact.plasticity_law").tolist() == ["etsion_kadin"] * 3 + ["kogut_etsion"] * 3
    assert m.values_of("switch.k_s").dtype == float
    assert m.grid["axes"][0] == {"field": "contact.plasticity_law", "words": ["etsion_kadin", "kogut_etsion"], "n": 2}
    scene = tmp_path / "spring.toml"
    scene.write_text(law_scene.to_toml())
    out = tmp_path / "map"
    p = cli.run("design", "map", "--scene", scene, "--accuracy", "fast", "--out", out,
                "--vary", LAW_VARY[0], "--vary", LAW_VARY[1])
    assert p.returncode == 0, p.stderr
    assert m.to_json() == (out / "map.json").read_text()
    assert m.to_csv() == (out / "map.csv").read_text()
    assert m.to_svg() == (out / "map.svg").read_text()


def test_a_law_axis_point_is_the_single_law_maps(law_scene, law_map):
    for w, law in enumerate(["etsion_kadin", "kogut_etsion"]):
        single = stiction.design_map(law_scene.with_values({"contact.plasticity_law": law}),
                                     LAW_VARY[1], accuracy="fast")
        for j, p in enumerate(single.points):
            q = law_map.points[3 * w + j]
            assert q.pull_out_ratio == p.pull_out_ratio and q.sticks == p.sticks
            assert q.values["switch.k_s"] == p.values["switch.k_s"]
    # Kogut-Etsion pulls out harder: at the middle spring one law is free, the other sticks
    r = law_map.column("pull_out_ratio")
    assert (r[3:] > r[:3]).all() and r[1] < 1 < r[4]


def test_an_unknown_law_is_input_naming_the_word(law_scene):
    with pytest.raises(stiction.InputError, match="kogut_etsoin") as e:
        stiction.design_map(law_scene, ["contact.plasticity_law=etsion_kadin,kogut_etsoin"])
    assert "etsion_kadin, kogut_etsion, adhesion_coupled, elastic" in str(e.value)
    with pytest.raises(stiction.InputError, match="takes numbers"):
        stiction.design_map(law_scene, ["switch.k_s=soft,stiff"])


def test_a_law_axis_on_a_process_pool_and_its_shards(law_scene, law_map):
    with ProcessPoolExecutor(2) as pool:
        m = stiction.design_map(law_scene, LAW_VARY, accuracy="fast", client=pool)
    assert m.to_json() == law_map.to_json()
    parts = [stiction.design_map(law_scene, LAW_VARY, accuracy="fast", shard=f"{k}/2") for k in (1, 2)]
    assert stiction.design_merge(parts).to_json() == law_map.to_json()
    other = stiction.design_map(law_scene, ["contact.plasticity_law=etsion_kadin,elastic", LAW_VARY[1]],
                                accuracy="fast", shard="2/2")
    with pytest.raises(stiction.InputError, match="the words of contact.plasticity_law"):
        stiction.design_merge([parts[0], other])


def test_the_dask_map_carries_the_words(dask_client, law_scene, law_map):
    m = stiction.design_map(law_scene, LAW_VARY, accuracy="fast", client=dask_client)
    assert m.to_json() == law_map.to_json()


def test_save_writes_the_folder_whole_and_never_through_a_link_or_into_a_fifo(tmp_path, local_map):
    # as the command's --out (the same writer): the folder may hold only the command's
    # files, so a name held by a symbolic link or a FIFO is refused before anything is
    # written (the link's target untouched); an earlier run's files are replaced whole
    import os

    out = tmp_path / "out"
    out.mkdir()
    target = tmp_path / "precious.txt"
    target.write_text("precious")
    os.symlink(target, out / "map.json")
    with pytest.raises(stiction.InputError, match="map.json"):
        local_map.save(out)
    assert target.read_text() == "precious" and not (out / "map.csv").exists()
    fifo_dir = tmp_path / "fifo"
    fifo_dir.mkdir()
    os.mkfifo(fifo_dir / "map.csv")
    with pytest.raises(stiction.InputError, match="map.csv"):
        local_map.save(fifo_dir)
    assert sorted(p.name for p in fifo_dir.iterdir()) == ["map.csv"]
    fine = tmp_path / "fine"
    fine.mkdir()
    (fine / "map.json").write_text("old")
    local_map.save(fine)
    assert (fine / "map.json").read_text() == local_map.to_json()
    assert sorted(p.name for p in fine.iterdir()) == ["map.csv", "map.json", "map.svg"]
    # the base scene's modelling choices, as every result states them
    assert local_map.laws.yield_modulus == local_map.scene["contact"]["yield_modulus"]
    assert local_map.laws.adhesion == "maugis_kim" and "laws" not in local_map.to_dict()


def test_a_probability_run_on_a_cluster_is_the_local_run(dask_client, paper_switch):
    # issue 42: the probability run takes a client like the map; its samples run on the
    # workers and the run is the local one, byte for byte
    s = paper_switch.with_values({"contact.yield_modulus": "composite"})
    scatter = ["surface.sigma_s=lognormal(7.78e-9,1.1)"]
    here = stiction.design_probability(s, scatter, samples=8, seed=3, accuracy="fast")
    there = stiction.design_probability(s, scatter, samples=8, seed=3, accuracy="fast", client=dask_client)
    assert there.to_json() == here.to_json()
    assert [w.code for w in there.warnings] == [w.code for w in here.warnings]


def test_a_checked_probability_and_map_on_a_cluster_equal_the_local_checks(dask_client, paper_switch):
    s = paper_switch.with_values({"contact.yield_modulus": "composite", "model_form": "check"})
    scatter = ["surface.sigma_s=lognormal(7.78e-9,1.1)"]
    here = stiction.design_probability(s, scatter, samples=6, seed=1, accuracy="fast", exact=False)
    there = stiction.design_probability(s, scatter, samples=6, seed=1, accuracy="fast", exact=False, client=dask_client)
    assert here.model_form is not None and len(here.model_form["runs"]) == 8
    for key in ("summary", "accuracy"):
        assert there.model_form[key] == here.model_form[key]
    assert list(there.model_form["stiction_probability_range"]) == list(here.model_form["stiction_probability_range"])
    assert [r["stiction_probability"] for r in there.model_form["runs"]] == [
        r["stiction_probability"] for r in here.model_form["runs"]
    ]
    lo, hi = here.model_form["stiction_probability_range"]
    assert 0.0 <= lo <= hi <= 1.0
    vary = ["surface.sigma_s=3e-9:5e-8:log:2"]
    m_here = stiction.design_map(s, vary, accuracy="fast")
    m_there = stiction.design_map(s, vary, accuracy="fast", client=dask_client)
    assert list(m_here.model_form["share_sticking"]) == list(m_there.model_form["share_sticking"])
    assert len(m_here.model_form["combinations"]) == 8


GOLD_LIKE = {
    # the QA's gold-like film (repro R2 of 2026-11-28): adhesion alone yields its
    # asperities, so every sample lies outside the model's validity under etsion_kadin
    "cycles": 3,
    "contact": {
        "youngs_modulus": 81178081745.26855, "yield_stress": 228848166.40098476,
        "poisson_ratio": 0.25059211185696706, "radius": 8.444083683934808e-06,
        "work_of_adhesion": 0.7697122983558029, "z0": 3.8213241138894935e-10,
        "counter": "same", "adhesion_law": "maugis_kim", "plasticity_law": "etsion_kadin",
        "yield_modulus": "as_printed", "reload": "as_printed",
    },
    "surface": {"sigma_s": 7.268982457521034e-09, "asperity_density": 6028195558853.958},
    "switch": {
        "d0": 4.484554620234818e-07, "t_d": 4.97310750554912e-07, "epsilon_r": 3.5714627715423752,
        "film_thickness": 1.612725346157318e-06, "impact_energy": 0.010124400610215594,
        "contact_area_fraction": 0.9467404331859421,
    },
}


def test_samples_outside_validity_still_answer_a_probability():
    # issue 43: every sample outside validity used to give None; the answer over all
    # samples is a number, and count_outside_validity makes it the headline
    scatter = ["surface.sigma_s=lognormal(7.27e-9,1.1)"]
    apart = stiction.design_probability(GOLD_LIKE, scatter, samples=6, accuracy="fast", exact=False)
    assert apart.stiction_probability is None
    assert apart.outside_validity == 6
    p = apart.all_samples["stiction"]["probability"]
    assert isinstance(p, float) and 0.0 <= p <= 1.0
    counted = stiction.design_probability(GOLD_LIKE, scatter, samples=6, accuracy="fast", exact=False,
                                          count_outside_validity=True)
    assert counted.stiction_probability == p
    assert counted.count_outside_validity is True
    with pytest.raises(stiction.InputError, match="count_outside_validity"):
        stiction.design_probability(GOLD_LIKE, scatter, samples=6, count_outside_validity="yes")


def test_a_dimensionless_field_has_the_unit_dash(paper_switch):
    # issue 46: ThresholdResult.unit was None for a dimensionless field
    t = stiction.design_threshold(paper_switch, "switch.contact_area_fraction", 0.5, 1.0, accuracy="fast")
    assert t.unit == "-"
    assert stiction.design_threshold(paper_switch, "surface.sigma_s", 2e-9, 1e-7, accuracy="fast").unit == "m"
