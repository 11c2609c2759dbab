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

import uuid
from typing import Any, List, Optional, Sequence, Tuple, Union

from . import _stiction


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
) -> Any:
    """Runs the points of a map on `client` and assembles them (a NativeMap)."""
    base, points = _stiction.design_map_plan(scene, vary, accuracy, shard, require)
    if not points:
        return _stiction.design_map_assemble(scene, vary, [], accuracy, shard, require)
    answers = _run_points(client, base, points, "design-point")
    pairs = [(index, answer) for (index, _), answer in zip(points, answers)]
    return _stiction.design_map_assemble(scene, vary, pairs, accuracy, shard, require)


def _run_points(client: Any, base: str, points: List[Tuple[int, Any]], what: str) -> List[Any]:
    """The answers of `points` (index, values) evaluated on `client` against `base`: on
    dask.distributed the scene once per worker and one task per point (a key of its own,
    hash=False: a run again with the same scene must not meet the release of the previous
    run's copy); on a concurrent.futures.Executor one submission per point."""
    if hasattr(client, "scatter") and hasattr(client, "gather"):
        base_ref = client.scatter(base, broadcast=True, hash=False)
        run = uuid.uuid4().hex[:12]
        futures = [
            client.submit(evaluate_point, base_ref, values, key=f"stiction-{what}-{run}-{index}", pure=False)
            for index, values in points
        ]
        return client.gather(futures)
    futures = [client.submit(evaluate_point, base, values) for _, values in points]
    return [f.result() for f in futures]


def probability_on_client(client: Any, scene: Any, args: tuple, exact: bool, count_outside_validity: bool = False) -> Any:
    """Runs the samples of a probability request on `client` and assembles them (a
    NativeProbability); `args` are design_probability's (scatter, samples, seed,
    correlate, confidence, accuracy, shard, target_halfwidth)."""
    scatter, samples, seed, correlate, confidence, accuracy, shard, target = args
    base, points = _stiction.design_probability_plan(
        scene, scatter, samples, seed, correlate, confidence, accuracy, shard, target,
        count_outside_validity=count_outside_validity,
    )
    answers = _run_points(client, base, points, "sample") if points else []
    pairs = [(index, answer) for (index, _), answer in zip(points, answers)]
    return _stiction.design_probability_assemble(
        scene, scatter, pairs, samples, seed, correlate, confidence, accuracy, shard, target, exact,
        count_outside_validity=count_outside_validity,
    )
