#!/usr/bin/env python3
"""The measuring half of scripts/gpu-check.sh (issue 29; docs/gpu.md "GPU check"): on the machine's
GPU, the interactive benchmark's sides and the fidelity survey at 1080p, and every technique's image on
the GPU against the same image on llvmpipe (Mesa's surfaceless platform, which a GPU machine with Mesa
installed also has), and each value of the profile choices made without a GPU (CHOICES) timed on
courtyard. Writes bench/results/gpu-<date>.json (bench/record.py's envelope) naming the GPU,
its driver and EGL device; it feeds no README table.

Usage: bench/gpu_check.py BOUNCE --info INFO_JSON --tests TESTS_JSON [--reduced] [--budget SEC] [--out FILE]
  --out: write the record there instead of bench/results/gpu-<date>.json (the CTest's reduced run).
  --reduced: llvmpipe: small sizes, two techniques, one scene (a smoke run of the same code path).
  --budget: seconds for the three measurements together (default 330); each stage gets its share and
            records what it skipped for lack of time.
"""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from cli import ROOT, compare, later, option, rel, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402


def load(path, name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(HERE, path))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


interactive = load("interactive/run.py", "bench_interactive")
fidelity = load("fidelity/run.py", "bench_fidelity")

FULL_HD = "1920x1080"
# Scenes of the fidelity stage at 1080p: a spot-lit and an area-lit Cornell box (every technique runs on
# one of them); the survey over all scenes is bench/fidelity/run.py's, at 128^2.
FIDELITY_SCENES = ["cornell-box", "cornell-box-area"]
# Reference cost cap at 1080p: the path tracer's time limit per reference (it keeps the samples reached;
# 64 spp of 1080p are ~133 M paths, seconds on 16 cores). Its noise is in the record's metrics: at this
# sample count the fidelity stage checks energy, not relMSE (bench/fidelity/run.py is the survey).
# A render or reference that runs longer than PROCESS_TIMEOUT is recorded as timed out.
PROCESS_TIMEOUT = 120
REFERENCE_SECONDS = 10
AGREEMENT_SIZE = "64x64"
AGREEMENT_SCENES = {"default": "cornell-box", "area": "cornell-box-area"}


class Clock:
    def __init__(self, budget):
        self.end = time.monotonic() + budget

    def left(self):
        return self.end - time.monotonic()


def run_interactive(bounce, size, frames, sides, clock, share):
    out, skipped = {}, []
    stop = time.monotonic() + share
    for name, (technique, settings) in sides.items():
        if time.monotonic() > stop or clock.left() <= 0:
            skipped.append(name)
            continue
        try:
            r, cmd = render(bounce, interactive.SCENE, technique, size, frames, settings)
        except subprocess.CalledProcessError as e:
            out[name] = {"error": e.stderr.decode().strip().splitlines()[-1:]}
            continue
        times = [f["cpu_ms"] for f in later(r)]
        gpu = [f["gpu_ms"].get("frame", 0.0) for f in later(r)]
        out[name] = {"command": cmd, "frameMs": summary(times), "gpuFrameMs": summary(gpu),
                     "fps": 1000.0 / summary(times)["median"]}
        print(f"interactive {size} {name:28s} {summary(times)['median']:8.2f} ms", flush=True)
    ratios = {}
    for key, (a, b) in interactive.RATIOS.items():
        if a in out and b in out and "frameMs" in out[a] and "frameMs" in out[b]:
            ratios[key] = out[a]["frameMs"]["median"] / out[b]["frameMs"]["median"]
    return {"scene": interactive.SCENE, "size": size, "frames": frames, "sides": out, "ratios": ratios,
            "skipped": skipped}


# Settings whose default differs between the llvmpipe and gpu profiles and whose GPU value was chosen
# without a GPU: each value timed on the large scene (docs/gpu.md "Device profiles").
CHOICES = [("photon-splat", "depthMaps", ["raster", "compute", "rays"], ["light=sun"]),
           ("photon-splat", "depthMaps", ["raster", "compute", "rays"], ["light=sky"])]


def run_choices(bounce, size, frames, params, clock, share):
    out, skipped = [], []
    stop = time.monotonic() + share
    for technique, setting, values, scene_params in CHOICES:
        row = {"technique": technique, "setting": setting, "sceneParams": scene_params + params, "values": {}}
        for value in values:
            if time.monotonic() > stop or clock.left() <= 0:
                skipped.append(f"{technique}.{setting}={value} {' '.join(scene_params)}")
                continue
            try:
                r, cmd = render(bounce, "courtyard", technique, size, frames, {setting: value}, scene_params + params)
            except subprocess.CalledProcessError as e:
                row["values"][value] = {"error": e.stderr.decode().strip().splitlines()[-1:]}
                continue
            times = [f["cpu_ms"] for f in later(r)]
            row["values"][value] = {"command": cmd, "frameMs": summary(times)}
            print(f"choice {technique}.{setting}={value:8s} {' '.join(scene_params):10s} {summary(times)['median']:8.2f} ms", flush=True)
        out.append(row)
    return {"scene": "courtyard", "size": size, "frames": frames, "rows": out, "skipped": skipped}


def run_fidelity(bounce, size, spp, scenes, techniques, clock, share):
    scopes = fidelity.list_techniques(bounce)
    results, skipped = {}, []
    stop = time.monotonic() + share
    with tempfile.TemporaryDirectory() as tmp:
        refs = {}
        for scene in scenes:
            for technique in techniques or list(scopes):
                if time.monotonic() > stop or clock.left() <= 0:
                    skipped.append(f"{scene}/{technique}")
                    continue
                flags, component = scopes[technique]
                out = os.path.join(tmp, "t.exr")
                cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", size, "--frames",
                       str(fidelity.FRAMES.get(technique, 1)), "--component", component, "--out", out]
                t0 = time.monotonic()
                try:
                    p = subprocess.run(cmd, capture_output=True, text=True, timeout=PROCESS_TIMEOUT)
                except subprocess.TimeoutExpired:
                    results.setdefault(scene, {})[technique] = {"command": rel(cmd), "timeout_s": PROCESS_TIMEOUT}
                    continue
                entry = {"command": rel(cmd), "scope": " ".join(flags), "component": component}
                if p.returncode != 0:
                    lines = [l for l in p.stderr.splitlines() if l.strip()]
                    entry["refused"] = lines[-1] if lines else f"exit {p.returncode}"
                else:
                    entry["wall_s"] = time.monotonic() - t0
                    key = (scene, tuple(flags))
                    if key not in refs:
                        path = os.path.join(tmp, f"ref-{len(refs)}.exr")
                        rcmd = [bounce, "reference", "--scene", scene, "--size", size, "--spp", str(spp),
                                "--time-limit", str(REFERENCE_SECONDS), "--out", path] + flags
                        subprocess.run(rcmd, capture_output=True, text=True, check=True, timeout=PROCESS_TIMEOUT)
                        refs[key] = (path, rel(rcmd))
                    ref, rcmd = refs[key]
                    entry["reference"] = rcmd
                    entry["metrics"] = fidelity.compare(bounce, out, ref)
                    e = entry["metrics"]["energy"]
                    print(f"fidelity {size} {scene:18s} {technique:22s} energy {e:.3f}", flush=True)
                results.setdefault(scene, {})[technique] = entry
    return {"size": size, "spp": spp, "referenceTimeLimit_s": REFERENCE_SECONDS, "results": results,
            "skipped": skipped}


def run_agreement(bounce, techniques, clock, share):
    """Each technique's image on this GPU (EGL device) against llvmpipe's (surfaceless) at 64^2."""
    scopes = fidelity.list_techniques(bounce)
    out, skipped = {}, []
    stop = time.monotonic() + share
    with tempfile.TemporaryDirectory() as tmp:
        for technique in techniques or list(scopes):
            if time.monotonic() > stop or clock.left() <= 0:
                skipped.append(technique)
                continue
            entry = {}
            for scene in (AGREEMENT_SCENES["default"], AGREEMENT_SCENES["area"]):
                images, errors = {}, {}
                for side, env in (("gpu", {}), ("llvmpipe", {"BOUNCE_EGL_PLATFORM": "surfaceless"})):
                    path = os.path.join(tmp, f"{side}.exr")
                    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", AGREEMENT_SIZE,
                           "--frames", str(fidelity.FRAMES.get(technique, 1)), "--out", path]
                    # Both sides at the llvmpipe profile's defaults: the same settings on both devices.
                    e = dict(os.environ, BOUNCE_PROFILE="llvmpipe", **env)
                    if side == "llvmpipe":
                        e.pop("BOUNCE_EGL_DEVICE", None)
                    try:
                        p = subprocess.run(cmd, capture_output=True, text=True, env=e, timeout=PROCESS_TIMEOUT)
                    except subprocess.TimeoutExpired:
                        errors[side] = f"timed out after {PROCESS_TIMEOUT} s"
                        continue
                    if p.returncode != 0:
                        errors[side] = (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
                    else:
                        images[side] = path
                if len(images) == 2:
                    m = compare(bounce, images["gpu"], images["llvmpipe"])
                    entry[scene] = {"energy": m["energy"], "relMse": m["relMse"], "flipLdr": m["flipLdr"]}
                    print(f"agreement {technique:22s} {scene:18s} energy {m['energy']:.4f} relMSE {m['relMse']:.2e}",
                          flush=True)
                    break  # one scene the technique accepts is enough
                entry[scene] = {"refused": errors}
            out[technique] = entry
    return {"size": AGREEMENT_SIZE, "profile": "llvmpipe (both sides)", "results": out, "skipped": skipped}


def main():
    args = sys.argv[1:]
    info_path = option(args, "--info", "", str)
    tests_path = option(args, "--tests", "", str)
    budget = option(args, "--budget", 330)
    out_file = option(args, "--out", "", str)
    reduced = "--reduced" in args
    if reduced:
        args.remove("--reduced")
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    with open(info_path) as f:
        info = json.load(f)
    clock = Clock(budget)
    command = "scripts/gpu-check.sh" + (" --reduced" if reduced else "")
    rec = new_record("gpu", command, bounce)
    rec["device"] = {k: info.get(k) for k in ("vendor", "renderer", "version", "glsl", "platform", "device",
                                               "device_name", "profile")}
    rec["eglDevices"] = info.get("egl_devices", [])
    rec["limits"] = info.get("limits", {})
    rec["extensions"] = info.get("extensions", {})
    rec["isGpu"] = info.get("profile") == "gpu"
    rec["reduced"] = reduced
    if tests_path and os.path.exists(tests_path):
        with open(tests_path) as f:
            rec["tests"] = json.load(f)
    if reduced:
        sides = {k: interactive.SIDES[k] for k in ("rsm", "isr")}
        rec["interactive"] = run_interactive(bounce, "96x54", 2, sides, clock, budget * 0.3)
        rec["choices"] = run_choices(bounce, "64x64", 2, ["triangles=2128"], clock, budget * 0.1)
        rec["fidelity"] = run_fidelity(bounce, "64x36", 16, ["cornell-box"], ["rsm", "isr"], clock, budget * 0.3)
        rec["agreement"] = run_agreement(bounce, ["ambient", "rsm"], clock, budget * 0.3)
    else:
        rec["interactive"] = run_interactive(bounce, FULL_HD, 4, interactive.SIDES, clock, budget * 0.3)
        rec["choices"] = run_choices(bounce, FULL_HD, 4, [], clock, budget * 0.1)
        rec["fidelity"] = run_fidelity(bounce, FULL_HD, 64, FIDELITY_SCENES, None, clock, budget * 0.35)
        rec["agreement"] = run_agreement(bounce, None, clock, max(clock.left(), 0))
    if out_file:
        with open(out_file, "w") as f:
            json.dump(rec, f, indent=1)
        print(out_file)
    else:
        print(write_record(rec))


if __name__ == "__main__":
    main()
