#!/usr/bin/env python3
# Convergence latency after an event (ctest study_events): a temporal study whose animation steps at an
# event frame, and one that plays and then holds: the scene frame each run frame shows, the references
# they share, and the latency counted from the event (docs/metrics.md "Temporal metrics").
#
# usage: events_test.py BOUNCE WORK
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_support import check, failures, load, runner, write_json  # noqa: E402

BOUNCE, WORK = sys.argv[1], sys.argv[2]
run = runner(BOUNCE)


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# ---- convergence latency after an event ----
# cornell-box-dynamic moves its spot and its tall block every frame. "step": frames 0-5 show frame 0,
# frames 6-19 frame 6 (the spot jumps 1/20 of its orbit at frame 6). iir with recalcMin 0 keeps every
# valid VPL, so once it has replaced the invalidated ones its image stops changing: with recalcMax 2
# that takes a few frames, with 64 one. `direct` has no history: settled at the event itself.
threshold = 0.05  # iir recalcMax 2 is 8-10 % from its settled image until it has refilled, then within 2 %
events = {
    "name": "events", "size": "48x48", "scenes": ["cornell-box-dynamic"],
    "techniques": ["direct", {"name": "iir", "settings": {"recalcMin": 0, "maxLights": 64}, "grid": {"recalcMax": [2, 64]}}],
    "reference": {"spp": 2, "seed": 1},
    "temporal": {"frames": 20, "eventFrame": 6, "animation": "step", "threshold": threshold},
}
events_path = os.path.join(WORK, "events.json")
write_json(events_path, events)
listing = run("sweep", events_path, "--list")
references = [l.split()[3] for l in listing.stdout.splitlines() if l.split()[1] == "reference"]
# Stills (frame 0) per scope, plus the temporal frames' moments: only frames 0 and 6 are shown.
check(sorted(set(r.split("/")[-1] for r in references)) == ["f0000", "f0006"],
      f"a stepped run needs references of its two moments only ({references})")
out = os.path.join(WORK, "events-out")
r = run("sweep", events_path, "--out", out, "--jobs", "2")
check(r.returncode == 0, f"the event study runs ({r.stderr.strip()[-300:]})")


def temporal(root, variant):
    return load(os.path.join(root, "temporal/cornell-box-dynamic", variant, "record.json"))


def latency_from(frames, event_index, t):
    # The definition, recomputed from the record's own per-frame errors: the smallest k with every
    # frame from the event + k on within the threshold.
    k = None
    for i in range(len(frames) - 1, event_index - 1, -1):
        if frames[i]["errorToSettled"] is None or not frames[i]["errorToSettled"] < t:
            break
        k = i - event_index
    return k


direct = temporal(out, "direct/default")
slow = temporal(out, "iir/maxLights-64_recalcMax-2_recalcMin-0")
fast = temporal(out, "iir/maxLights-64_recalcMax-64_recalcMin-0")
check([f["sceneFrame"] for f in direct["frames"]] == [0] * 6 + [6] * 14, "step: frames 0-5 show frame 0, the rest frame 6")
check(all("errorToSettled" not in f for f in direct["frames"][:6]) and all("errorToSettled" in f for f in direct["frames"][6:]),
      "the error to the settled image is measured from the event on only")
# Measured from the start of the run, direct would need 6 frames: its first six show the old pose.
check(direct["convergence"]["latencyFrames"] == 0 and direct["convergence"]["settled"],
      f"direct: latency 0 after the event ({direct['convergence']})")
check(direct["frames"][5]["relRms"] != direct["frames"][6]["relRms"], "direct's image changes at the event (the spot moved)")
ls, lf = slow["convergence"]["latencyFrames"], fast["convergence"]["latencyFrames"]
check(slow["convergence"]["settled"] and isinstance(ls, int) and ls >= 2,
      f"iir refilling 2 VPLs a frame needs frames after the event ({slow['convergence']})")
check(ls == latency_from(slow["frames"], 6, threshold), "its latency is the definition applied to its per-frame errors")
check(slow["frames"][6]["errorToSettled"] > threshold, "iir's first frame after the event is outside the threshold")
check(fast["convergence"]["settled"] and lf is not None and lf < ls, f"refilling 64 a frame settles sooner ({lf} < {ls})")
# Times are single-precision floats in bounce (frame / frame rate): equal to 1e-6 relative.
check(math.isclose(slow["convergence"]["latencySeconds"], ls / 30.0, rel_tol=1e-6), "latency in seconds at the scene's 30 frames per second")

# "hold": the animation plays to the event and stops there.
held = dict(events, name="held", techniques=["direct"], temporal=dict(events["temporal"], animation="hold", frames=10))
held_path = os.path.join(WORK, "held.json")
write_json(held_path, held)
held_out = os.path.join(WORK, "held-out")
r = run("sweep", held_path, "--out", held_out)
check(r.returncode == 0, f"the held study runs ({r.stderr.strip()[-300:]})")
h = load(os.path.join(held_out, "temporal/cornell-box-dynamic/direct/default/record.json"))
check([f["sceneFrame"] for f in h["frames"]] == [0, 1, 2, 3, 4, 5, 6, 6, 6, 6], "hold: frames play to 6, then show 6")
check(h["frames"][6]["time_s"] == h["frames"][9]["time_s"] and math.isclose(h["frames"][9]["time_s"], 6 / 30.0, rel_tol=1e-6),
      "the held frames' time is the event's")
check(h["convergence"]["latencyFrames"] == 0, "direct holds still at once")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
