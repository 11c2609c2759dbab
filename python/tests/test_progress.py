"""Long calls report progress and stop on Ctrl-C (issue 46): `progress(done, total)` with
done monotone, at most total, ending at done == total; an exception of the callback
propagates; SIGINT during a long run raises KeyboardInterrupt within a second. And the
reference table of docs/python.md lists every argument of every public function."""

from __future__ import annotations

import ast
import inspect
import os
import pathlib
import re
import signal
import threading
import time

import pytest

import stiction

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"


class Recorder:
    def __init__(self):
        self.calls = []
        self.times = []

    def __call__(self, done, total):
        assert isinstance(done, int) and isinstance(total, int)
        self.calls.append((done, total))
        self.times.append(time.monotonic())

    def check(self):
        assert self.calls, "progress was never called"
        for (d0, t0), (d1, t1) in zip(self.calls, self.calls[1:]):
            assert d1 >= d0, self.calls
            assert t1 >= t0, self.calls
        for d, t in self.calls:
            assert 0 <= d <= t, self.calls
        done, total = self.calls[-1]
        assert done == total and total > 0, self.calls
        # at most ten calls a second, plus the last one
        span = self.times[-1] - self.times[0]
        assert len(self.calls) <= 10 * span + 3, (len(self.calls), span)


def _long_calls(scene):
    """Each long call, small enough for a test, with its progress argument."""
    probability_scene = scene.with_values({"contact.yield_modulus": "composite"})
    return {
        "run": lambda p: stiction.run(scene, accuracy="fast", progress=p),
        "design_threshold": lambda p: stiction.design_threshold(
            scene, "surface.sigma_s", 2e-9, 1e-7, accuracy="fast", progress=p
        ),
        "design_map": lambda p: stiction.design_map(
            scene, ["surface.sigma_s=2e-9:1e-7:log:6"], accuracy="fast", progress=p
        ),
        "design_probability": lambda p: stiction.design_probability(
            probability_scene, ["surface.sigma_s=lognormal(7.78e-9,1.1)"], samples=12, accuracy="fast", progress=p
        ),
        "tabulate_law": lambda p: stiction.tabulate_law(scene, d_min="9e-9:5e-9:3", points=16, progress=p),
    }


@pytest.mark.parametrize("name", ["run", "design_threshold", "design_map", "design_probability", "tabulate_law"])
def test_progress_is_monotone_and_ends_at_its_total(name, paper_switch):
    rec = Recorder()
    result = _long_calls(paper_switch)[name](rec)
    assert result is not None
    rec.check()
    assert "progress" in inspect.signature(getattr(stiction, name)).parameters


def test_a_run_without_progress_is_the_run_with_it(paper_switch):
    a = stiction.run(paper_switch, accuracy="fast")
    b = stiction.run(paper_switch, accuracy="fast", progress=lambda d, t: None)
    assert a.to_dict() == b.to_dict()


def test_the_stages_of_a_model_form_check_add_up(paper_switch):
    rec = Recorder()
    r = stiction.run(paper_switch.with_values({"model_form": "check"}), accuracy="fast", progress=rec)
    assert r.model_form is not None
    rec.check()
    # the scene's own 10 cycles, then its combinations
    assert rec.calls[-1][1] > 10


def test_a_design_question_counts_its_model_form_combinations_too(paper_switch):
    # the combinations are a stage of their own, one step each: the total grows past the
    # points (it stood at the points while the combinations ran, the fourteenth stop's QA)
    scene = paper_switch.with_values({"model_form": "check"})
    rec = Recorder()
    m = stiction.design_map(scene, ["surface.sigma_s=2e-9:1e-7:log:3"], accuracy="fast", progress=rec)
    rec.check()
    assert m.model_form is not None
    assert rec.calls[-1][0] == rec.calls[-1][1] > 3, rec.calls


def test_a_map_reports_every_point(paper_switch):
    rec = Recorder()
    stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:4"], accuracy="fast", progress=rec)
    assert rec.calls[-1] == (4, 4)


def test_a_progress_that_is_not_callable_is_an_input_error(paper_switch):
    with pytest.raises(stiction.InputError, match="progress"):
        stiction.run(paper_switch, accuracy="fast", progress=3)


class Stop(Exception):
    pass


def test_an_exception_of_the_callback_propagates_and_stops_the_run(paper_switch):
    seen = []

    def progress(done, total):
        seen.append((done, total))
        raise Stop(f"stopped at {done}/{total}")

    # a map of 400 accurate points: tens of seconds whole
    t = time.monotonic()
    with pytest.raises(Stop, match="stopped at"):
        stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:20", "switch.impact_energy=0.1:1:lin:20"],
                            progress=progress)
    assert time.monotonic() - t < 3.0
    assert len(seen) == 1


def _interrupt_after(delay):
    sent = []

    def fire():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, fire)
    timer.start()
    return timer, sent


def _gas_switch(scene):
    """The paper's switch in time under an atmosphere's squeeze film, the plate creeping to
    the contact, over 300 cycles in accurate mode: about 17 s whole (a cycle in the
    default mode takes about 0.06 s)."""
    return scene.with_values({
        "cycles": 300,
        "accuracy": "accurate",
        "switch.impact_energy": None,
        "switch.k_s": 8.44e9,
        "switch.voltage": 60.0,
        "switch.dimple_height": 50e-9,
        "dynamics.areal_mass": 0.0246,
        "dynamics.gas_pressure": 101325.0,
    })


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals go to the main thread")
@pytest.mark.parametrize("with_progress", [False, True])
def test_ctrl_c_interrupts_a_long_run_within_a_second(paper_switch, with_progress):
    scene = _gas_switch(paper_switch)
    timer, sent = _interrupt_after(0.5)
    t = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            stiction.run(scene, progress=Recorder() if with_progress else None)
    finally:
        timer.cancel()
    assert sent, "the run ended before the signal"
    latency = time.monotonic() - sent[0]
    assert latency < 1.0, latency
    assert time.monotonic() - t < 3.0


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals go to the main thread")
def test_ctrl_c_interrupts_a_long_map_within_a_second(paper_switch):
    # 1600 accurate design points: a minute and a half whole (16 take about a second)
    timer, sent = _interrupt_after(0.5)
    try:
        with pytest.raises(KeyboardInterrupt):
            stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:40", "switch.impact_energy=0.1:1:lin:40"])
    finally:
        timer.cancel()
    assert sent, "the map ended before the signal"
    latency = time.monotonic() - sent[0]
    assert latency < 1.0, latency
    # the package works on after an interrupt
    assert stiction.run(paper_switch, accuracy="fast").stiction


# -- the reference table lists every argument ---------------------------------------------


def _table_signatures():
    """`name(args) -> T` entries of section 4's table, by name (the first entry of each)."""
    text = DOC.read_text()
    section = text[text.index("## 4. Reference"):text.index("## 5.")]
    found = {}
    for m in re.finditer(r"`((\w+)\(([^`]*?)\))(?: -> [\w\[\], ]+)?`", section):
        found.setdefault(m.group(2), m.group(1))
    return found


def _params_of(entry):
    tree = ast.parse(f"def {entry}: pass")
    f = tree.body[0]
    a = f.args
    names = [x.arg for x in a.posonlyargs + a.args] + [x.arg for x in a.kwonlyargs]
    defaults = [None] * (len(a.posonlyargs + a.args) - len(a.defaults)) + list(a.defaults) + list(a.kw_defaults)
    out = {}
    for name, d in zip(names, defaults):
        out[name] = inspect.Parameter.empty if d is None else ast.literal_eval(d)
    return out


@pytest.mark.skipif(not DOC.is_file(), reason="docs/python.md is not beside the tests")
def test_the_reference_table_lists_every_argument_of_every_public_function():
    table = _table_signatures()
    public = [n for n in stiction.__all__ if inspect.isfunction(getattr(stiction, n))]
    assert len(public) >= 15
    for name in public:
        assert name in table, f"{name} is not in the reference table"
        sig = inspect.signature(getattr(stiction, name))
        want = {p.name: p.default for p in sig.parameters.values()}
        got = _params_of(table[name])
        assert list(got) == list(want), f"{name}: table {list(got)}, signature {list(want)}"
        for p, default in want.items():
            assert got[p] == default, f"{name}({p}=...): table {got[p]!r}, signature {default!r}"


@pytest.mark.skipif(not DOC.is_file(), reason="docs/python.md is not beside the tests")
def test_the_reference_table_lists_the_constructors_it_shows():
    table = _table_signatures()
    for name in ("Asperity", "Surface"):
        cls = getattr(stiction, name)
        want = [p for p in inspect.signature(cls).parameters]
        assert list(_params_of(table[name])) == want, name


def test_a_map_on_an_executor_reports_its_tasks(paper_switch):
    from concurrent.futures import ThreadPoolExecutor

    rec = Recorder()
    with ThreadPoolExecutor(2) as pool:
        m = stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:4"], accuracy="fast",
                                client=pool, progress=rec)
    rec.check()
    assert rec.calls[-1] == (4, 4)
    assert m.to_json() == stiction.design_map(paper_switch, ["surface.sigma_s=2e-9:1e-7:log:4"],
                                              accuracy="fast").to_json()
