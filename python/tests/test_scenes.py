"""Scenes from dicts, TOML and JSON files, validated by the library: the same keys, the
same messages and the same category of error as the command line."""

from __future__ import annotations

import json
import math
import pickle

import pytest

import stiction


def test_toml_json_and_dict_scenes_are_the_same_scene(tmp_path, paper_switch):
    toml_path = tmp_path / "s.toml"
    toml_path.write_text(paper_switch.to_toml())
    as_dict = paper_switch.to_dict()
    json_path = tmp_path / "s.json"
    json_path.write_text(json.dumps(as_dict))
    from_toml = stiction.load_scene(toml_path)
    from_str_path = stiction.load_scene(str(json_path))
    from_dict = stiction.load_scene(as_dict)
    assert from_toml == from_str_path == from_dict == paper_switch
    assert from_toml.file == str(toml_path)
    assert from_dict.file == "<dict>"
    assert from_dict.kind == "switch"


def test_a_misspelled_key_raises_input_error_naming_the_key(paper_switch):
    d = paper_switch.to_dict()
    d["surface"]["sigma_ss"] = 1e-8
    with pytest.raises(stiction.InputError) as e:
        stiction.load_scene(d)
    assert "surface.sigma_ss" in str(e.value)
    assert e.value.key == "surface.sigma_ss"
    assert "did you mean `surface.sigma_s`" in str(e.value)
    assert isinstance(e.value, ValueError) and isinstance(e.value, stiction.StictionError)
    assert e.value.category == "input"


def test_a_value_outside_its_domain_names_key_value_and_range(paper_switch):
    d = paper_switch.to_dict()
    d["surface"]["sigma_s"] = -1.0
    with pytest.raises(stiction.InputError) as e:
        stiction.load_scene(d)
    assert str(e.value) == "<dict>: invalid `surface.sigma_s` = -1e0: must be finite and in [1e-11, 1e-6]"
    assert e.value.key == "surface.sigma_s"


def test_a_missing_required_key_is_named():
    with pytest.raises(stiction.InputError) as e:
        stiction.load_scene({"kind": "switch"})
    assert "missing `contact.youngs_modulus`" in str(e.value)


def test_none_and_foreign_values_are_refused_with_the_key(paper_switch):
    d = paper_switch.to_dict()
    d["contact"]["radius"] = None
    with pytest.raises(stiction.InputError, match=r"`contact.radius` = null"):
        stiction.load_scene(d)
    d["contact"]["radius"] = object()
    with pytest.raises(stiction.InputError, match=r"`contact.radius` = a object"):
        stiction.load_scene(d)


def test_messages_are_the_command_lines(tmp_path, cli, paper_switch):
    bad = paper_switch.copy()
    bad.set("surface.sigma_s", 2e-5)
    path = tmp_path / "bad.toml"
    path.write_text(bad.to_toml())
    p = cli.run("switch", "--scene", path)
    assert p.returncode == 2
    with pytest.raises(stiction.InputError) as e:
        stiction.load_scene(path)
    # the CLI prints the library's message (with its own prefix)
    assert str(e.value).replace(str(path), "") in p.stderr.replace(str(path), "")
    assert "surface.sigma_s" in str(e.value) and "2e-5" in str(e.value)


def test_an_unreadable_file_is_input(tmp_path):
    with pytest.raises(stiction.InputError, match="cannot read"):
        stiction.load_scene(tmp_path / "absent.toml")
    (tmp_path / "bad.json").write_text("{ not json")
    with pytest.raises(stiction.InputError, match="JSON parse error"):
        stiction.load_scene(tmp_path / "bad.json")


def test_infinity_is_written_as_float_or_the_word():
    base = stiction.Scene.paper("asperity").to_dict()
    base["contact"]["plasticity_law"] = "elastic"
    base["contact"].pop("effective_radius", None)
    base["contact"].pop("plasticity", None)
    for inf in (math.inf, "inf"):
        base["contact"]["yield_stress"] = inf
        s = stiction.load_scene(base)
        assert s.get("contact.yield_stress") in (math.inf, "inf")
        assert stiction.Asperity(s).delta_cp == math.inf


def test_edits_are_checked_when_the_scene_is_used(paper_switch):
    s = paper_switch.copy()
    s.set("surface.sigma_s", 1e-8)
    assert s.get("surface.sigma_s") == 1e-8
    s.validate()
    s.set("surface.sigma_s", 1.0)
    with pytest.raises(stiction.InputError, match="surface.sigma_s"):
        s.validate()
    with pytest.raises(stiction.InputError, match="surface.sigma_s"):
        stiction.run(s)
    t = paper_switch.with_values({"switch.impact_energy": None, "switch.k_s": 1e10})
    assert t.get("switch.k_s") == 1e10 and t.get("switch.impact_energy") is None
    assert paper_switch.get("switch.k_s") is None  # the original is unchanged


def test_scenes_pickle_as_their_text(paper_switch):
    s = pickle.loads(pickle.dumps(paper_switch))
    assert s == paper_switch and s.kind == "switch"


def test_the_key_registry_is_exposed():
    keys = {k["key"]: k for k in stiction.scene_keys("switch")}
    assert keys["surface.sigma_s"]["unit"] == "m"
    assert "surface.sigma_s" in stiction.variable_fields()
    assert keys["contact.yield_modulus"]["accepts"]
