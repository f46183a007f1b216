"""Path-traced references, photon maps, and the GIL released while they run."""
import threading
import time

import numpy as np

import bounce


def test_reference_image_variance_and_noise(cli, tmp_path):
    scene = bounce.Scene.load("cornell-box")
    ref = bounce.reference(scene, (16, 12), spp=8, seed=3, **bounce.reference_scope("rsm"))
    assert ref.image.shape == (12, 16, 3) and ref.image.dtype == np.float32
    assert ref.variance.shape == (12, 16, 3) and (ref.variance >= 0).all() and ref.variance.max() > 0
    assert ref.samples_per_pixel == 8 and 0 < ref.noise["meanPixelRelativeStdError"] < 10
    assert ref.noise["floor"]["relMse"] > 0 and ref.record["settings"]["indirectOnly"] is True
    # The CLI's image for the same run, bit for bit (the path tracer is deterministic per seed).
    done = cli("reference", "--scene", "cornell-box", "--size", "16x12", "--spp", 8, "--seed", 3, "--bounces", 1,
               "--indirect-only", "--out", tmp_path / "r.exr")
    assert done.returncode == 0, done.stderr
    assert np.array_equal(bounce.read_image(tmp_path / "r.exr"), ref.image)
    # Edits show in the reference: the scene as it is now.
    scene.move_light(0, (0.0, -0.5, 0.0))
    moved = bounce.reference(scene, (16, 12), spp=8, seed=3, **bounce.reference_scope("rsm"))
    assert not np.array_equal(moved.image, ref.image)


def test_photon_map():
    pm = bounce.photon_map("cornell-box", 12, photons=2000, k=16, spp=1, seed=1)
    assert pm.image.shape == (12, 12, 3) and pm.image.dtype == np.float32 and pm.image.mean() > 0
    assert pm.record["kind"] == "photon-map"


def test_the_gil_is_released_while_tracing():
    """A reference on another thread leaves this one running Python: many loop turns meanwhile."""
    result = {}
    worker = threading.Thread(target=lambda: result.setdefault("ref", bounce.reference("cornell-box", 48, spp=256, threads=1)))
    turns = 0
    start = time.perf_counter()
    worker.start()
    while worker.is_alive():
        turns += 1
        time.sleep(0.001)
    elapsed = time.perf_counter() - start
    assert "ref" in result and elapsed > 0.05
    # Holding the GIL for the trace would allow no turn until it ended (one at most).
    assert turns > 10, f"{turns} turns in {elapsed:.2f} s"
