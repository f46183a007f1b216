"""The listing functions, scenes and camera paths: no OpenGL needed."""
import json

import numpy as np
import pytest

import bounce


def test_scenes_lists_the_builtins_with_parameters():
    scenes = bounce.scenes()
    names = [s["name"] for s in scenes]
    assert "cornell-box" in names and "cornell-box-dynamic" in names and "atrium" in names
    atrium = next(s for s in scenes if s["name"] == "atrium")
    assert "triangles" in atrium["params"] and atrium["description"]


def test_techniques_carry_settings_and_reference_scope(cli):
    techniques = bounce.techniques()
    names = [t["name"] for t in techniques]
    # The same registry as `bounce list`: every name, in its order.
    listed = cli("list", "--techniques", "--names").stdout.split()
    assert names == listed
    for t in techniques:
        assert t["summary"] and t["paper"]
        assert set(t["scope"]) == {"bounces", "indirect_only", "diffuse_only", "component"}
        assert t["scope"]["component"] in ("full", "direct", "indirect")
        for s in t["settings"]:
            assert set(s) == {"name", "type", "default", "range", "doc", "profile_defaults"} and s["name"] and s["type"] and s["doc"]
    rsm = bounce.technique("rsm")
    grid = next(s for s in rsm["settings"] if s["name"] == "vplGrid")
    assert grid["type"] == "int" and grid["default"] and grid["range"]
    assert rsm["scope"] == {"bounces": 1, "indirect_only": True, "diffuse_only": False, "component": "indirect"}
    assert bounce.reference_scope("rsm") == {"bounces": 1, "indirect_only": True, "diffuse_only": False}
    assert bounce.technique("ambient")["scope"]["bounces"] == "unbounded"
    with pytest.raises(bounce.Error, match="unknown technique 'nope'"):
        bounce.technique("nope")
    renderer = {s["name"] for s in bounce.renderer_settings()}
    assert "shadowMapSize" in renderer and "exposure" in renderer


def test_scene_load_properties_and_copy():
    scene = bounce.Scene.load("furnace", albedo=0.25, emission=2)
    assert scene.name == "furnace" and scene.params == {"albedo": "0.25", "emission": "2"}
    assert scene.source.startswith("builtin:") and scene.frame_rate > 0 and scene.triangles > 0
    box = bounce.Scene.load("cornell-box-dynamic")
    light = box.lights[0]
    assert set(light) == {"name", "type", "position", "direction", "animated"} and light["type"] == "spot"
    assert any(o["animated"] for o in box.objects)
    assert set(box.camera) == {"position", "target", "up", "fov"}
    copy = box.copy()
    copy.move_light(0, (0.1, 0.0, 0.0))
    assert copy.lights[0]["position"][0] == pytest.approx(light["position"][0] + 0.1)
    assert box.lights[0]["position"] == light["position"], "a copy is independent"
    box.set_light(light["name"], direction=(0, -2, 0))
    assert box.lights[0]["direction"] == pytest.approx([0, -1, 0]), "directions are normalised"
    box.set_camera((0, 1, 4), (0, 1, 0), fov=0.5)
    assert box.camera["position"] == pytest.approx([0, 1, 4]) and box.camera["fov"] == pytest.approx(0.5)


def test_camera_path(tmp_path):
    path = tmp_path / "path.json"
    path.write_text(json.dumps({
        "format": "bounce-camera-path", "version": 1, "scene": "cornell-box",
        "keys": [{"time": 0.0, "position": [0, 1, 3], "target": [0, 1, 0], "up": [0, 1, 0], "verticalFov": 0.7},
                 {"time": 1.0, "position": [1, 1, 3], "target": [0, 1, 0], "up": [0, 1, 0], "verticalFov": 0.7}],
        "lights": []}))
    p = bounce.CameraPath.load(path)
    assert p.scene == "cornell-box" and p.frame_range(30.0) == (0, 30)
    assert p.evaluate(0.5)["position"] == pytest.approx([0.5, 1, 3])
    scene = bounce.Scene.load("cornell-box")
    scene.apply_camera_path(p, 1.0)
    assert scene.camera["position"] == pytest.approx([1, 1, 3])


def test_read_and_write_images(tmp_path):
    image = np.random.default_rng(1).random((5, 7, 3), dtype=np.float32) * 4
    bounce.write_image(tmp_path / "a.exr", image)
    back = bounce.read_image(tmp_path / "a.exr")
    assert back.dtype == np.float32 and back.shape == (5, 7, 3) and np.array_equal(back, image)
    bounce.write_image(tmp_path / "a.png", image)
    png = bounce.read_image(tmp_path / "a.png")
    assert png.shape == (5, 7, 3) and png.max() <= 1.0
