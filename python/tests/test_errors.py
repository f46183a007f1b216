"""Every class of bad input raises bounce.Error with the command line's one-line message, and the
interpreter goes on (docs/reliability.md's bad-input classes, seen from Python)."""
import json

import numpy as np
import pytest

import bounce
from conftest import cli_message


def raises(fn, *args, **kwargs):
    with pytest.raises(bounce.Error) as e:
        fn(*args, **kwargs)
    message = str(e.value)
    assert message and "\n" not in message, "one line"
    return message


def test_unknown_technique_and_setting_carry_the_cli_messages(gl, cli, tmp_path):
    out = tmp_path / "x.exr"
    expected = cli_message(cli("render", "--scene", "cornell-box", "--technique", "nope", "--size", "8x8", "--out", out), "render")
    assert raises(bounce.Renderer, "cornell-box", "nope", 8) == expected
    expected = cli_message(cli("render", "--scene", "cornell-box", "--technique", "rsm", "--set", "vplGird=8", "--size", "8x8",
                               "--out", out), "render")
    assert raises(bounce.Renderer, "cornell-box", "rsm", 8, settings={"vplGird": 8}) == expected
    # Out of range and unparsable values.
    expected = cli_message(cli("render", "--scene", "cornell-box", "--technique", "rsm", "--set", "vplGrid=100000",
                               "--size", "8x8", "--out", out), "render")
    assert raises(bounce.Renderer, "cornell-box", "rsm", 8, settings={"vplGrid": 100000}) == expected
    assert "vplGrid" in raises(bounce.Renderer, "cornell-box", "rsm", 8, settings={"vplGrid": "many"})
    assert "--size" in raises(bounce.Renderer, "cornell-box", "direct", 0)
    assert "--size" in raises(bounce.Renderer, "cornell-box", "direct", (20000, 8))
    assert "--component" in raises(bounce.Renderer, "cornell-box", "direct", 8, component="both")
    assert "another technique" in raises(bounce.Renderer, "cornell-box", "rsm", 8, settings={"isr.lightCoarsest": 8})


def test_bad_scenes(cli, tmp_path):
    broken = tmp_path / "broken.json"
    broken.write_text('{"objects": [')
    expected = cli_message(cli("reference", "--scene", broken, "--size", "8x8", "--out", tmp_path / "r.exr"), "reference")
    assert raises(bounce.Scene.load, str(broken)) == expected
    assert "no-such" in raises(bounce.Scene.load, str(tmp_path / "no-such.json"))
    assert "unknown" in raises(bounce.Scene.load, "cornell-box", colour="red").lower()
    assert "wallThickness" in raises(bounce.Scene.load, "two-rooms", wallThickness=-1)
    assert "nowhere" in raises(bounce.Scene.load, "nowhere-scene")
    scene = bounce.Scene.load("cornell-box")
    assert "light 'x'" in raises(scene.set_light, "x", (0, 0, 0))
    assert "static" in raises(scene.move_object, 0, (0.1, 0, 0))
    assert "finite" in raises(scene.move_light, 0, (float("nan"), 0, 0))
    assert "parallel" in raises(scene.set_camera, (0, 1, 3), (0, 1, 0), up=(0, 0, 1))


def test_bad_reference_and_photon_map_arguments(cli, tmp_path):
    scene = bounce.Scene.load("cornell-box")
    expected = cli_message(cli("reference", "--scene", "cornell-box", "--size", "8x8", "--spp", "0", "--out", tmp_path / "r.exr"),
                           "reference")
    assert raises(bounce.reference, scene, 8, spp=0) == expected
    expected = cli_message(cli("reference", "--scene", "cornell-box", "--size", "8x8", "--bounces", "-3", "--out",
                               tmp_path / "r.exr"), "reference")
    assert raises(bounce.reference, scene, 8, spp=1, bounces=-3) == expected
    assert "--time-limit" in raises(bounce.reference, scene, 8, spp=1, time_limit=-1.0)
    assert "--threads" in raises(bounce.reference, scene, 8, spp=1, threads=-2)
    assert "--size" in raises(bounce.reference, scene, 100000, spp=1)
    assert "--k" in raises(bounce.photon_map, scene, 8, k=1)
    assert "--photons" in raises(bounce.photon_map, scene, 8, photons=0)
    dark = tmp_path / "dark.json"
    dark.write_text(json.dumps({"objects": [], "lights": []}))
    with pytest.raises(bounce.Error):
        bounce.reference(bounce.Scene.load(str(dark)), 8, spp=1)


def test_bad_compare_inputs(tmp_path):
    a = np.zeros((4, 4, 3), np.float32)
    assert "differ in size" in raises(bounce.compare, a, np.zeros((4, 5, 3), np.float32))
    assert "H x W x 3" in raises(bounce.compare, np.zeros((4, 4)), a)
    nan = a.copy()
    nan[1, 1, 1] = np.nan
    assert "test image" in raises(bounce.compare, nan, a)
    assert "unknown metric 'psnrr'" in raises(bounce.compare, a, a, metrics=["psnrr"])
    assert "--heatmap-metric" in raises(bounce.compare, a, a, heatmap="hot")
    assert "--tonemap" in raises(bounce.compare, a, a, tonemap="filmic")
    assert "--ppd" in raises(bounce.compare, a, a, ppd=-1)
    assert "no-such.exr" in raises(bounce.compare, str(tmp_path / "no-such.exr"), a)
    assert "variance image" in raises(bounce.compare, a, a, variance=np.zeros((2, 2, 3), np.float32))
    with pytest.raises(TypeError):
        bounce.compare(a, a, exposure="bright")


def test_bad_studies(tmp_path):
    study = tmp_path / "study.json"
    study.write_text(json.dumps({"scenes": ["cornell-box"], "techniques": ["direct"], "sceens": []}))
    assert "sceens" in raises(bounce.sweep, study)
    assert "not a folder" in raises(bounce.report, tmp_path / "none")


def test_closed_renderer(gl):
    r = bounce.Renderer("cornell-box", "direct", 8)
    r.close()
    assert r.closed
    assert "closed" in raises(r.frame, 0)
    r.close()  # twice is fine
