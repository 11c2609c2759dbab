"""The nondimensional Maugis-Kim force: against the command line (`stiction md`), against
closed forms and known limits (DMT, JKR), vectorised against scalar calls."""

from __future__ import annotations

import math

import numpy as np
import pytest

import stiction

# `stiction md --lambda 0.5 --delta 0.3` (and --path retract --from 1): Fbar
MD_05_03 = -1.2145010207171922


@pytest.mark.parametrize(
    "lam, delta, path, from_",
    [
        (0.5, 0.3, "approach", None),
        (0.5, -1.0, "approach", None),
        (0.5, -1.0, "retract", 1.0),
        (1.8, 0.0, "retract", 2.0),
        (1e-3, 1.0, "approach", None),
        (30.0, -0.5, "retract", 0.7),
    ],
)
def test_force_equals_the_command_line(cli, lam, delta, path, from_):
    args = ["md", "--lambda", repr(lam), "--delta", repr(delta), "--path", path]
    if from_ is not None:
        args += ["--from", repr(from_)]
    expected = cli.json(*args)["force"]
    assert stiction.maugis_kim_force(lam, delta, path, from_=from_) == expected


def test_force_equals_the_recorded_value():
    assert stiction.maugis_kim_force(0.5, 0.3) == MD_05_03
    assert stiction.maugis_kim_force(0.5, 0.3, "retract", from_=1.0) == MD_05_03
    assert stiction.maugis_kim_force(0.5, 0.3, "retract", delta_max=1.0) == MD_05_03


def test_the_curve_equals_the_command_line(cli):
    expected = cli.json("md", "--lambda", "0.5", "--points", "50")
    r = stiction.md_curve(0.5, points=50)
    assert r.lambda_ == 0.5
    for k in ("jump_in_delta", "turning_delta", "turning_force", "pull_off_load_control", "pull_off_displacement_control"):
        assert getattr(r, k) == expected[k], k
    assert np.array_equal(r.curve.delta, [p["delta"] for p in expected["curve"]])
    assert np.array_equal(r.curve.force, [p["force"] for p in expected["curve"]])
    s = [p.get("s", math.nan) for p in expected["curve"]]
    assert np.array_equal(r.curve.s, s, equal_nan=True)
    assert list(r.curve.branch) == [p["branch"] for p in expected["curve"]]


def test_pull_off_tends_to_dmt_and_jkr():
    # load control: -2 (DMT, lambda -> 0), -3/2 (JKR, lambda -> inf); JKR's jump-out -5/6
    assert stiction.md_curve(1e-4).pull_off_load_control == pytest.approx(-2.0, abs=2e-3)
    jkr = stiction.md_curve(1e4)
    assert jkr.pull_off_load_control == pytest.approx(-1.5, abs=2e-3)
    assert jkr.pull_off_displacement_control == pytest.approx(-5.0 / 6.0, abs=5e-3)
    # the same limits as the minimum of the vectorised retract branch
    delta = np.linspace(-1.0, 1.0, 4001)
    dmt = stiction.maugis_kim_force(1e-4, delta, "retract", from_=1.0)
    assert dmt.min() == pytest.approx(-2.0, abs=2e-3)
    big = stiction.maugis_kim_force(1e4, delta, "retract", from_=1.0)
    assert big.min() == pytest.approx(-1.5, abs=2e-3)


def test_the_jkr_limit_follows_its_closed_form():
    # JKR in eq 7's units: Fbar = A^3 - sqrt(6) A^(3/2), Delta = A^2 - (2/3) sqrt(6 A)
    a = np.linspace(0.8, 2.0, 7)
    delta = a**2 - (2.0 / 3.0) * np.sqrt(6.0 * a)
    expected = a**3 - math.sqrt(6.0) * a**1.5
    f = stiction.maugis_kim_force(1e5, delta, "retract", from_=5.0)
    assert np.allclose(f, expected, rtol=0, atol=3e-3)


def test_the_dmt_limit_is_hertz_less_two():
    # DMT in contact: Fbar = Delta^(3/2) - 2; Maugis-Kim approaches it as sqrt(lambda)
    delta = np.array([0.5, 1.0, 2.0])
    dmt = delta**1.5 - 2.0
    err = [np.abs(stiction.maugis_kim_force(lam, delta) - dmt).max() for lam in (1e-2, 1e-4, 1e-6)]
    assert err[2] < 4e-3
    assert err[0] / err[1] == pytest.approx(10.0, rel=0.3)
    assert err[1] / err[2] == pytest.approx(10.0, rel=0.3)


def test_approach_is_zero_before_the_jump_in():
    lam = 0.5
    jump_in = -2.0 / (math.pi * lam)
    assert stiction.maugis_kim_force(lam, jump_in - 0.1) == 0.0
    assert stiction.maugis_kim_force(lam, jump_in + 0.01) < 0.0


def test_vectorised_equals_scalar_calls_and_keeps_the_shape():
    delta = np.linspace(-1.5, 3.0, 24).reshape(4, 6)
    for path, from_ in (("approach", None), ("retract", 3.0)):
        v = stiction.maugis_kim_force(1.3, delta, path, from_=from_)
        assert v.shape == (4, 6) and v.dtype == np.float64
        scalar = [stiction.maugis_kim_force(1.3, float(x), path, from_=from_) for x in delta.ravel()]
        assert np.array_equal(v.ravel(), scalar)
        assert isinstance(scalar[0], float)
    # lists and integer arrays are numbers too
    assert np.array_equal(stiction.maugis_kim_force(1.3, [0, 1]), stiction.maugis_kim_force(1.3, np.array([0.0, 1.0])))


def test_bad_arguments_raise_input_error():
    with pytest.raises(stiction.InputError, match="invalid lambda = 1e9"):
        stiction.maugis_kim_force(1e9, 0.3)
    with pytest.raises(stiction.InputError, match="delta"):
        stiction.maugis_kim_force(0.5, [0.1, math.nan])
    with pytest.raises(stiction.InputError, match="from"):
        stiction.maugis_kim_force(0.5, 0.1, "retract")
    with pytest.raises(stiction.InputError, match="path"):
        stiction.maugis_kim_force(0.5, 0.1, "sideways")


def test_the_curve_as_data_is_the_command_lines_json(cli):
    # the key `lambda` (attribute lambda_) and no `s` on the non-contact branch, as the
    # command writes it: to_dict() is the command's JSON, never a NaN
    expected = cli.json("md", "--lambda", "0.5", "--points", "50")
    assert stiction.md_curve(0.5, points=50).to_dict() == expected


def test_a_retraction_deeper_than_its_excursion_is_refused_as_the_command_line_does():
    with pytest.raises(stiction.InputError, match="excursion"):
        stiction.maugis_kim_force(0.5, 3.0, "retract", from_=1.0)
    with pytest.raises(stiction.InputError, match="excursion"):
        stiction.maugis_kim_force(0.5, np.array([0.2, 1.5]), "retract", from_=1.0)
    # at the extreme itself it is the retraction's force
    assert stiction.maugis_kim_force(0.5, 1.0, "retract", from_=1.0) == stiction.maugis_kim_force(0.5, 1.0)
