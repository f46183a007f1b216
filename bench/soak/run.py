#!/usr/bin/env python3
"""Soak: every technique for many frames of cornell-box-dynamic; live GL objects, buffer and texture
bytes and CPU RSS stay flat after warm-up (docs/reliability.md "Soak").

Usage: bench/soak/run.py [BOUNCE] [--frames N] [--size S] [--budget SEC] [--techniques a,b,...]
                         [--check] [--json PATH]
       (defaults: build/src/app/bounce, 10000 frames, 64^2, 180 s per technique, every technique)

Each technique is one `bounce render --frames F --stats-every E --stats` process (E = F / 100, so the
run record holds about 100 samples and stays small: keeping every frame's statistics would itself
grow the process by ~1.5 kB a frame). Every sample has the frame's `resources`: the GL objects and the
buffer and texture storage bytes the wrappers of src/gpu/ hold (gl::liveResources) and the resident
set size (/proc/self/statm). F is N, or fewer where a short probe run says N frames would take more
than the time budget (the record says which limited it). Techniques come from `bounce list`; one that
refuses cornell-box-dynamic (the radiosity methods, area-light: area lights only) runs on the first of
FALLBACK_SCENES it accepts.

Flat, per technique: warm-up is the first third of the frames (GPU timer pools, lazily sized buffers
and the radiosity methods' shooting reach their steady state in the first tens of frames); after it,
the GL object count and the buffer and texture bytes never exceed their value at the end of warm-up
(the ledger is exact: any growth is an object or storage kept per frame), and the RSS grows by at
most RSS_GROWTH_BOUND after warm-up, measured on its floor (the smallest sample of the last third against
the smallest of the first third: a leak raises every sample, allocation noise only some).

Without --check, writes the raw record bench/results/soak-<date>.json (bench/record.py) for
bench/tables.py. With --check (ctest soak_flat: few frames, 32^2), writes no record and exits 1 when a
technique is not flat; --json PATH keeps the measurements.
"""
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENE = "cornell-box-dynamic"
FALLBACK_SCENES = ["cornell-box-rotating", "area-screen"]
# Settings that keep the slowest technique's frames affordable: the same passes, fewer elements
# (radiosity-gather's defaults gather a hemicube per element per bounce: ~16 s a frame at 64^2 here).
CHEAP_SETTINGS = {"radiosity-gather": ["elementSize=0.1", "dynamicElementSize=0.1", "bounces=2", "hemicubeSize=16"]}
# --check (CI) also makes the other radiosity methods cheap (coarser elements, smaller hemicubes,
# fewer shooters a frame): their per-frame work, not its kind, is what this changes.
# threshold=0 and shooterFlux=1: every frame shoots exactly maxIterations quads of one shooter each,
# so the per-frame GPU timer scopes (a pool of query objects as large as the busiest frame's, a
# high-water mark by design) stop growing after the first frame; on the spot-lit cornell-box-dynamic
# PR's frames otherwise vary in iterations and shooter batches and the pool grew after warm-up.
# frameBudgetMs=0: no time budget, which would cut frames at a host-dependent batch.
RADIOSITY_CHECK = ["elementSize=0.1", "dynamicElementSize=0.1", "hemicubeSize=16", "maxIterations=40", "threshold=0",
                   "shooterFlux=1", "frameBudgetMs=0"]
CHECK_SETTINGS = {"radiosity-pr": RADIOSITY_CHECK, "radiosity-incremental": RADIOSITY_CHECK,
                  "radiosity-cross": RADIOSITY_CHECK}
# A run shortened by the time budget keeps at least this many frames (a third of them warm-up).
MIN_FRAMES = 90
# The RSS floor may rise by this much after warm-up. Measured (soak_flat, 60-133 post-warm-up samples
# per technique): the floor moved by at most 1.68 MB (radiosity-gather), 0.66 MB for photon-splat,
# 0 for most; a CPU leak of 40 kB a frame over the 90 post-warm-up frames of a 135-frame run exceeds it.
# GL objects and storage are checked exactly by the ledger, not by this bound.
RSS_GROWTH_BOUND = 3_000_000  # bytes
PROBE_FRAMES = 6
SAMPLES = 100
RESOURCE_KEYS = ["gl_objects", "buffers", "textures", "framebuffers", "programs", "queries", "buffer_bytes",
                 "texture_bytes", "rss_bytes"]


def techniques(bounce):
    """Every registered technique, as `bounce list --techniques --names` prints them (one per line)."""
    out = subprocess.run([bounce, "list", "--techniques", "--names"], capture_output=True, text=True, check=True).stdout
    return out.split()


def settings_for(technique, check):
    return CHEAP_SETTINGS.get(technique, []) + (CHECK_SETTINGS.get(technique, []) if check else [])


def render(bounce, technique, scene, size, frames, every, tmp, settings):
    stats = os.path.join(tmp, f"{technique}.json")
    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", f"{size}x{size}",
           "--frames", str(frames), "--stats-every", str(every), "--out", os.path.join(tmp, f"{technique}.exr"),
           "--stats", stats]
    for s in settings:
        cmd += ["--set", s]
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        return None, cmd, seconds, r.stderr.strip()
    with open(stats) as f:
        return json.load(f), cmd, seconds, None


def analyse(record, frames):
    samples = [[f["frame"]] + [f["resources"][k] for k in RESOURCE_KEYS] for f in record["frames"]]
    warmup = max(1, frames // 3)
    first_frame = samples[0][0]
    after = [s for s in samples if s[0] - first_frame >= warmup]
    before = [s for s in samples if s[0] - first_frame < warmup]
    column = {k: i + 1 for i, k in enumerate(RESOURCE_KEYS)}
    end_of_warmup = before[-1] if before else after[0]
    out = {"warmupFrames": warmup, "problems": []}
    for key in ["gl_objects", "buffer_bytes", "texture_bytes"]:
        c = column[key]
        base, peak, last = end_of_warmup[c], max(s[c] for s in after), after[-1][c]
        out[key] = {"warmup": base, "max": peak, "last": last, "first": samples[0][c]}
        if peak > base:
            out["problems"].append(f"{key} grew after warm-up: {base} at frame {end_of_warmup[0]}, up to {peak}")
    rss = [s[column["rss_bytes"]] for s in after]
    # A leak grows RSS steadily, so it raises the floor: the smallest sample of the last third of the
    # post-warm-up samples against the smallest of the first third. Allocation noise only adds to the
    # floor: photon-splat's CPU photon tracing and bundle placement keep a ~4.6 MB block resident in
    # some frames and not in others (measured: RSS alternating 155.0 / 159.6 MB with no trend over 200
    # frames, one sample at 172 MB), which medians read as growth when the last samples happen to sit
    # on the high level (CI: +5.7 MB from 3- and 10-sample medians; the floor moved 0.5 MB).
    third = max(1, len(rss) // 3)
    growth = min(rss[-third:]) - min(rss[:third])
    xs = [s[0] for s in after]
    mean_x, mean_y = statistics.fmean(xs), statistics.fmean(rss)
    var = sum((x - mean_x) ** 2 for x in xs)
    slope = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, rss)) / var if var > 0 else 0.0
    out["rss_bytes"] = {"first": samples[0][column["rss_bytes"]], "warmup": end_of_warmup[column["rss_bytes"]],
                        "min": min(rss), "max": max(rss), "last": rss[-1], "growth": growth,
                        "slopeBytesPerFrame": slope}
    if growth > RSS_GROWTH_BOUND:
        out["problems"].append(f"RSS grew by {growth / 1e6:.1f} MB after warm-up (bound {RSS_GROWTH_BOUND / 1e6:.1f} MB)")
    out["flat"] = not out["problems"]
    out["samples"] = samples
    return out


def main():
    args = sys.argv[1:]
    frames = option(args, "--frames", 10000)
    size = option(args, "--size", 64)
    budget = option(args, "--budget", 180.0, float)
    only = option(args, "--techniques", "", str)
    json_path = option(args, "--json", "", str)
    check = "--check" in args
    if check:
        args.remove("--check")
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    names = [t for t in techniques(bounce) if not only or t in only.split(",")]
    command = f"bench/soak/run.py --frames {frames} --size {size} --budget {budget:g}" + (f" --techniques {only}" if only else "")
    rec = new_record("soak", command, bounce) if not check else {"command": command}
    rec.update({"frames": frames, "size": size, "budgetSeconds": budget, "scene": SCENE, "fallbackScenes": FALLBACK_SCENES,
                "cheapSettings": CHEAP_SETTINGS, "checkSettings": CHECK_SETTINGS if check else {}, "minFrames": MIN_FRAMES, "rssGrowthBound": RSS_GROWTH_BOUND, "resourceKeys": RESOURCE_KEYS,
                "techniques": {}})
    def soak(technique, tmp):
        settings = settings_for(technique, check)
        refusals, probe, error = [], None, None
        for scene in [SCENE] + FALLBACK_SCENES:
            probe, cmd, seconds, error = render(bounce, technique, scene, size, PROBE_FRAMES, 1, tmp, settings)
            if probe is not None or f"technique '{technique}'" not in (error or ""):
                break
            refusals.append(f"{scene}: {error}")
        if probe is None:
            return {"error": error, "refusals": refusals}, f"FAIL {technique}: {error}"
        frame_s = statistics.median(f["cpu_ms"] for f in probe["frames"][1:]) / 1000.0
        run_frames, limited = frames, "frames"
        if budget > 0 and frame_s * frames > budget:
            run_frames, limited = max(MIN_FRAMES, int(budget / frame_s)), "time budget"
        every = max(1, run_frames // SAMPLES)
        record, cmd, seconds, error = render(bounce, technique, scene, size, run_frames, every, tmp, settings)
        if record is None:
            return {"error": error, "command": rel(cmd)}, f"FAIL {technique}: {error}"
        a = analyse(record, run_frames)
        entry = {"scene": scene, "refusals": refusals, "settings": settings, "frames": run_frames, "limitedBy": limited,
                 "statsEvery": every, "seconds": seconds,
                 "frameMs": statistics.median(f["cpu_ms"] for f in record["frames"][1:]), "command": rel(cmd)}
        entry.update(a)
        line = (f"{'ok' if a['flat'] else 'FAIL':4} {technique:22} {scene:20} {run_frames:6} frames {seconds:7.1f} s  "
                f"GL objects {a['gl_objects']['warmup']}->{a['gl_objects']['last']}  "
                f"textures {a['texture_bytes']['last'] / 1e6:.2f} MB  buffers {a['buffer_bytes']['last'] / 1e6:.3f} MB  "
                f"RSS {a['rss_bytes']['warmup'] / 1e6:.1f}->{a['rss_bytes']['last'] / 1e6:.1f} MB "
                f"(growth {a['rss_bytes']['growth'] / 1e6:+.2f} MB)" + "".join(f"\n     - {p}" for p in a["problems"]))
        return entry, line

    failures = 0
    # --check runs two techniques at a time (CI: 2 cores); the benchmark one, so its times are its own.
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(max_workers=2 if check else 1) as pool:
        for technique, (entry, line) in zip(names, pool.map(lambda t: soak(t, tmp), names)):
            rec["techniques"][technique] = entry
            failures += not entry.get("flat", False)
            print(line, flush=True)
    if json_path:
        with open(json_path, "w") as f:
            json.dump(rec, f, indent=1)
    if check:
        print(f"{len(names)} techniques, {failures} not flat")
        return 1 if failures else 0
    print(write_record(rec))
    return 0


if __name__ == "__main__":
    sys.exit(main())
