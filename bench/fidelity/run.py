#!/usr/bin/env python3
"""Fidelity of every technique on every built-in scene against the reference scope it declares.

Usage: bench/fidelity/run.py [BOUNCE] [--size N] [--spp N] [--scenes a,b] [--techniques x,y] [--name NAME]
                             [--timeout S] [--note TEXT] [--scene-param K=V ...] [--set K=V ...]
       (BOUNCE defaults to build/src/app/bounce; any Python 3, no numpy)

For each (technique, scene): `bounce render` at the technique's defaults (`FRAMES` frames: the image a
user sees after the technique has settled), the component its scope names, against
`bounce reference` with the scope's flags (`bounce list` prints them), and the no-GI image of the same
scope (black indirect light for indirect scopes; the shared `direct` pass for full-image scopes).
Recorded per pair: energy (image mean / reference mean), relMSE, relRMS and LDR-FLIP of the technique
and of the no-GI image, the render's wall time, or the one-line refusal of a scene the technique does
not accept, or *stopped* where a render ran past `--timeout` seconds (default: none; the gather on the
Sponza-class scene takes minutes a frame on llvmpipe). The raw record goes to bench/results/<NAME>-<date>.json (NAME defaults to `fidelity`);
bench/tables.py turns it into the README's fidelity table. `--name fidelity-rows --techniques x,y --note WHY`
reruns some techniques' rows after their defaults changed: tables.py puts them over the newest full record's.
"""
import functools
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("energy", "relMse", "relRms", "flipLdr", "testMean", "referenceMean"))

# Frames rendered before the image is taken, for techniques that converge or settle over frames
# (the rest are complete in their first frame). iir maintains its VPL set incrementally from frame 0;
# the progressive radiosity methods shoot a budget per frame until converged.
FRAMES = {"radiosity-pr": 8, "radiosity-incremental": 8, "radiosity-cross": 8}
# Settings other than the defaults: the shooting radiosity methods' time budget per frame is off (a time
# budget makes the frame a solution reaches depend on the host's speed; maxIterations alone bounds the
# frames, as before the budget; docs/techniques/radiosity.md, "Per-frame shooting budget").
SETTINGS = {t: {"frameBudgetMs": "0"} for t in FRAMES}

# --scene-param K=V (every render and reference) and --set K=V (the technique's renders, not the no-GI
# image's): a scene variant (courtyard under its sky) or a setting other than the default, for records
# beside the defaults' one.
SCENE_PARAMS = []
EXTRA_SETS = []

# The bounds every technique meets at its defaults (DEVELOPERS.md, issue 28).
ENERGY_TOLERANCE = 0.15
# The baselines are recorded but not held to the bounds: `direct` is the no-GI image itself and
# `ambient`'s constant term is an arbitrary setting.
BASELINES = ("direct", "ambient")


def list_techniques(bounce):
    """name -> (reference flags, component) from `bounce list --techniques`."""
    out = subprocess.run([bounce, "list", "--techniques"], check=True, capture_output=True, text=True).stdout
    scopes, name = {}, None
    for line in out.splitlines():
        m = re.match(r"^  (\S+)\s", line)
        if m and not line.startswith("    "):
            name = m.group(1)
        m = re.match(r"^\s+reference scope: (.*), compared with its (\w+) output", line)
        if m and name:
            flags = m.group(1).split()
            if "unbounded" in flags:  # every bounce: the reference's default
                i = flags.index("unbounded")
                del flags[i - 1:i + 1]
            scopes[name] = (flags, m.group(2))
    return scopes


def scenes(bounce):
    return subprocess.run([bounce, "list", "--scenes", "--names"], check=True, capture_output=True, text=True).stdout.split()


def render(bounce, scene, technique, size, frames, component, out, start=0, timeout=None):
    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", f"{size}x{size}", "--frames",
           str(frames), "--component", component, "--out", out]
    for k, v in SETTINGS.get(technique, {}).items():
        cmd += ["--set", f"{k}={v}"]
    if technique != "direct":
        cmd += [a for kv in EXTRA_SETS for a in ("--set", kv)]
    cmd += [a for kv in SCENE_PARAMS for a in ("--scene-param", kv)]
    if start:
        cmd += ["--start-frame", str(start)]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, rel(cmd), None
    wall = time.monotonic() - t0
    if p.returncode != 0:
        lines = [l for l in p.stderr.strip().splitlines() if l.strip()]
        return None, rel(cmd), lines[-1] if lines else f"exit {p.returncode}"
    return wall, rel(cmd), None


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 128)
    spp = option(args, "--spp", 1024)
    only_scenes = option(args, "--scenes", "", str)
    only_techniques = option(args, "--techniques", "", str)
    name = option(args, "--name", "fidelity", str)
    timeout = option(args, "--timeout", None, float)
    note = option(args, "--note", "", str)
    while "--scene-param" in args:
        SCENE_PARAMS.append(option(args, "--scene-param", "", str))
    while "--set" in args:
        EXTRA_SETS.append(option(args, "--set", "", str))
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    scopes = list_techniques(bounce)
    scene_list = [s for s in scenes(bounce) if not only_scenes or s in only_scenes.split(",")]
    techniques = [t for t in scopes if not only_techniques or t in only_techniques.split(",")]
    record = new_record(name, " ".join(["bench/fidelity/run.py"] + sys.argv[1:]), bounce)
    record.update({"size": size, "spp": spp, "frames": FRAMES, "settings": SETTINGS, "energyTolerance": ENERGY_TOLERANCE,
                   "runTimeoutSeconds": timeout, "results": {}})
    if note:
        record["note"] = note
    if SCENE_PARAMS or EXTRA_SETS:
        record.update({"sceneParams": SCENE_PARAMS, "extraSettings": EXTRA_SETS})
    with tempfile.TemporaryDirectory() as tmp:
        refs = {}

        # The reference at the frame the technique's image shows (its last): in an animated scene the
        # lights or objects have moved by then.
        def reference(scene, flags, frame):
            key = (scene, tuple(flags), frame)
            if key not in refs:
                path = os.path.join(tmp, f"ref-{len(refs)}.exr")
                cmd = [bounce, "reference", "--scene", scene, "--size", f"{size}x{size}", "--spp", str(spp), "--out", path] + flags
                cmd += [a for kv in SCENE_PARAMS for a in ("--scene-param", kv)]
                if frame:
                    cmd += ["--frame", str(frame)]
                p = subprocess.run(cmd, capture_output=True, text=True, check=True)
                noise = re.search(r"noise ([\d.]+)% per pixel, ([\d.]+)% image mean", p.stdout + p.stderr)
                refs[key] = (path, rel(cmd), float(noise.group(2)) / 100 if noise else None)
            return refs[key]

        for scene in scene_list:
            for technique in techniques:
                flags, component = scopes[technique]
                frames = FRAMES.get(technique, 1)
                out = os.path.join(tmp, "t.exr")
                wall, cmd, refusal = render(bounce, scene, technique, size, frames, component, out, timeout=timeout)
                entry = {"command": cmd, "frames": frames, "scope": " ".join(flags), "component": component}
                if wall is None and refusal is None:
                    entry["timedOut"] = f"stopped after {timeout:g} s"
                elif refusal:
                    entry["refused"] = refusal
                else:
                    ref, ref_cmd, noise = reference(scene, flags, frames - 1)
                    entry.update({"wall_s": wall, "reference": ref_cmd, "referenceNoise": noise})
                    entry["metrics"] = compare(bounce, out, ref)
                    # No-GI image of the same scope: the shared direct pass's image of this component.
                    nogi = os.path.join(tmp, "nogi.exr")
                    render(bounce, scene, "direct", size, 1, component, nogi, start=frames - 1)
                    entry["noGi"] = compare(bounce, nogi, ref)
                    e, r, r0 = entry["metrics"]["energy"], entry["metrics"]["relMse"], entry["noGi"]["relMse"]
                    entry["withinBounds"] = e is not None and abs(e - 1.0) <= ENERGY_TOLERANCE and r < r0
                    if technique in BASELINES:
                        entry["baseline"] = True
                record["results"].setdefault(scene, {})[technique] = entry
                m = entry.get("metrics")
                print(f"{scene:22s} {technique:22s} " + (f"energy {m['energy']:.3f} relMSE {m['relMse']:.4f} "
                      f"(no GI {entry['noGi']['relMse']:.4f}) {'baseline' if entry.get('baseline') else 'ok' if entry['withinBounds'] else 'OUT'} {wall:.1f}s"
                      if m else entry.get("timedOut") or f"refused: {entry['refused'][:90]}"), flush=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
