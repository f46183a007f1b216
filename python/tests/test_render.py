"""Renderers: arrays, run records, the CLI's pixels bit for bit, and the viewer's scene edits."""
import numpy as np
import pytest

import bounce

SIZE = (32, 24)  # tiny: every render here takes milliseconds on llvmpipe


def test_frame_shapes_dtypes_and_record(gl):
    with bounce.Renderer("cornell-box", "rsm", SIZE, settings={"vplGrid": 8, "renderer.shadowMapSize": 256}) as r:
        image, record = r.frame(0)
        assert image.dtype == np.float32 and image.shape == (24, 32, 3) and image.flags.c_contiguous
        assert np.isfinite(image).all() and image.mean() > 0
        assert record["technique"] == "rsm" and record["size"] == [32, 24] and record["component"] == "full"
        assert record["settings"]["vplGrid"] == 8 and record["renderer"]["shadowMapSize"] == 256
        frame = record["frames"][0]
        assert frame["gpu_ms"]["frame"] >= 0 and "gbuffer" in frame["gpu_ms"]
        assert frame["counters"] and frame["resources"]["gl_objects"] > 0
        assert r.technique == "rsm" and r.size == (32, 24) and r.settings["technique"]["vplGrid"] == 8
        indirect, _ = r.frame(1, component="indirect")
        direct, _ = r.frame(1, component="direct")
        full, _ = r.frame(1)
        np.testing.assert_allclose(full, direct + indirect, rtol=1e-5, atol=1e-6)
        images, record = r.frames(3)
        assert images.shape == (3, 24, 32, 3) and images.dtype == np.float32
        assert [f["frame"] for f in record["frames"]] == [2, 3, 4] and "median_ms" in record


@pytest.mark.parametrize("technique,scene,frames", [("direct", "cornell-box", 1), ("rsm", "cornell-box-dynamic", 3)])
def test_same_pixels_as_the_cli(gl, cli, tmp_path, technique, scene, frames):
    """`bounce render --frames N` writes frame N-1's EXR; the module's frames 0..N-1 end on the same floats."""
    out = tmp_path / "cli.exr"
    done = cli("render", "--scene", scene, "--technique", technique, "--size", "32x24", "--frames", frames,
               "--set", "renderer.shadowMapSize=256", "--out", out)
    assert done.returncode == 0, done.stderr
    expected = bounce.read_image(out)
    with bounce.Renderer(scene, technique, SIZE, settings={"renderer.shadowMapSize": 256}) as r:
        images, _ = r.frames(frames, start=0)
    assert np.array_equal(images[-1], expected), "bit-identical to the CLI's EXR"


def test_moving_the_light_the_object_and_the_camera(gl):
    scene = bounce.Scene.load("cornell-box-dynamic")
    with bounce.Renderer(scene, "direct", SIZE) as r:
        base, _ = r.frame(0, time=0.0)
        held, _ = r.frame(5, time=0.0)
        assert np.array_equal(base, held), "time held: the same picture"
        scene.move_light(0, (0.2, 0.0, 0.0))
        moved, _ = r.frame(6, time=0.0)
        assert not np.array_equal(moved, base), "a moved light changes the next frame"
        scene.move_light(0, (-0.2, 0.0, 0.0))
        back, _ = r.frame(7, time=0.0)
        np.testing.assert_allclose(back, base, atol=1e-6)
        block = next(i for i, o in enumerate(scene.objects) if o["animated"])
        scene.move_object(block, (0.0, 0.3, 0.0))
        lifted, _ = r.frame(8, time=0.0)
        assert np.abs(lifted - base).max() > 0.01, "a moved object is uploaded again"
        scene.move_object(block, (0.0, -0.3, 0.0))
        camera = scene.camera
        scene.set_camera([p + 0.3 for p in camera["position"]], camera["target"])
        turned, _ = r.frame(9, time=0.0)
        assert np.abs(turned - base).max() > 0.01
        scene.set_camera(**camera)
        again, _ = r.frame(10, time=0.0)
        np.testing.assert_allclose(again, base, atol=1e-6)


def test_renderers_share_one_context_and_release_their_objects(gl):
    before = bounce.resources()["gl_objects"]
    renderers = [bounce.Renderer("cornell-box", t, 16) for t in ("direct", "ambient", "rsm")]
    during = bounce.resources()["gl_objects"]
    assert during > before
    for r in renderers:
        r.frame(0)
        r.close()
    assert bounce.resources()["gl_objects"] == before
    info = bounce.gl_info()
    assert info["version"] and info["platform"].startswith("egl")
