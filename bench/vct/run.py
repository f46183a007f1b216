#!/usr/bin/env python3
"""Benchmarks of `vct` (Rauwendaal 2013) through the CLI's run records, written as one raw record.

Usage: bench/vct/run.py [BOUNCE] [--quick]    (BOUNCE defaults to build/src/app/bounce)

Every comparison is interleaved (A B C A B C ...) with `--reps` repetitions; each run renders
`--frames` frames and the run record's median over frames is taken (frame 0 also compiles the
shaders on llvmpipe, the median of 5 frames skips it). The raw record goes to
bench/results/vct-<date>.json with the command, git commit, date and machine; bench/tables.py turns
it into the README's tables. Absolute times on llvmpipe are indicative only; the ratios are the
results (thesis Table 4.1 and ch. 5-7 claims, docs/techniques/vct.md).
"""
import functools
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("relMse", "flipLdr", "mae"))


def run_record(bounce, scene, settings, size, frames, scene_params=None, component="indirect"):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "o.exr")
        stats = os.path.join(tmp, "run.json")
        cmd = [bounce, "render", "--scene", scene, "--technique", settings.get("technique", "vct"), "--size",
               f"{size}x{size}", "--frames", str(frames), "--component", component, "--out", out, "--stats", stats]
        for p in scene_params or []:
            cmd += ["--scene-param", p]
        for k, v in settings.items():
            if k != "technique":
                cmd += ["--set", f"{k}={v}"]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        with open(stats) as f:
            rec = json.load(f)
        return rec, cmd


def stage(rec, name):
    return rec["median_ms"].get(name, 0.0)


def interleaved(bounce, cases, reps, frames, size):
    """cases: list of (label, scene, settings, scene_params). Returns label -> list of run records."""
    runs = {label: [] for label, *_ in cases}
    cmds = {}
    for _ in range(reps):
        for label, scene, settings, params in cases:
            rec, cmd = run_record(bounce, scene, settings, size, frames, params)
            runs[label].append(rec)
            cmds[label] = " ".join(os.path.relpath(c, ROOT) if c == bounce else c for c in cmd)
    return runs, cmds


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    reps = 2 if quick else 3
    frames = 5
    record = new_record("vct", " ".join(["bench/vct/run.py"] + sys.argv[1:]), bounce)
    record.update({"reps": reps, "frames": frames, "results": {}})

    # R1-R5: voxelizer time over resolution and scene (binary, thin: the Table 4.1 set-up).
    vox = {}
    for scene, params in [("cornell-box", []), ("atrium", ["triangles=25000"]), ("atrium", ["triangles=100000"])]:
        for res in ([64, 128] if quick else [64, 128, 256]):
            cases = [(v, scene, {"voxelizer": v, "binary": "true", "separability": "thin", "resolution": str(res)}, params)
                     for v in ("triangle", "fragment", "hybrid")]
            runs, cmds = interleaved(bounce, cases, reps, frames, 64)
            key = f"{scene}{'-' + params[0] if params else ''}@{res}"
            entry = {}
            for v in ("triangle", "fragment", "hybrid"):
                recs = runs[v]
                entry[v] = {"voxelize_ms": summary([stage(r, "vct/voxelize") for r in recs]), "command": cmds[v]}
                if v == "hybrid":
                    entry[v]["pass1_ms"] = summary([stage(r, "vct/voxelize/pass1") for r in recs])
                    entry[v]["pass2_ms"] = summary([stage(r, "vct/voxelize/pass2") for r in recs])
                    c = recs[0]["frames"][-1]["counters"]
                    entry[v]["trianglesPass1"] = c["trianglesPass1"]
                    entry[v]["trianglesPass2"] = c["trianglesPass2"]
            entry["triangles"] = runs["hybrid"][0]["scene"]["triangles"]
            vox[key] = entry
            print(key, {v: round(entry[v]["voxelize_ms"]["median"], 1) for v in ("triangle", "fragment", "hybrid")}, flush=True)
    record["results"]["voxelizers"] = vox

    # R8, R11, R12, frame time: per storage on cornell-box, 256^2, 64^3, both diffuse tracers.
    storages = ("iso", "aniso", "sh-f32", "sh-u8")
    cases = []
    for s in storages:
        for t in ("specialised", "generic"):
            cases.append((f"{s}/{t}", "cornell-box", {"storage": s, "tracer": t, "resolution": "64"}, []))
    runs, cmds = interleaved(bounce, cases, reps, frames, 256)
    st = {}
    for label, recs in runs.items():
        st[label] = {name: summary([stage(r, key) for r in recs]) for name, key in
                     [("frame_ms", "frame"), ("voxelize_ms", "vct/voxelize"), ("post_ms", "vct/post-voxelize"),
                      ("mipmap_ms", "vct/mipmap"), ("diffuse_ao_ms", "vct/diffuse-ao"), ("specular_ms", "vct/specular")]}
        st[label]["bytesPerVoxel"] = recs[0]["frames"][-1]["counters"]["bytesPerVoxel"]
        st[label]["activeVoxels"] = recs[0]["frames"][-1]["counters"]["activeVoxels"]
        st[label]["command"] = cmds[label]
    record["results"]["storages"] = st
    print("storages", {k: round(v["frame_ms"]["median"], 1) for k, v in st.items()}, flush=True)

    # Mipmap scaling with N (SH vs aniso, R11), 256^2.
    mip = {}
    for res in ([64, 128] if quick else [64, 128, 256]):
        cases = [(s, "cornell-box", {"storage": s, "resolution": str(res)}, []) for s in ("aniso", "sh-f32", "sh-u8")]
        runs, cmds = interleaved(bounce, cases, reps, frames, 128)
        mip[str(res)] = {s: {"mipmap_ms": summary([stage(r, "vct/mipmap") for r in recs]),
                             "voxelize_ms": summary([stage(r, "vct/voxelize") for r in recs]), "command": cmds[s]}
                         for s, recs in runs.items()}
    record["results"]["mipmap"] = mip

    # R9 (Fig. 5.4): voxelization cost per format and level-0 write mode, with the fragment-parallel
    # voxelizer as the thesis's format study, on cornell-box and atrium (100K triangles), 128^3.
    r9 = {}
    for scene, params in [("cornell-box", []), ("atrium", ["triangles=100000"])]:
        cases = [(f"{st}/{at}", scene, {"voxelizer": "fragment", "storage": st, "atomic": at, "resolution": "128"}, params)
                 for st, at in [("iso", "max"), ("iso", "average"), ("aniso", "average"), ("sh-f32", "average"), ("sh-u8", "average")]]
        runs, cmds = interleaved(bounce, cases, reps, frames, 64)
        r9[scene] = {label: {"voxelize_ms": summary([stage(r, "vct/voxelize") for r in recs]),
                             "post_ms": summary([stage(r, "vct/post-voxelize") for r in recs]),
                             "voxelWrites": recs[0]["frames"][-1]["counters"]["voxelWrites"], "command": cmds[label]}
                     for label, recs in runs.items()}
        print("R9", scene, {k: round(v["voxelize_ms"]["median"], 1) for k, v in r9[scene].items()}, flush=True)
    record["results"]["r9"] = r9

    # R10 (Fig. 5.11): voxelization + post + mipmap with and without the active-voxel lists, per format,
    # cornell-box and atrium at 128^3 (the hybrid voxelizer, the default).
    r10 = {}
    for scene, params in [("cornell-box", []), ("atrium", ["triangles=100000"])]:
        cases = [(f"{st}/{'sparse' if sp else 'dense'}", scene, {"storage": st, "sparseMip": "true" if sp else "false",
                                                                "resolution": "128"}, params)
                 for st in ("iso", "aniso", "sh-f32", "sh-u8") for sp in (True, False)]
        runs, cmds = interleaved(bounce, cases, reps, frames, 64)
        r10[scene] = {label: {name: summary([stage(r, key) for r in recs]) for name, key in
                              [("voxelize_ms", "vct/voxelize"), ("post_ms", "vct/post-voxelize"), ("mipmap_ms", "vct/mipmap")]}
                      for label, recs in runs.items()}
        for label, recs in runs.items():
            r10[scene][label]["total_ms"] = summary([stage(r, "vct/voxelize") + stage(r, "vct/post-voxelize") + stage(r, "vct/mipmap")
                                                     for r in recs])
            r10[scene][label]["activeVoxelsAllLevels"] = recs[0]["frames"][-1]["counters"].get("activeVoxelsAllLevels", 0)
            r10[scene][label]["command"] = cmds[label]
        print("R10", scene, {k: round(v["total_ms"]["median"], 1) for k, v in r10[scene].items()}, flush=True)
    record["results"]["r10"] = r10

    # Figs. 4.16/4.17: hybrid time over the cutoff (atrium 100K triangles, 128^3, binary, thin).
    cutoffs = [0.5, 1, 2, 4, 8, 16, 64] if not quick else [1, 4, 16]
    cases = [(str(c), "atrium", {"voxelizer": "hybrid", "binary": "true", "separability": "thin", "resolution": "128",
                                 "cutoff": str(c)}, ["triangles=100000"]) for c in cutoffs]
    runs, cmds = interleaved(bounce, cases, reps, frames, 64)
    record["results"]["cutoff"] = {c: {"voxelize_ms": summary([stage(r, "vct/voxelize") for r in recs]),
                                       "pass1_ms": summary([stage(r, "vct/voxelize/pass1") for r in recs]),
                                       "pass2_ms": summary([stage(r, "vct/voxelize/pass2") for r in recs]),
                                       "trianglesPass2": recs[0]["frames"][-1]["counters"]["trianglesPass2"],
                                       "command": cmds[c]} for c, recs in runs.items()}
    print("cutoff", {c: round(v["voxelize_ms"]["median"], 1) for c, v in record["results"]["cutoff"].items()}, flush=True)

    # Shadow cones (Eq. 6.3): time over aperture (R13) on cornell-box, 256^2, 64^3.
    cases = [(str(a), "cornell-box", {"coneShadows": "true", "shadowAperture": str(a), "specular": "false"}, [])
             for a in (0, 2, 4, 6, 10)]
    runs, cmds = interleaved(bounce, cases, reps, frames, 256)
    record["results"]["shadowCone"] = {a: {"shadow_ms": summary([stage(r, "vct/shadow") for r in recs]), "command": cmds[a]}
                                       for a, recs in runs.items()}

    # two-rooms light leak per storage (library metric, through bounce_bench).
    bench_bin = os.path.join(os.path.dirname(os.path.dirname(bounce)), "..", "bench", "bounce_bench")
    bench_bin = os.path.normpath(bench_bin)
    if os.path.exists(bench_bin):
        out = subprocess.run([bench_bin, "--benchmark_filter=LightLeak", "--benchmark_format=json"], check=True,
                             capture_output=True, text=True).stdout
        record["results"]["lightLeak"] = {b["label"]: b["leak"] for b in json.loads(out)["benchmarks"]}
        record["results"]["lightLeakCommand"] = os.path.relpath(bench_bin, ROOT) + " --benchmark_filter=LightLeak --benchmark_format=json"
        print("leak", record["results"]["lightLeak"], flush=True)

    # Quality: indirect vs bounce reference --bounces 1 --indirect-only, 128^2.
    quality = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scene, frame_count in [("cornell-box", 1), ("cornell-box-dynamic", 1), ("cornell-box-dynamic", 16),
                                   ("cornell-box-dynamic", 31), ("atrium", 1)]:
            ref = os.path.join(tmp, f"{scene}-ref.exr")
            subprocess.run([bounce, "reference", "--scene", scene, "--size", "128x128", "--spp", "512", "--bounces", "1",
                            "--indirect-only", "--frame", str(frame_count - 1), "--out", ref], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            q = {}
            techniques = [("vct/" + s, {"technique": "vct", "storage": s}) for s in storages]
            techniques += [(t, {"technique": t}) for t in ("rsm", "isr", "iir")]
            for label, settings in techniques:
                out = os.path.join(tmp, f"{scene}-{label.replace('/', '-')}.exr")
                cmd = [bounce, "render", "--scene", scene, "--technique", settings["technique"], "--size", "128x128",
                       "--frames", str(frame_count), "--component", "indirect", "--out", out]
                for k, v in settings.items():
                    if k != "technique":
                        cmd += ["--set", f"{k}={v}"]
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                q[label] = compare(bounce, out, ref)
            quality[f"{scene}@frame{frame_count - 1}"] = q
            print(scene, {k: round(v["relMse"], 3) for k, v in q.items()}, flush=True)
    record["results"]["quality"] = quality
    record["results"]["quality_reference"] = "bounce reference --size 128x128 --spp 512 --bounces 1 --indirect-only --frame F"

    print("wrote", write_record(record))


if __name__ == "__main__":
    main()
