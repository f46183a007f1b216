#!/usr/bin/env python3
"""Radiosity's element counts against elementSize and scene area (issue 30: charts decoupled from the
mesh's faces; docs/techniques/radiosity.md "Charts, not the mesh's faces" and "Charts and element size:
measurements").

Usage: bench/radiosity/elements.py [BOUNCE] [--scenes a,b] [--sizes auto,0.2,...] [--name NAME] [--note TEXT]
       (--note: stored in the record, e.g. which commit an older BOUNCE was built from)

Per (scene, elementSize): one `bounce render` of radiosity-pr at 16x16 with one shooting iteration
(maxIterations=1, 16^2 hemicubes: the counts, not the solution) and its run record's counters: elements,
activeElements (non-ghost), quads (charts), elementSize (the setting or what auto derived), with the
set-up time (the patch model is built there). Writes bench/results/<NAME>-<date>.json.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import option  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENES = "cornell-box-area,cornell-box,two-rooms,furnished-room,atrium,courtyard"
SIZES = "auto,0.2,0.3,0.5,1.0"


def main():
    args = sys.argv[1:]
    scenes = option(args, "--scenes", SCENES, str).split(",")
    sizes = option(args, "--sizes", SIZES, str).split(",")
    name = option(args, "--name", "radiosity-elements", str)
    note = option(args, "--note", "", str)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record(name, " ".join(["bench/radiosity/elements.py"] + sys.argv[1:]), bounce)
    if note:
        record["note"] = note
    record["results"] = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            for size in sizes:
                value = "0" if size == "auto" else size
                stats = os.path.join(tmp, "run.json")
                cmd = [bounce, "render", "--scene", scene, "--technique", "radiosity-pr", "--size", "16x16", "--frames", "1",
                       "--set", f"elementSize={value}", "--set", f"dynamicElementSize={value}", "--set", "maxIterations=1",
                       "--set", "hemicubeSize=16", "--out", os.path.join(tmp, "o.exr"), "--stats", stats]
                start = time.monotonic()
                run = subprocess.run(cmd, capture_output=True, text=True)
                entry = {"scene": scene, "setting": size, "command": " ".join(cmd[1:]), "wall_s": round(time.monotonic() - start, 2)}
                if run.returncode != 0:
                    entry["refused"] = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else f"exit {run.returncode}"
                else:
                    with open(stats) as f:
                        r = json.load(f)
                    c = r["frames"][-1]["counters"]
                    # A binary from before the charts reports neither the derived size nor the ghosts (the size
                    # was a counter in the first charts commits, the run record's `derived` since).
                    size_used = r.get("derived", {}).get("elementSizeMetres", c.get("elementSize", float(value)))
                    entry.update({"triangles": r["scene"]["triangles"], "elementSize": size_used,
                                  "elements": int(c["elements"]), "activeElements": int(c.get("activeElements", c["elements"])),
                                  "charts": int(c["quads"]), "setup_s": round(r["setup_seconds"], 2)})
                record["results"].append(entry)
                print(f"{scene:16s} {size:5s} " + (entry.get("refused") or
                      f"elementSize {entry['elementSize']:.4g} m: {entry['elements']} elements ({entry['activeElements']} active), "
                      f"{entry['charts']} charts, {entry['triangles']} triangles, set-up {entry['setup_s']} s"), flush=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
