"""`stiction.topography` (issue 45 item 3): the CLI's analysis of a height map from Python,
its report equal to `stiction topography FILE --format json`, the map as a numpy array and
the scene fragment that `--out` writes."""

from __future__ import annotations

import numpy as np
import pytest

import stiction


def _map(tmp_path):
    # a rough 64 x 48 map of nm heights (seeded), 10 nm spacing, in a text matrix
    rng = np.random.default_rng(5)
    z = rng.normal(0.0, 3.0, (48, 64))
    z = (z + np.roll(z, 1, 0) + np.roll(z, 1, 1) + np.roll(z, (1, 1), (0, 1))) / 4.0
    path = tmp_path / "map.txt"
    lines = ["# spacing = 10 nm", "# height_unit = nm"] + [" ".join(f"{v:.6f}" for v in row) for row in z]
    path.write_text("\n".join(lines) + "\n")
    return path, z


def test_the_report_is_the_command_lines_and_the_map_is_the_files(tmp_path, cli):
    path, z = _map(tmp_path)
    t = stiction.topography(path)
    assert t.to_dict() == cli.json("topography", str(path), "--format", "json")
    assert t.height_map.shape == (48, 64)
    assert np.allclose(t.height_map, z * 1e-9, rtol=1e-6, atol=1e-15)
    assert t.dx == pytest.approx(10e-9) and t.dy == pytest.approx(10e-9)
    assert t.rms_height > 0 and t.grid["nx"] == 64 and t.grid["ny"] == 48
    assert "[surface]" in t.fragment and "asperity_density" in t.fragment
    out = tmp_path / "out"
    cli.json("topography", str(path), "--format", "json", "--out", str(out))
    assert (out / "surface.toml").read_text() == t.fragment
    # the options, as the command's
    spectral = stiction.topography(path, route="spectral", detrend="mean")
    assert spectral.to_dict() == cli.json(
        "topography", str(path), "--route", "spectral", "--detrend", "mean", "--format", "json"
    )


def test_bad_options_are_input_errors_naming_them(tmp_path):
    path, _ = _map(tmp_path)
    for kwargs, name in (
        ({"detrend": "poly:9"}, "detrend"),
        ({"route": "peaks"}, "route"),
        ({"file_format": "vk6"}, "file_format"),
        ({"spacing": -1.0}, "spacing"),
        ({"height_unit": "furlong"}, "height_unit"),
        ({"spacing": "10nm"}, "spacing"),
    ):
        with pytest.raises(stiction.InputError, match=name):
            stiction.topography(path, **kwargs)
    with pytest.raises(stiction.InputError, match="no_such_file"):
        stiction.topography(tmp_path / "no_such_file.txt")
