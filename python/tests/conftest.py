"""Fixtures of the Python package's tests: the command line to compare with, the paper's
scenes, a small tabulated contact law.

The CLI comparisons need the `stiction` binary: $STICTION_CLI, else
target/release/stiction of the repository (or of $CARGO_TARGET_DIR). Without it they are
skipped, unless $STICTION_REQUIRE_CLI=1 (CI), which makes a missing binary a failure.
"""

from __future__ import annotations

import json
import os
import pathlib
import subprocess

import pytest

try:
    import stiction
    from stiction import _stiction  # noqa: F401  (the compiled extension)
except ImportError as e:  # pragma: no cover - a message for a wrong setup
    raise ImportError(
        "the stiction extension is not built: `pip install ./python` from the repository root "
        "(or `maturin develop` in python/), and run pytest from outside python/ or as `pytest` "
        f"(not `python -m pytest` inside python/, which imports the source folder): {e}"
    ) from e

REPO = pathlib.Path(__file__).resolve().parents[2]


def _find_cli() -> pathlib.Path | None:
    candidates = []
    if os.environ.get("STICTION_CLI"):
        candidates.append(pathlib.Path(os.environ["STICTION_CLI"]))
    if os.environ.get("CARGO_TARGET_DIR"):
        candidates.append(pathlib.Path(os.environ["CARGO_TARGET_DIR"]) / "release" / "stiction")
    candidates.append(REPO / "target" / "release" / "stiction")
    for c in candidates:
        if c.is_file() and os.access(c, os.X_OK):
            return c
    return None


class Cli:
    """The `stiction` command line."""

    def __init__(self, path: pathlib.Path) -> None:
        self.path = path

    def run(self, *args: str, cwd: str | None = None) -> subprocess.CompletedProcess:
        return subprocess.run(
            [str(self.path), *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600
        )

    def json(self, *args: str, cwd: str | None = None):
        p = self.run(*args, cwd=cwd)
        assert p.returncode == 0, f"stiction {' '.join(map(str, args))}: {p.stderr}"
        return json.loads(p.stdout)


@pytest.fixture(scope="session")
def cli() -> Cli:
    path = _find_cli()
    if path is None:
        message = (
            "the stiction CLI is not built (cargo build --release, or set STICTION_CLI): "
            "the comparisons with it are skipped"
        )
        if os.environ.get("STICTION_REQUIRE_CLI") == "1":
            pytest.fail(message)
        pytest.skip(message)
    return Cli(path)


@pytest.fixture(scope="session")
def paper_switch() -> stiction.Scene:
    return stiction.Scene.paper("switch")


@pytest.fixture(scope="session")
def law_file(tmp_path_factory) -> pathlib.Path:
    """A small contact law of the paper's switch (a uniform grid of 6 histories), written
    by the package."""
    r = stiction.tabulate_law(stiction.Scene.paper("switch"), d_min="9e-9:5e-9:6", points=24)
    path = tmp_path_factory.mktemp("law") / "law.json"
    r.law.save(path)
    return path
