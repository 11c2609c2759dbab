"""Design maps on a cluster: one task per design point, evaluated on the workers by this
package, the answers assembled here into exactly the map of ``stiction design map``.

The plan (the base scene of every point as TOML text, and the points) is made and checked
by the library before any task is submitted; each worker runs the library's design-point
evaluator on one point (``stiction._stiction.design_point``); the assembly runs the
library's map engine over the answers, so the points, statuses and messages are those of
a local run (the engine is deterministic: the same map to the bit on any number of
workers or threads).

`client` is a ``dask.distributed.Client`` (the scene text is scattered once to every
worker, the points are submitted as tasks and gathered), or any
``concurrent.futures.Executor`` (``ProcessPoolExecutor``: one process per core here).
Every worker must have this package installed.
"""

from __future__ import annotations

import time
import uuid
from typing import Any, Callable, List, Optional, Sequence, Tuple, Union

from . import _stiction

Progress = Optional[Callable[[int, int], None]]


class Stages:
    """The progress of a call made of several runs on the cluster (a map, then its
    model-form combinations): their tasks added up, so that ``done`` never decreases and
    ``total`` grows when a further run starts; calls `progress` at most ten times a second
    and once at the end (:meth:`end`)."""

    def __init__(self, progress: Progress) -> None:
        self.progress = progress
        self.before = 0
        self.last = 0.0

    def run(self, total: int) -> Callable[[int], None]:
        """A further run of `total` tasks: the function to call with its tasks done."""
        before = self.before
        self.before += total

        def report(done: int) -> None:
            now = time.monotonic()
            if self.progress is not None and now - self.last >= 0.1:
                self.last = now
                self.progress(before + done, self.before)

        return report

    def end(self) -> None:
        if self.progress is not None:
            self.progress(self.before, self.before)


def evaluate_point(base: str, values: Sequence[Tuple[str, Union[float, str]]]) -> tuple:
    """One design point, on a worker: `base` the plan's scene (TOML), `values` the
    point's (field, value) pairs (a float, or the word of a categorical axis). Returns the
    answer the assembly takes."""
    from . import _stiction as native  # imported on the worker

    return native.design_point(base, [(str(k), v if isinstance(v, str) else float(v)) for k, v in values])


def map_on_client(
    client: Any,
    scene: Any,
    vary: List[str],
    accuracy: Optional[str],
    shard: Optional[str],
    require: Optional[str] = None,
    stages: Optional[Stages] = None,
) -> Any:
    """Runs the points of a map on `client` and assembles them (a NativeMap), reporting
    the points done to `stages`."""
    base, points = _stiction.design_map_plan(scene, vary, accuracy, shard, require)
    report = (stages or Stages(None)).run(len(points))
    if not points:
        return _stiction.design_map_assemble(scene, vary, [], accuracy, shard, require)
    answers = _run_points(client, base, points, "design-point", report)
    pairs = [(index, answer) for (index, _), answer in zip(points, answers)]
    return _stiction.design_map_assemble(scene, vary, pairs, accuracy, shard, require)


def _run_points(
    client: Any, base: str, points: List[Tuple[int, Any]], what: str, report: Callable[[int], None]
) -> List[Any]:
    """The answers of `points` (index, values) evaluated on `client` against `base`: on
    dask.distributed the scene once per worker and one task per point (a key of its own,
    hash=False: a run again with the same scene must not meet the release of the previous
    run's copy); on a concurrent.futures.Executor one submission per point. `report` is
    called with the count of tasks done as they complete."""
    if hasattr(client, "scatter") and hasattr(client, "gather"):
        from distributed import as_completed

        base_ref = client.scatter(base, broadcast=True, hash=False)
        run = uuid.uuid4().hex[:12]
        futures = [
            client.submit(evaluate_point, base_ref, values, key=f"stiction-{what}-{run}-{index}", pure=False)
            for index, values in points
        ]
        for done, _ in enumerate(as_completed(futures), 1):
            report(done)
        return client.gather(futures)
    import concurrent.futures

    futures = [client.submit(evaluate_point, base, values) for _, values in points]
    for done, _ in enumerate(concurrent.futures.as_completed(futures), 1):
        report(done)
    return [f.result() for f in futures]


def probability_on_client(
    client: Any,
    scene: Any,
    args: tuple,
    exact: bool,
    count_outside_validity: bool = False,
    stages: Optional[Stages] = None,
) -> Any:
    """Runs the samples of a probability request on `client` and assembles them (a
    NativeProbability), reporting the samples done to `stages`; `args` are
    design_probability's (scatter, samples, seed, correlate, confidence, accuracy, shard,
    target_halfwidth)."""
    scatter, samples, seed, correlate, confidence, accuracy, shard, target = args
    base, points = _stiction.design_probability_plan(
        scene, scatter, samples, seed, correlate, confidence, accuracy, shard, target,
        count_outside_validity=count_outside_validity,
    )
    report = (stages or Stages(None)).run(len(points))
    answers = _run_points(client, base, points, "sample", report) if points else []
    pairs = [(index, answer) for (index, _), answer in zip(points, answers)]
    return _stiction.design_probability_assemble(
        scene, scatter, pairs, samples, seed, correlate, confidence, accuracy, shard, target, exact,
        count_outside_validity=count_outside_validity,
    )
