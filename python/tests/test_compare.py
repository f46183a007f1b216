"""compare(): arrays and files, metric selection, heat maps, the reference's noise floor."""
import json

import numpy as np
import pytest

import bounce

RNG = np.random.default_rng(7)


def test_identical_and_different_arrays():
    a = RNG.random((20, 24, 3), dtype=np.float32)
    same = bounce.compare(a, a)
    assert same["relMse"] == 0 and same["ssim"] == 1 and same["psnr"] is None and same["energy"] == 1
    assert same["heatmap"].shape == (20, 24) and same["heatmap"].dtype == np.float32 and same["heatmap"].max() == 0
    darker = bounce.compare(a * 0.5, a, metrics=["relMse", "energy", "heatmap"])
    assert set(darker) == {"relMse", "energy", "heatmap"} and darker["energy"] == pytest.approx(0.5, rel=1e-6)
    assert darker["heatmap"].max() > 0
    assert set(bounce.METRICS) >= set(bounce.compare(a, a * 0.9))


def test_files_give_the_cli_numbers(cli, tmp_path):
    a, b = RNG.random((16, 16, 3), dtype=np.float32), RNG.random((16, 16, 3), dtype=np.float32)
    bounce.write_image(tmp_path / "a.exr", a)
    bounce.write_image(tmp_path / "b.exr", b)
    done = cli("compare", tmp_path / "a.exr", tmp_path / "b.exr", "--json")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)["metrics"]
    for got in (bounce.compare(tmp_path / "a.exr", str(tmp_path / "b.exr")), bounce.compare(a, b)):
        for k in ("relMse", "relRms", "ssim", "flipLdr", "flipHdr", "energy", "psnr"):
            assert got[k] == expected[k], k


def test_noise_floor_from_a_reference_and_from_its_record(cli, tmp_path):
    # 64 spp: at 16 the reference's noise (52 % per pixel) puts even a half-bright image's relMSE
    # within 2x of the floor (measured 0.108 vs floor 0.073); at 64 it is 0.099 vs 0.031, outside.
    ref = bounce.reference("cornell-box", 24, spp=64, seed=1)
    exact_like = bounce.reference("cornell-box", 24, spp=1024, seed=2)
    good = bounce.compare(exact_like, ref)
    assert good["floor"]["relMse"] == pytest.approx(ref.noise["floor"]["relMse"])
    assert good["insideFloor"]["relMse"] and good["insideFloor"]["flipLdr"], "a near-exact image is inside the floor"
    assert good["relMseCorrected"] == pytest.approx(good["relMse"] - good["floor"]["relMse"])
    bad = bounce.compare(exact_like.image * 0.5, ref)
    assert not bad["insideFloor"]["relMse"] and not bad["insideFloor"]["energy"]
    # The CLI's reference with its record and variance beside it: compare finds them.
    done = cli("reference", "--scene", "cornell-box", "--size", "24x24", "--spp", 64, "--seed", 1,
               "--out", tmp_path / "ref.exr", "--stats", tmp_path / "ref.json", "--variance", tmp_path / "ref-var.exr")
    assert done.returncode == 0, done.stderr
    from_files = bounce.compare(exact_like, tmp_path / "ref.exr")
    assert from_files["noise"]["variance"].endswith("ref-var.exr")
    assert from_files["floor"]["relMse"] == pytest.approx(good["floor"]["relMse"], rel=1e-6)
    printed = cli("compare", tmp_path / "ref.exr", tmp_path / "ref.exr")
    assert "noise floor" in printed.stdout and "INSIDE" in printed.stdout
