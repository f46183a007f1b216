"""sweep() and report() on a tiny study: the same jobs and records as `bounce sweep`, with noise floors."""
import json
import os

import bounce


def test_sweep_and_report(gl, cli, tmp_path):
    study = {"name": "py", "size": "16x16", "scenes": ["cornell-box"], "techniques": ["direct", "ambient"],
             "reference": {"spp": 4, "seed": 1}, "temporal": {"techniques": ["ambient"], "frames": 2}}
    path = tmp_path / "py.json"
    path.write_text(json.dumps(study))
    out = tmp_path / "out"
    run = bounce.sweep(path, out)
    listing = cli("sweep", path, "--out", out, "--list").stdout.splitlines()
    assert run["jobs"] == len(listing) and run["ran"] == run["jobs"] and not run["failed"]
    assert all(line.split()[2] == "finished" for line in listing), "the CLI sees every job finished"
    again = bounce.sweep(path, out)
    assert again["ran"] == 0 and again["finished_before"] == run["jobs"]
    compare = json.loads((out / "compare/cornell-box/direct/default/record.json").read_text())
    assert compare["floor"]["relMse"] > 0 and isinstance(compare["insideFloor"]["relMse"], bool)
    assert os.path.exists(out / "reference/cornell-box/b0/f0000/variance.exr")
    page = bounce.report(out)
    assert page == os.path.abspath(out / "report.html") and os.path.getsize(page) > 1000
    rows = json.loads((out / "results.json").read_text())
    assert all("relMse_floor" in r and "relMse_insideFloor" in r for r in rows)
