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
    got["from"] = got.pop("from_")
    got.pop("warnings")
    assert got == expected
    assert t.critical_value == pytest.approx(4.494e-8, rel=1e-3) and t.free_side == "above"
    assert t.scan.status[0] == "ok" and t.scan.value[0] == 2e-9


def test_guards_of_the_points_are_counted(paper_switch):
    soft = paper_switch.with_values({"contact.yield_stress": 3e8})
    m = stiction.design_map(soft, ["surface.sigma_s=3e-9:5e-8:log:2"], accuracy="fast")
    assert not m.validity.holds
    assert {w.code for w in m.warnings} >= {"adhesion_yields_asperity", "beyond_fit_range"}
    assert all(w.message.startswith("2 of 2 design points") for w in m.warnings)
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
