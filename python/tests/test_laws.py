"""The laws on numpy arrays in SI units: adhesion laws of a sphere (against closed forms and
the nondimensional curve), the asperity and the rough surface (against the runs of the
command line's models), vectorised against scalar calls."""

from __future__ import annotations

import math

import numpy as np
import pytest

import stiction

# Table 1 of the paper: Ru films, R = 4 um, w = 1 J/m^2, z0 = 0.169 nm
E, NU, R, W, Z0 = 410e9, 0.3, 4e-6, 1.0, 1.69e-10
# two identical films: 1/E* = 2 (1 - nu^2)/E, K = 4/3 E*
K = 4.0 / 3.0 * E / (2.0 * (1.0 - NU**2))


def test_hertz_is_its_closed_form():
    law = stiction.AdhesionLaw.hertz(K)
    delta = np.array([-1e-9, 0.0, 1e-10, 1e-9, 3e-9])
    expected = np.where(delta > 0, K * math.sqrt(R) * np.clip(delta, 0, None) ** 1.5, 0.0)
    assert np.allclose(law.force(delta, R), expected, rtol=1e-14, atol=0)


def test_the_si_maugis_kim_law_is_the_nondimensional_curve_scaled():
    law = stiction.AdhesionLaw.maugis_kim(K, W, Z0)
    lam = 2.0 * (W / Z0) * (R / (math.pi * W * K**2)) ** (1.0 / 3.0)
    length = (math.pi**2 * W**2 * R / K**2) ** (1.0 / 3.0)
    delta = np.linspace(-0.3e-9, 2e-9, 9)
    for path, from_ in (("approach", None), ("retract", 2e-9)):
        si = law.force(delta, R, path, from_=from_)
        nd = stiction.maugis_kim_force(lam, delta / length, path, from_=None if from_ is None else from_ / length)
        assert np.allclose(si, math.pi * W * R * nd, rtol=1e-9, atol=1e-18)


def test_the_scenes_law_is_the_papers_maugis_kim(paper_switch):
    scene_law = stiction.AdhesionLaw.of_scene(paper_switch)
    assert scene_law.name == "maugis_kim"
    mine = stiction.AdhesionLaw.maugis_kim(K, W, Z0)
    delta = np.linspace(-0.5e-9, 1e-9, 7)
    assert np.allclose(scene_law.force(delta, R), mine.force(delta, R), rtol=1e-12, atol=1e-20)
    j = scene_law.jumps(R)
    assert j.jump_in == pytest.approx(-Z0)  # the closed form on approach: -z0
    assert j.jump_out < j.jump_in


def test_jkr_and_dmt_pull_offs():
    jkr = stiction.AdhesionLaw.jkr(K, W)
    dmt = stiction.AdhesionLaw.dmt(K, W, Z0)
    delta = np.linspace(-2e-9, 1e-9, 20001)
    # load control: the most tensile force on the branch retracting from contact
    assert jkr.force(delta, R, "retract", from_=1e-9).min() == pytest.approx(-1.5 * math.pi * W * R, rel=1e-4)
    assert dmt.force(0.0, R) == pytest.approx(-2.0 * math.pi * W * R, rel=1e-12)
    assert dmt.force(delta, R).min() >= -2.0 * math.pi * W * R * (1 + 1e-12)
    # DMT out of contact: -2 pi w R (1 + delta/z0) for -z0 < delta < 0
    assert dmt.force(-0.5 * Z0, R) == pytest.approx(-2.0 * math.pi * W * R * 0.5, rel=1e-12)


def test_adhesion_laws_are_vectorised_over_delta_and_radius():
    law = stiction.AdhesionLaw.maugis_kim(K, W, Z0)
    delta = np.linspace(-0.4e-9, 1e-9, 12).reshape(3, 4)
    radius = np.linspace(1e-6, 5e-6, 12).reshape(3, 4)
    v = law.force(delta, radius, "retract", from_=1e-9)
    assert v.shape == (3, 4)
    s = [law.force(float(d), float(r), "retract", from_=1e-9) for d, r in zip(delta.ravel(), radius.ravel())]
    assert np.array_equal(v.ravel(), s)
    with pytest.raises(stiction.InputError, match="radius"):
        law.force(delta, radius[:2])
    with pytest.raises(stiction.InputError, match="radius"):
        law.force(1e-9, -1.0)
    with pytest.raises(stiction.InputError, match="work_of_adhesion"):
        stiction.AdhesionLaw.jkr(K, -1.0)


@pytest.fixture(scope="module")
def asperity_run():
    s = stiction.Scene.paper("asperity")
    s.set("points", 25)
    return s, stiction.run(s)


def test_the_asperity_gives_the_runs_curves(asperity_run):
    scene, r = asperity_run
    a = stiction.Asperity(scene)
    e = stiction.Asperity(scene, elastic=True)
    assert a.delta_cp == r.delta_cp and a.radius == r.radius
    for case in r.cases:
        assert np.array_equal(a.force(case.loading.delta), case.loading.force)
        unloading = a.force(case.unloading.delta, case.delta_max, "retract")
        assert np.array_equal(unloading, case.unloading.force)
        f, at = a.pull_off(case.delta_max)
        assert (f, at) == (case.pull_off_force, case.pull_off_interference)
        assert e.pull_off(case.delta_max).force == case.elastic_pull_off_force
        st = a.state(case.delta_max)
        assert (st.delta_res, st.r_res, st.extrapolated) == (case.delta_res, case.r_res, case.extrapolated)


def test_asperity_calls_are_vectorised(asperity_run):
    scene, r = asperity_run
    a = stiction.Asperity(scene)
    dmax = np.array([r.cases[0].delta_max, r.cases[-1].delta_max])
    delta = np.array([0.5 * dmax[0], 0.9 * dmax[1]])
    v = a.force(delta, dmax, "retract")
    assert list(v) == [a.force(float(x), float(m), "retract") for x, m in zip(delta, dmax)]
    f, at = a.pull_off(dmax)
    assert list(f) == [a.pull_off(float(m)).force for m in dmax]


@pytest.fixture(scope="module")
def surface_run():
    s = stiction.Scene.paper("surface")
    s.set("unload_from", 5e-9)
    s.set("points", 30)
    s.set("accuracy", "fast")
    return s, stiction.run(s)


def test_the_surface_gives_the_runs_curves(surface_run):
    scene, r = surface_run
    s = stiction.Surface(scene)
    assert s.sigma_s == r.sigma_s and s.accuracy == "fast"
    assert np.array_equal(s.pressure(r.loading.d), r.loading.pressure)
    assert np.array_equal(s.pressure(r.unloading.d, d_min=5e-9, path="retract"), r.unloading.pressure)
    assert np.array_equal(s.pressure(r.reloading.d, d_min=5e-9), r.reloading.pressure)
    po = s.pull_out(5e-9)
    assert (po.pressure, po.separation) == (r.pull_out_pressure, r.pull_out_separation)
    assert po.error == r.error_estimate.pull_out


def test_surface_pressures_are_vectorised(surface_run):
    scene, _ = surface_run
    s = stiction.Surface(scene)
    d = np.linspace(4e-9, 30e-9, 8).reshape(2, 4)
    d_min = np.full((2, 4), 4e-9)
    v = s.pressure(d, d_min, "retract")
    assert v.shape == (2, 4)
    assert list(v.ravel()) == [s.pressure(float(x), 4e-9, "retract") for x in d.ravel()]
    p, err = s.pressure_estimate(d)
    assert np.array_equal(p, s.pressure(d)) and (err >= 0).all()
    assert s.pressure(s.reach() * 1.01) == 0.0


def test_surface_errors_are_input(surface_run, paper_switch):
    scene, _ = surface_run
    with pytest.raises(stiction.InputError, match="asperity scene has no rough surface"):
        stiction.Surface(stiction.Scene.paper("asperity"))
    s = stiction.Surface(scene)
    with pytest.raises(stiction.InputError, match="d_min"):
        s.pressure(1e-8, path="retract")  # a virgin surface has nothing to retract from
    with pytest.raises(stiction.InputError, match="path"):
        s.pressure(1e-8, path="up")
    with pytest.raises(stiction.InputError, match="accuracy"):
        stiction.Surface(paper_switch, accuracy="quick")


def test_histories_and_excursions_that_mean_nothing_are_input(surface_run, asperity_run):
    # a NaN history read as a virgin surface, a point deeper than the excursion it
    # retracts from, a press far beyond the heights: each refused, naming the argument
    scene, _ = surface_run
    s = stiction.Surface(scene)
    with pytest.raises(stiction.InputError, match="d_min"):
        s.pressure(10e-9, d_min=math.nan)
    with pytest.raises(stiction.InputError, match="d_min"):
        s.reach(math.nan)
    for bad in (math.nan, -1.0):
        with pytest.raises(stiction.InputError, match="d_min"):
            s.pull_out(bad)
    a = stiction.Asperity(asperity_run[0])
    with pytest.raises(stiction.InputError, match="delta_max"):
        a.force(1e-9, math.nan)
    with pytest.raises(stiction.InputError, match="delta_max"):
        a.pull_off(math.nan)
    with pytest.raises(stiction.InputError, match="delta_max"):
        a.state(math.nan)
    with pytest.raises(stiction.InputError, match="delta = inf"):
        a.force(math.inf)
    with pytest.raises(stiction.InputError, match="deeper point is on the approach"):
        a.force(40e-9, 34e-9, "retract")
    law = stiction.AdhesionLaw.of_scene(asperity_run[0])
    with pytest.raises(stiction.InputError, match="deeper point is on the approach"):
        law.force(2e-9, 4e-6, "retract", from_=1e-9)


def test_asperity_delta_max_has_the_scenes_domain(asperity_run):
    # delta_max in (0, 1e3 R], as an asperity scene's delta_max: an interference of 1e10 m
    # (a residual radius of 1e13 m) or 1e308 m (an infinite one) is refused by name
    a = stiction.Asperity(asperity_run[0])
    for bad in (1e308, 1e10, 1.001e3 * a.radius, 0.0, -1e-9):
        with pytest.raises(stiction.InputError, match="delta_max"):
            a.state(bad)
        with pytest.raises(stiction.InputError, match="delta_max"):
            a.pull_off(bad)
        with pytest.raises(stiction.InputError, match="delta_max"):
            a.force(1e-9, bad)
        with pytest.raises(stiction.InputError, match="delta_max"):
            a.jumps(bad)
    with pytest.raises(stiction.InputError, match="delta_max"):
        a.state(np.array([1e-8, 1e308]))
    st = a.state(1e3 * a.radius)
    assert math.isfinite(st.r_res) and math.isfinite(st.delta_res)


def test_separations_and_interferences_beyond_the_scenes_reach_are_refused_by_name():
    # issue 41: a separation far below the heights, or an interference beyond 1e3 R, failed
    # deep inside the laws ("invalid radius = inf") instead of naming the argument
    surf = stiction.Surface(stiction.Scene.paper("switch"), accuracy="fast")
    with pytest.raises(stiction.InputError, match="invalid d = "):
        surf.pressure(-1e308)
    with pytest.raises(stiction.InputError, match="invalid d_min = "):
        surf.pressure_estimate(1e-8, d_min=-1e-3)
    a = stiction.Asperity(stiction.Scene.paper("asperity"))
    with pytest.raises(stiction.InputError, match="invalid delta = "):
        a.force(1e300)
    assert surf.pressure(1e308) == 0.0
