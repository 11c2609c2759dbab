"""The GIL is released while the library computes: Python code in other threads keeps
running, and two long computations in two threads run at the same time."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

import stiction


def _heartbeat_while(work, *args):
    """Runs `work` in threads (one per args tuple) while this thread counts; returns the
    largest pause between two counts, the time the threads took, and their (start, end)."""
    spans = []

    def target(a):
        t0 = time.perf_counter()
        work(*a)
        spans.append((t0, time.perf_counter()))

    threads = [threading.Thread(target=target, args=(a,)) for a in args]
    # the first beat before the threads start: a thread that takes the GIL at once and
    # keeps it would stop this one inside start()
    start = time.perf_counter()
    beats = [start]
    for t in threads:
        t.start()
        beats.append(time.perf_counter())
    while any(t.is_alive() for t in threads):
        x = 0
        for i in range(2000):  # pure Python work: needs the GIL
            x += i
        beats.append(time.perf_counter())
    for t in threads:
        t.join()
    gaps = np.diff(beats)
    return float(gaps.max()), time.perf_counter() - start, spans, len(beats)


@pytest.fixture(scope="module")
def long_surface_work():
    s = stiction.Surface(stiction.Scene.paper("switch"), accuracy="accurate")
    d = np.linspace(4e-9, 40e-9, 3000)

    def work():
        s.pressure(d, d_min=5e-9, path="retract")

    t0 = time.perf_counter()
    work()
    return work, time.perf_counter() - t0


def test_the_heartbeat_sees_a_computation_that_holds_the_gil():
    import re

    def work():  # a backtracking match holds the GIL throughout
        re.match(r"(a+)+$", "a" * 22 + "b")

    gap, took, _, _ = _heartbeat_while(work, ())
    assert took > 0.1 and gap > 0.8 * took, (gap, took)


def test_python_runs_while_a_surface_computes(long_surface_work):
    work, alone = long_surface_work
    assert alone > 0.2, "the computation is too short to tell"
    gap, took, _, beats = _heartbeat_while(work, ())
    # holding the GIL would stop this thread for the whole computation
    assert gap < 0.5 * took, (gap, took)
    assert beats > 10


def test_two_computations_overlap_in_time(long_surface_work):
    work, alone = long_surface_work
    gap, took, spans, _ = _heartbeat_while(work, (), ())
    (a0, a1), (b0, b1) = spans
    # each started before the other ended: they ran at the same time
    assert a0 < b1 and b0 < a1
    assert min(a1, b1) - max(a0, b0) > 0.5 * min(a1 - a0, b1 - b0)
    assert gap < 0.5 * took


@pytest.mark.parametrize(
    "name",
    ["run", "law_evaluate", "maugis_kim_force", "design_map"],
)
def test_every_kind_of_computation_releases_the_gil(name, tmp_path_factory):
    if name == "run":
        scene = stiction.Scene.paper("switch")

        def work():
            stiction.run(scene, accuracy="balanced")

    elif name == "law_evaluate":
        r = stiction.tabulate_law(stiction.Scene.paper("switch"), d_min="9e-9:5e-9:6", points=24)
        law = r.law
        d = np.random.default_rng(1).uniform(5e-9, 25e-9, 3_000_000)

        def work():
            law.evaluate(d, 7e-9, "retract")

    elif name == "maugis_kim_force":
        delta = np.linspace(-1.0, 3.0, 2_000_000)

        def work():
            stiction.maugis_kim_force(0.7, delta, "retract", from_=3.0)

    else:
        scene = stiction.Scene.paper("switch")

        def work():
            # 12 points: long enough (> 0.1 s) for the heartbeat to measure, now that a fast
            # point takes a few milliseconds
            stiction.design_map(scene, ["surface.sigma_s=2e-9:1e-7:log:12"], accuracy="fast")

    gap, took, _, _ = _heartbeat_while(work, ())
    assert took > 0.1, (name, took)
    assert gap < 0.5 * took, (name, gap, took)
