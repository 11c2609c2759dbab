"""The public API: the contract's names, the stubs of the extension module against the
module itself, docstrings that state units."""

from __future__ import annotations

import ast
import inspect
import pathlib

import pytest

import stiction
from stiction import _stiction

STUB = pathlib.Path(stiction.__file__).with_name("_stiction.pyi")


def _stub_tree():
    tree = ast.parse(STUB.read_text())
    funcs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    return funcs, classes


def _params(node: ast.FunctionDef) -> list:
    a = node.args
    return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg not in ("self", "cls")]


def test_the_contracts_names_exist():
    for name in ("load_scene", "run", "maugis_kim_force", "design_map", "ContactLaw", "InputError", "NumericalError", "StictionError"):
        assert hasattr(stiction, name), name
    assert callable(stiction.ContactLaw.load) and callable(stiction.ContactLaw.evaluate)
    assert list(inspect.signature(stiction.design_map).parameters)[:4] == ["scene", "vary", "accuracy", "client"]
    assert list(inspect.signature(stiction.run).parameters) == ["scene", "accuracy", "progress"]
    assert list(inspect.signature(stiction.maugis_kim_force).parameters)[:3] == ["lam", "delta", "path"]
    assert inspect.signature(stiction.maugis_kim_force).parameters["path"].default == "approach"
    assert list(inspect.signature(stiction.ContactLaw.evaluate).parameters)[1:] == ["d", "d_min", "path"]
    for name in stiction.__all__:
        assert hasattr(stiction, name), name


def test_the_stub_declares_the_extension_module():
    funcs, classes = _stub_tree()
    public = {n for n in dir(_stiction) if not n.startswith("_")}
    assert public == set(funcs) | set(classes)
    for name, node in funcs.items():
        sig = inspect.signature(getattr(_stiction, name))
        assert _params(node) == list(sig.parameters), name
    for name, node in classes.items():
        cls = getattr(_stiction, name)
        declared = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
        members = {m for m in dir(cls) if not m.startswith("_")}
        assert members == {m for m in declared if not m.startswith("_")}, name
        for m, fn in declared.items():
            obj = inspect.getattr_static(cls, m)
            if isinstance(obj, property) or type(obj).__name__ == "getset_descriptor":
                continue
            target = getattr(cls, m)
            try:
                sig = inspect.signature(target)
            except (ValueError, TypeError):
                continue
            got = [p for p in sig.parameters if p not in ("self", "cls", "$self")]
            if m.startswith("__"):
                continue  # slot wrappers name their arguments their own way
            assert _params(fn) == got, f"{name}.{m}"


@pytest.mark.parametrize(
    "obj",
    [
        stiction.run,
        stiction.maugis_kim_force,
        stiction.design_map,
        stiction.tabulate_law,
        stiction.AdhesionLaw.force,
        stiction.Asperity.force,
        stiction.Surface.pressure,
        stiction.ContactLaw.evaluate,
        stiction.Surface,
    ],
)
def test_docstrings_state_units(obj):
    doc = inspect.getdoc(obj) or ""
    assert any(u in doc for u in ("(m", " m)", "Pa", "(N", "nondimensional", "units of")), obj


def test_result_classes_declare_units():
    src = pathlib.Path(stiction.__file__).with_name("_results.py").read_text()
    for field in ("d_e: float  #: end-of-impact separation (m)", "pull_out_pressure: float  #: pull-out pressure (Pa"):
        assert field in src


def test_arguments_of_the_wrong_type_are_input_errors_naming_them(paper_switch):
    # never a bare OverflowError or TypeError, never a bool read as a count
    for kwargs, name in (
        ({"seed": -1}, "seed"),
        ({"samples": -1}, "samples"),
        ({"samples": True}, "samples"),
        ({"samples": 10.5}, "samples"),
        ({"accuracy": 3}, "accuracy"),
    ):
        with pytest.raises(stiction.InputError, match=name):
            stiction.design_probability(paper_switch, "surface.sigma_s=lognormal(7.78e-9,1.1)", **kwargs)
    with pytest.raises(stiction.InputError, match="accuracy"):
        stiction.run(paper_switch, accuracy=3)
    with pytest.raises(stiction.InputError, match="points"):
        stiction.md_curve(0.5, points=10.5)
    with pytest.raises(stiction.InputError, match="fit") as e:
        stiction.calibrate(stiction.Scene.paper("asperity"), {"delta_max_m": [], "delta_m": [], "force_n": [], "branch": []}, fit="zz")
    assert "must be unknown" not in str(e.value)
    with pytest.raises(stiction.InputError, match="a design runs a switch scene"):
        stiction.design_map(stiction.Scene.paper("surface"), ["surface.sigma_s=2e-9:1e-8:log:2"])


def test_integers_beyond_the_librarys_range_and_a_client_that_is_none_are_input_errors(paper_switch):
    # a huge integer is refused naming the argument, never an OverflowError on the way in;
    # a `client` that is not a Dask client or an executor is refused naming `client`,
    # never an AttributeError from deep inside the map
    scatter = "switch.k_s=lognormal(1.25e10,1.3)"
    for kwargs, name in (
        ({"samples": 10**30}, "samples"),
        ({"samples": 2**64}, "samples"),
        ({"seed": 2**70}, "seed"),
        ({"seed": 2**64}, "seed"),
        ({"seed": -1}, "seed"),
    ):
        with pytest.raises(stiction.InputError, match=name):
            stiction.design_probability(paper_switch, scatter, accuracy="fast", **kwargs)
    with pytest.raises(stiction.InputError, match="points"):
        stiction.md_curve(0.5, points=10**30)
    with pytest.raises(stiction.InputError, match="points"):
        stiction.tabulate_law(paper_switch, points=2**64)
    for client in (object(), "tcp://127.0.0.1:8786", 3):
        with pytest.raises(stiction.InputError, match="client"):
            stiction.design_map(paper_switch, "surface.sigma_s=3e-9:5e-8:log:2", accuracy="fast", client=client)
    # a scene value beyond any float (a Python int of 1400 bits), and one beyond the key's
    # domain, are refused naming the key
    s = stiction.Scene.paper("switch")
    with pytest.raises(stiction.InputError, match="cycles"):
        s.set("cycles", 10**400)
    s.set("cycles", 10**30)
    with pytest.raises(stiction.InputError, match="cycles"):
        s.validate()


def test_a_model_form_check_runs_every_credible_combination(paper_switch):
    # issue 42: the paper's switch sticks under all 8 combinations (2 plasticity laws x 2
    # readings of eq 1 x 2 reload rules x Maugis-Kim), with a 7 % margin at worst
    s = stiction.Scene.paper("switch")
    s.set("model_form", "check")
    s.set("elastic_comparison", False)
    s.set("contact_state", "none")
    r = stiction.run(s, accuracy="fast")
    m = r.model_form
    assert isinstance(m, stiction.ModelFormReport)
    assert m.robust and m.flips == []
    assert len(m.runs) == 8
    assert m.runs[0].pull_out_ratio == r.pull_out_ratio
    lo, hi = m.ratio_range
    assert 1.06 < lo < 1.08 and 157 < hi < 159
    assert {e["value"] for e in m.excluded} >= {"jkr", "dmt", "hertz", "elastic"}
    assert m.to_dict()["summary"].startswith("sticks under all 8 combinations")
    # without the check there is none
    assert stiction.run(stiction.Scene.paper("switch"), accuracy="fast").model_form is None


def test_the_namespace_is_all():
    # issue 46: dir(stiction) is __all__, not the helpers the module imports
    assert set(dir(stiction)) == set(stiction.__all__)
    for helper in ("Any", "List", "Mapping", "Optional", "np", "os", "annotations"):
        assert helper not in dir(stiction)
