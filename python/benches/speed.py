"""Speed of the Python package against the library and the command line
(docs/performance.md, "The Python package").

    python python/benches/speed.py --law LAW.json [--rust SPEED_BIN] [--cli STICTION_BIN]

* the contact law's vectorised evaluation per point (1e5 points, one call), against the
  same points evaluated by the library in Rust (`python/examples/speed.rs`, --rust);
* the rough surface's pressure per point (the paper's switch, fast and accurate);
* a design map (16 points, fast) run by `stiction design map` (--cli), by
  `stiction.design_map` here, and on a Dask LocalCluster of two worker processes.

Prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import stiction


def points(n: int) -> tuple:
    """The points of `speed.rs`: the same doubles, by the same operations."""
    i = np.arange(n, dtype=float)
    d = 5e-9 + 20e-9 * np.fmod(i * 0.6180339887498949, 1.0)
    m = 5e-9 + 4e-9 * np.fmod(i * 0.7548776662466927, 1.0)
    return d, m


def best(repeats: int, f) -> float:
    out = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        out.append(time.perf_counter() - t)
    return min(out)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--law", required=True)
    ap.add_argument("--rust", help="the speed example binary (python/examples/speed.rs)")
    ap.add_argument("--cli", help="the stiction binary")
    ap.add_argument("--n", type=int, default=100_000)
    ap.add_argument("--map-points", type=int, default=16)
    a = ap.parse_args()
    out: dict = {"python": sys.version.split()[0], "cores": os.cpu_count()}

    law = stiction.ContactLaw.load(a.law)
    d, m = points(a.n)
    t = best(7, lambda: law.evaluate(d, m, "retract"))
    out["law_evaluate_ns_per_point"] = t / a.n * 1e9
    out["law_evaluate_one_point_call_us"] = best(200, lambda: law.evaluate(7e-9, 6e-9, "retract")) * 1e6
    loop = d[:2000], m[:2000]
    t = best(3, lambda: [law.evaluate(float(x), float(y), "retract") for x, y in zip(*loop)])
    out["law_evaluate_python_loop_ns_per_point"] = t / 2000 * 1e9

    sd, _ = points(2000)
    for accuracy in ("fast", "accurate"):
        s = stiction.Surface(stiction.Scene.paper("switch"), accuracy=accuracy)
        t = best(3, lambda: s.pressure(sd, 5e-9, "retract"))
        out[f"surface_{accuracy}_ns_per_point"] = t / len(sd) * 1e9

    if a.rust:
        r = subprocess.run([a.rust, a.law, str(a.n)], capture_output=True, text=True, check=True)
        out["rust"] = json.loads(r.stdout)

    scene = stiction.Scene.paper("switch")
    vary = [f"surface.sigma_s=2e-9:1e-7:log:{a.map_points}"]
    if a.cli:
        with tempfile.TemporaryDirectory() as tmp:
            def cli_map() -> None:
                subprocess.run(
                    [a.cli, "design", "map", "--vary", vary[0], "--accuracy", "fast", "--out", os.path.join(tmp, "m")],
                    check=True, capture_output=True,
                )

            out["map_cli_s"] = best(3, cli_map)
    out["map_python_s"] = best(3, lambda: stiction.design_map(scene, vary, accuracy="fast"))
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        pass
    else:
        t0 = time.perf_counter()
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        client.run(lambda: __import__("stiction") and None)
        out["dask_startup_s"] = time.perf_counter() - t0
        out["map_dask_s"] = best(3, lambda: stiction.design_map(scene, vary, accuracy="fast", client=client))
        same = stiction.design_map(scene, vary, accuracy="fast", client=client).to_json()
        out["map_dask_equals_local"] = same == stiction.design_map(scene, vary, accuracy="fast").to_json()
        client.close()
        cluster.close()
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
