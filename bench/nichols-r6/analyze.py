"""Prints relative RMS error (sqrt(sum (x - r)^2 / sum r^2), the thesis's Figs. 4.9/4.13 measure), relMSE
and frame time of every image of bench/nichols-r6/run.sh against each reference given, and writes them
as the raw record bench/results/nichols-r6-<date>.json (bench/tables.py puts R6 in the README from it).
Usage: analyze.py BOUNCE_BINARY DIR REFERENCE.exr [REFERENCE.exr ...]"""
import glob
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from record import new_record, write_record  # noqa: E402


def metrics(bounce, test, reference):
    out = subprocess.run([bounce, "compare", "--json", test, reference], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["metrics"]


def main():
    bounce, folder, references = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3:]
    rec = new_record("nichols-r6", "bench/nichols-r6/run.sh", bounce)
    rec.update({"scene": "cornell-box", "size": 64, "against": {}})
    os.chdir(folder)
    tests = sorted(glob.glob("hisr_*.exr")) + sorted(glob.glob("isr_f*.exr"), key=lambda f: int(f[5:-4])) \
        + sorted(glob.glob("rsm_g*.exr"), key=lambda f: int(f[5:-4])) + ["multires1m.exr"]
    for reference in references:
        # MSE against black is the reference's mean square: their ratio is the relative RMS squared.
        meanSquare = metrics(bounce, "zero.exr", reference)["mse"]
        print(f"== against {reference}")
        rows = rec["against"].setdefault(reference, {})
        for test in tests:
            if test == reference:
                continue
            m = metrics(bounce, test, reference)
            frame = json.load(open(test.replace(".exr", ".json")))["frames"][0]
            counters = frame["counters"]
            rows[test] = {"relRms": (m["mse"] / meanSquare) ** 0.5, "relMse": m["relMse"], "frameMs": frame["gpu_ms"]["frame"],
                          "vpls": counters.get("vpls", 0), "nodesPerFragment": counters.get("nodesPerFragment", 0)}
            print(f"{test:24s} relRms {100 * (m['mse'] / meanSquare) ** 0.5:6.2f} %  relMSE {m['relMse']:.4f}  "
                  f"frame {frame['gpu_ms']['frame']:9.1f} ms  VPLs {counters.get('vpls', 0):8.0f}  "
                  f"nodes/fragment {counters.get('nodesPerFragment', 0):7.1f}")
    print(write_record(rec))


if __name__ == "__main__":
    main()
