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


def _sur(path, objects, dx=10e-9):
    """A Digital Surf .sur file of `objects` ((name, heights in m with NaN undefined), one
    after the other), written as crates/topography/tests/encoders writes it: 32-bit
    integers, spacings in um, heights in nm from a 1 nm offset, NaN as zmin - 2."""
    import struct

    out = bytearray()
    for name, z in objects:
        ny, nx = z.shape
        big = float(np.nanmax(np.abs(z))) + 1e-9
        q = big / (0.9 * 2.0**31)
        h = bytearray(512)
        h[0:12] = b"DIGITAL SURF"
        struct.pack_into("<hHhh", h, 12, 0, len(objects), 1, 2)
        h[20:20 + len(name)] = name.encode()
        h[50:55] = b"tests"
        struct.pack_into("<hh", h, 86, int(np.isnan(z).any()), 1)
        zmin = -(2**31) + 2
        struct.pack_into("<hiiiii", h, 98, 32, zmin, 2**31 - 1, nx, ny, nx * ny)
        struct.pack_into("<fff", h, 120, dx * 1e6, dx * 1e6, q * 1e9)
        for at, text in ((132, b"X"), (148, b"Y"), (164, b"Z"), (180, b"\xb5m"), (196, b"\xb5m"), (212, b"nm"),
                         (228, b"\xb5m"), (244, b"\xb5m"), (260, b"nm")):
            h[at:at + len(text)] = text
        struct.pack_into("<fff", h, 276, 1.0, 1.0, 1.0)
        comment = b"$_tests\n"
        struct.pack_into("<hh", h, 334, len(comment), 0)
        struct.pack_into("<f", h, 474, 1.0)
        dz = float(np.float32(q * 1e9)) * 1e-9
        raw = np.where(np.isnan(z), zmin - 2, np.round((np.nan_to_num(z) - 1e-9) / dz)).astype("<i4")
        out += h + comment + raw.tobytes()
    path.write_bytes(bytes(out))
    return path


def test_undefined_points_and_channels_as_the_command_line(tmp_path, cli):
    _, z = _map(tmp_path)
    z = z * 1e-9
    holes = z.copy()
    holes[3, 5] = holes[20, 40] = np.nan
    path = _sur(tmp_path / "two.sur", [("Height", holes), ("Height 2", 2.0 * holes)])
    # refused by default, naming the option
    with pytest.raises(stiction.InputError, match="undefined"):
        stiction.topography(path)
    t = stiction.topography(path, undefined="fill")
    d = t.to_dict()
    assert d == cli.json("topography", str(path), "--undefined", "fill", "--format", "json")
    assert d["source"]["undefined_points"] == 2
    assert d["source"]["format"] == "sur"
    channels = d["source"]["channels"]
    assert len(channels) == 2 and d["source"]["title"] == channels[0]
    # the second channel by index and by name, as the command's --channel
    by_index = stiction.topography(path, undefined="fill", channel=1).to_dict()
    assert by_index == cli.json("topography", str(path), "--undefined", "fill", "--channel", "1", "--format", "json")
    assert by_index["source"]["title"] == channels[1]
    by_name = stiction.topography(path, undefined="fill", channel=channels[1]).to_dict()
    assert by_name["summits"] == by_index["summits"]
    assert by_index["rms_height"] == pytest.approx(2.0 * d["rms_height"], rel=1e-6)
    assert stiction.topography(path, undefined="fill", channel="0").to_dict()["summits"] == d["summits"]
    # errors name the option
    with pytest.raises(stiction.InputError, match="channel"):
        stiction.topography(path, undefined="fill", channel="Phase")
    with pytest.raises(stiction.InputError, match="channel"):
        stiction.topography(path, undefined="fill", channel=-1)
    with pytest.raises(stiction.InputError, match="undefined"):
        stiction.topography(path, undefined="zero")
    with pytest.raises(stiction.InputError, match="undefined"):
        stiction.topography(path, undefined=True)


def test_the_band_as_the_command_line(tmp_path, cli):
    path, _ = _map(tmp_path)
    plain = stiction.topography(path).to_dict()
    assert plain["cutoff"]["applied"] is False and plain["band"][0]["chosen"] is True
    cut = stiction.topography(path, cutoff=4e-8)
    assert cut.to_dict() == cli.json("topography", str(path), "--cutoff", "4e-8", "--format", "json")
    assert cut.cutoff["applied"] is True and cut.cutoff["wavelength"] == 4e-8
    assert cut.summits["asperity_density"] < plain["summits"]["asperity_density"]
    # the pixel scale: the map as sampled
    assert stiction.topography(path, cutoff=1e-8).to_dict()["summits"] == plain["summits"]
    contact = stiction.topography(path, contact_radius=2e-8)
    assert contact.to_dict() == cli.json("topography", str(path), "--contact-radius", "2e-8", "--format", "json")
    assert contact.cutoff["from"] == "contact_radius"
    for kwargs, name in (
        ({"cutoff": -1e-8}, "cutoff"),
        ({"cutoff": 1e-3}, "cutoff"),
        ({"cutoff": "40 nm"}, "cutoff"),
        ({"contact_radius": 0.0}, "contact_radius"),
        ({"contact_radius": True}, "contact_radius"),
    ):
        with pytest.raises(stiction.InputError, match=name):
            stiction.topography(path, **kwargs)


def test_a_scene_takes_its_surface_from_a_map_beside_it(tmp_path, cli):
    path, _ = _map(tmp_path)
    scene = tmp_path / "surface.toml"
    # the paper's surface scene, its sigma_s from the map
    paper = cli.run("scene", "--print", "surface").stdout
    lines = [l for l in paper.splitlines() if not l.split("#")[0].strip().startswith(("sigma_s", "unload_from"))]
    lines.insert(lines.index("[surface]") + 1, 'topography = "map.txt"\ntopography_cutoff = 0.0')
    scene.write_text("\n".join(lines) + "\n")
    s = stiction.load_scene(scene)
    report = stiction.topography(path)
    resolved = s.resolved()
    assert resolved["surface"]["sigma_s"] == report.summits["sigma_s"]
    assert resolved["surface"]["topography"] == str(path)
    assert resolved["contact"]["radius"] == 4e-6  # the scene's own, as it gives one
    r = stiction.run(s)
    assert r.to_dict()["scene"]["surface"]["sigma_s"] == report.summits["sigma_s"]
    # an option without the map names the key
    with pytest.raises(stiction.InputError, match="surface.topography_route"):
        stiction.load_scene({"kind": "surface", "surface": {"topography_route": "spectral"}}).resolved()
