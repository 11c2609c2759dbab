"""The probability of stiction under process scatter (``stiction.design_probability``):
the command line's files to the byte, typed results with numpy columns, the exact
single-field answer against the lognormal CDF at the critical stiffness, shards merged
against one run, and refusals that name the field.

The scene is the paper's switch driven by a spring (K_s = 8.44e9 Pa/m), eq 1 read
"composite", at most 3 cycles, fast mode: its critical K_s is about 1.3e10 Pa/m
(docs/design.md), so a lognormal K_s around 1.25e10 sticks about half the time.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import stiction

SPRING = "switch.k_s=lognormal(1.25e10,1.3)"
TWO = [SPRING, "contact.work_of_adhesion=lognormal(0.5,1.2)"]
CORRELATE = "switch.k_s,contact.work_of_adhesion=-0.3"


@pytest.fixture(scope="module")
def spring_scene():
    return stiction.Scene.paper("switch").with_values(
        {
            "switch.impact_energy": None,
            "switch.k_s": 8.44e9,
            "contact.yield_modulus": "composite",
            "cycles": 3,
        }
    )


@pytest.fixture(scope="module")
def one_field(spring_scene):
    return stiction.design_probability(spring_scene, SPRING, samples=30, seed=5, accuracy="fast")


@pytest.fixture(scope="module")
def two_fields(spring_scene):
    return stiction.design_probability(spring_scene, TWO, samples=12, seed=9, correlate=CORRELATE, accuracy="fast")


def _lognormal_cdf(x: float, median: float, factor: float) -> float:
    z = math.log(x / median) / math.log(factor)
    return 0.5 * (1.0 + math.erf(z / math.sqrt(2.0)))


def test_the_files_are_the_command_lines(cli, spring_scene, two_fields, one_field, tmp_path):
    scene = tmp_path / "spring.toml"
    scene.write_text(spring_scene.to_toml())
    out = tmp_path / "prob"
    args = ["design", "probability", "--scene", scene, "--accuracy", "fast", "--samples", "12", "--seed", "9"]
    for s in TWO:
        args += ["--scatter", s]
    p = cli.run(*args, "--correlate", CORRELATE, "--out", out)
    assert p.returncode == 0, p.stderr
    assert two_fields.to_json() == (out / "probability.json").read_text()
    assert two_fields.to_csv() == (out / "samples.csv").read_text()
    # --format json prints the summary: the same as summary_json(), the contract's keys
    printed = cli.json(
        "design", "probability", "--scene", scene, "--accuracy", "fast", "--scatter", SPRING,
        "--samples", "30", "--seed", "5", "--format", "json",
    )
    # with the validity of the samples, which the command adds to the run's summary
    assert printed["validity"] == {"holds": one_field.validity.holds, "reasons": list(one_field.validity.reasons)}
    assert printed == json.loads(one_field.summary_json())
    assert one_field.summary_json() == cli.run(
        "design", "probability", "--scene", scene, "--accuracy", "fast", "--scatter", SPRING,
        "--samples", "30", "--seed", "5", "--format", "json",
    ).stdout
    for key in ("samples", "stiction_probability", "ci_low", "ci_high", "does_not_close_probability", "outside_validity", "by_cycle"):
        assert key in printed, key
    assert printed["stiction_probability"] == one_field.stiction_probability


def test_the_result_is_typed_with_numpy_columns(one_field, two_fields):
    r = two_fields
    assert isinstance(r, stiction.ProbabilityResult)
    assert r.samples == 12 and r.samples_requested == 12 and r.seed == 9 and r.confidence == 0.95
    assert r.scatter == TWO and r.correlate == [CORRELATE]
    # the three outcomes of the counted samples partition the denominator; none apart here
    c = r.counts
    assert c.sticks + c.free + c.does_not_close == r.denominator == 12
    assert r.outside_validity == c.outside_validity == 0
    assert r.stiction.count == c.sticks and r.stiction_probability == c.sticks / 12
    assert r.ci_low <= r.stiction_probability <= r.ci_high
    # P(stuck by cycle n): numpy columns, rising to the answer after accommodation
    by = r.by_cycle
    assert isinstance(by, stiction.Table) and len(by) == r.cycles == 3
    assert isinstance(by.probability, np.ndarray) and by.cycle.tolist() == [1, 2, 3]
    assert by.cycle.dtype.kind == "i" and by.sticking.dtype.kind == "i"
    assert np.all(np.diff(by.probability) >= 0)
    assert np.all((by.ci_low <= by.probability) & (by.probability <= by.ci_high))
    assert by.probability[-1] == r.stiction_probability
    # every sample, in index order, with its values and design point
    assert [p.index for p in r.points] == list(range(12))
    assert all(isinstance(p, stiction.ProbabilitySample) for p in r.points)
    k = r.values_of("switch.k_s")
    ratio = r.column("pull_out_ratio")
    assert k.shape == ratio.shape == (12,) and np.all(k > 0)
    assert np.array_equal(r.column("sticks"), ratio > 1)
    # the CSV's counted column and the counted() helper agree
    rows = r.to_csv().splitlines()
    col = rows[0].split(",").index("counted")
    assert [row.split(",")[col] == "true" for row in rows[1:]] == r.counted().tolist()
    # the driver is the field of largest |rho| with the ratio
    rho = r.rank_correlation
    assert rho.field.tolist() == ["switch.k_s", "contact.work_of_adhesion"]
    assert r.driver == rho.field[int(np.nanargmax(np.abs(rho.spearman)))]
    assert r.exact is None  # two fields: no exact answer
    assert r.validity is not None and r.validity.holds
    d = r.to_dict()
    assert d["by_cycle"][2]["probability"] == r.stiction_probability and "_native" not in d


def test_one_monotone_field_has_the_exact_answer_of_the_cdf_at_the_critical_value(one_field):
    r = one_field
    e = r.exact
    assert isinstance(e, stiction._results.ExactAnswer)
    assert e.available and e.monotone and e.direction == "decreasing" and e.free_side == "above"
    # the paper's switch needs about 1.3e10 Pa/m (docs/design.md)
    assert 1.2e10 < e.critical_value < 1.4e10
    # P = F(critical K_s) for the lognormal of median 1.25e10 and factor 1.3
    assert abs(e.stiction_probability - _lognormal_cdf(e.critical_value, 1.25e10, 1.3)) < 1e-12
    assert e.range.shape == (2,) and e.range[0] < e.critical_value < e.range[1]
    assert r.ci_low <= e.stiction_probability <= r.ci_high and r.exact_inside_interval is True
    # each sample sticks exactly when its K_s is below the critical value
    assert np.array_equal(r.column("sticks"), r.values_of("switch.k_s") < e.critical_value)
    assert r.driver == "switch.k_s" and abs(r.rank_correlation.spearman[0] + 1.0) < 1e-12


def test_shards_merged_equal_one_run(spring_scene, two_fields, tmp_path):
    parts = [
        stiction.design_probability(spring_scene, TWO, samples=12, seed=9, correlate=[CORRELATE], accuracy="fast", shard=s)
        for s in ("2/2", "1/2")
    ]
    assert [p.index for p in parts[1].points] == [0, 2, 4, 6, 8, 10]
    assert parts[1].shard == {"k": 1, "n": 2}
    merged = stiction.design_merge(parts)
    assert isinstance(merged, stiction.ProbabilityResult)
    assert merged.to_json() == two_fields.to_json() and merged.to_csv() == two_fields.to_csv()
    assert merged == two_fields
    # through the files, as `stiction design merge` reads them
    for i, p in enumerate(parts):
        p.save(tmp_path / f"part{i}")
    paths = [tmp_path / f"part{i}" / "probability.json" for i in range(2)]
    assert stiction.design_merge(paths) == two_fields
    # a part's kind is read from the file, whatever its name
    renamed = [tmp_path / f"p{i}.json" for i in range(2)]
    for src, dst in zip(paths, renamed):
        dst.write_bytes(src.read_bytes())
    assert stiction.design_merge(renamed) == two_fields
    assert stiction.read_probability(paths[1]) == parts[1]
    # what `--format json` prints: the statistics with the validity, no samples; no
    # private name among the fields
    summary = json.loads(two_fields.summary_json())
    assert "validity" in summary and "points" not in summary
    assert not any(k.startswith("_") for k in two_fields.keys())
    with pytest.raises(stiction.InputError, match="missing part"):
        stiction.design_merge(paths[:1])
    with pytest.raises(stiction.InputError, match="do not merge"):
        stiction.design_merge([parts[0], tmp_path / "map.json"])


def test_a_target_halfwidth_stops_at_a_block_of_100(spring_scene):
    r = stiction.design_probability(
        spring_scene, SPRING, samples=1000, seed=1, accuracy="fast", target_halfwidth=0.2, exact=False
    )
    assert r.stopping.rule == "target_halfwidth" and r.stopping.target_met is True
    assert r.samples == 100 and r.samples_requested == 1000
    assert (r.ci_high - r.ci_low) / 2 == r.stopping.halfwidth <= 0.2
    assert r.exact is None


def test_bad_scatter_is_refused_naming_the_field(spring_scene):
    # a normal roughness puts 10 % of its mass below the domain: refused, never clipped
    with pytest.raises(stiction.InputError, match="surface.sigma_s") as e:
        stiction.design_probability(spring_scene, "surface.sigma_s=normal(5e-9,4e-9)", samples=5)
    assert "never clipped" in str(e.value)
    with pytest.raises(stiction.InputError, match="unknown field `surface.sigma`"):
        stiction.design_probability(spring_scene, "surface.sigma=lognormal(1e-8,1.2)", samples=5)
    with pytest.raises(stiction.InputError, match="unknown distribution `gamma`"):
        stiction.design_probability(spring_scene, "surface.sigma_s=gamma(1,2)", samples=5)
    with pytest.raises(stiction.InputError, match="samples"):
        stiction.design_probability(spring_scene, SPRING, samples=0)
    with pytest.raises(stiction.InputError, match="contact.z0 is not a scattered field"):
        stiction.design_probability(spring_scene, SPRING, samples=5, correlate="switch.k_s,contact.z0=0.2")
    # the paper's own scene gives the impact energy: K_s cannot scatter there
    with pytest.raises(stiction.InputError, match="scene's drive"):
        stiction.design_probability(stiction.Scene.paper("switch"), SPRING, samples=5)
