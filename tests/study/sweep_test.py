#!/usr/bin/env python3
# `bounce sweep` end to end on a tiny study (ctest study_sweep): expansion, a local run, resuming,
# a job killed halfway, and the GNU parallel job list giving the same records as the local run.
# Leaves WORK/local (the local run's output) for the report test (fixture study_results).
#
# usage: sweep_test.py BOUNCE WORK
import json
import os
import shutil
import signal
import subprocess
import sys
import time

BOUNCE, WORK = sys.argv[1], sys.argv[2]
failures = []


def check(condition, message):
    if condition:
        print(f"ok: {message}")
    else:
        print(f"FAIL: {message}")
        failures.append(message)


def run(*args, **kw):
    return subprocess.run([BOUNCE, *args], capture_output=True, text=True, **kw)


def records(root):
    out = {}
    for folder, _dirs, files in os.walk(root):
        if "record.json" in files:
            with open(os.path.join(folder, "record.json")) as f:
                r = json.load(f)
            out[r["job"]] = r
    return out


def comparable(record):
    # What must agree between two runs of the same job: the outcome, not the clock. Timings, host
    # and finish time differ by construction; images and metrics must not.
    keep = {k: record.get(k) for k in ("job", "kind", "status", "spec", "reason", "metrics", "leak", "flicker",
                                       "referenceFlicker", "convergence", "floor", "insideFloor")}
    if "frames" in record and record["kind"] == "temporal":
        keep["frames"] = [{k: v for k, v in f.items() if k not in ("gpu_ms", "cpu_ms")} for f in record["frames"]]
    if record["kind"] == "reference":
        keep["samples"] = record["result"]["samplesPerPixel"]
    return keep


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
study = {
    "name": "tiny",
    "size": "16x16",
    "scenes": ["cornell-box", "two-rooms"],
    "techniques": [
        "direct",
        {"name": "ambient", "grid": {"radiance": [0.05, 0.1]}},
        # Refused by the technique's setup on every scene (an odd hemicube): the sweep's refusal path.
        {"name": "radiosity-pr", "settings": {"hemicubeSize": 7}},
    ],
    "reference": {"spp": 4, "seed": 3},
    "temporal": {"scenes": ["cornell-box"], "techniques": ["ambient"], "frames": 3},
}
study_path = os.path.join(WORK, "tiny.json")
with open(study_path, "w") as f:
    json.dump(study, f, indent=1)

# Expansion: 2 scenes x 4 variants renders and compares; references shared by scope (direct: b0,
# ambient: all, radiosity-pr: all-diffuse) per scene, plus cornell-box's temporal frames 1 and 2
# (frame 0 is the still reference); 2 temporal jobs.
listing = run("sweep", study_path, "--list")
check(listing.returncode == 0, f"--list runs ({listing.stderr.strip()})")
lines = [l.split() for l in listing.stdout.splitlines()]
ids = [l[3] for l in lines]
kinds = [l[1] for l in lines]
check(len(ids) == 26 and len(set(ids)) == 26, f"26 distinct jobs (got {len(ids)})")
check(kinds.count("render") == 8 and kinds.count("compare") == 8, "8 renders and 8 compares")
check(kinds.count("reference") == 8, f"8 shared references (got {kinds.count('reference')})")
check(kinds.count("temporal") == 2, "2 temporal jobs")
check("render/cornell-box/ambient/radiance-0.05" in ids and "reference/two-rooms/b0/f0000" in ids
      and "reference/cornell-box/all/f0002" in ids, "stable job names")
check(all(l[0] == "1" for l in lines if l[1] in ("render", "reference"))
      and all(l[0] == "2" for l in lines if l[1] in ("compare", "temporal")), "stage 1 renders/references, stage 2 the rest")
check(all(l[2] == "pending" for l in lines), "nothing finished before the first run")

local = os.path.join(WORK, "local")
r = run("sweep", study_path, "--out", local, "--jobs", "2")
check(r.returncode == 0, f"local run succeeds ({r.stderr.strip()[-300:]})")
rec = records(local)
check(len(rec) == 26, f"every job wrote its record ({len(rec)})")
check(rec["render/cornell-box/radiosity-pr/hemicubeSize-7"]["status"] == "refused", "radiosity-pr refuses an odd hemicube")
check(rec["compare/cornell-box/radiosity-pr/hemicubeSize-7"]["status"] == "skipped", "its compare is skipped")
check(rec["compare/cornell-box/direct/default"]["metrics"]["relMse"] > 0, "compare records carry metrics")
# Reference noise (docs/metrics.md "Reference noise floor"): every reference writes its variance image
# and floors, every compare the floor beside each metric, whether it is within 2x, and the corrected relMSE.
ref0 = rec["reference/cornell-box/all/f0000"]
check(os.path.exists(os.path.join(local, "reference/cornell-box/all/f0000/variance.exr"))
      and ref0["noise"]["variance"] == "variance.exr" and ref0["noise"]["floor"]["relMse"] > 0,
      "references write variance.exr and their floors")
c = rec["compare/cornell-box/ambient/radiance-0.05"]
check(set(c["floor"]) >= {"relMse", "relRms", "ssim", "flipLdr", "flipHdr", "energy"}
      and all(isinstance(c["insideFloor"][m], bool) for m in ("relMse", "relRms", "flipLdr"))
      and abs(c["metrics"]["relMseCorrected"] - (c["metrics"]["relMse"] - c["floor"]["relMse"])) < 1e-9
      and c["floor"]["relMse"] == ref0["noise"]["floor"]["relMse"],
      "compare records carry the floor, the inside-2x flags and the corrected relMSE")
# 4 spp at 16x16: references this noisy put ambient's error inside its floor on some metric.
check(any(any(r.get("insideFloor", {}).values()) for j, r in rec.items() if j.startswith("compare/")),
      "a 4-spp reference leaves some comparison inside its floor")
t = rec["temporal/cornell-box/ambient/radiance-0.05"]["frames"]
check(all(f["relRmsFloor"] > 0 and isinstance(f["relRmsInsideFloor"], bool) for f in t), "temporal frames carry their floors")
leak = rec["compare/two-rooms/ambient/radiance-0.1"]["leak"]
# The ambient term lights the dark room: a leak the direct technique does not have.
check(leak["test"] > 0.05 and rec["compare/two-rooms/direct/default"]["leak"]["test"] == 0, "leak scores on two-rooms")
check(rec["temporal/cornell-box/ambient/radiance-0.05"]["flicker"] == 0.0
      and rec["temporal/cornell-box/ambient/radiance-0.05"]["convergence"]["latencyFrames"] == 0,
      "a static deterministic technique: no flicker, settled at once")

# Resuming: nothing to do; a record removed (a job killed after its images) reruns only that job.
r = run("sweep", study_path, "--out", local)
check(r.returncode == 0 and "0 ran, 26 already finished" in r.stdout, f"rerun skips finished jobs ({r.stdout.strip()})")
os.remove(os.path.join(local, "render/two-rooms/direct/default/record.json"))
r = run("sweep", study_path, "--out", local)
check("1 ran, 25 already finished" in r.stdout, f"a job without its record runs again ({r.stdout.strip()})")
# A changed study (reference seed) makes the references' and compares' records stale.
study_changed = dict(study, reference={"spp": 4, "seed": 4})
changed_path = os.path.join(WORK, "changed.json")
with open(changed_path, "w") as f:
    json.dump(study_changed, f)
listing = run("sweep", changed_path, "--out", local, "--list")
pending = [l.split()[3] for l in listing.stdout.splitlines() if l.split()[2] == "pending"]
check(sorted(set(p.split("/")[0] for p in pending)) == ["compare", "reference", "temporal"] and len(pending) == 8 + 8 + 2,
      f"a changed reference seed invalidates references, compares and temporal jobs only ({len(pending)})")

# Killed halfway: a slow reference job killed by SIGKILL leaves no record and no final image.
slow = dict(study, size="96x96", reference={"spp": 100000}, techniques=["direct"], scenes=["cornell-box"])
slow.pop("temporal")
slow_path = os.path.join(WORK, "slow.json")
with open(slow_path, "w") as f:
    json.dump(slow, f)
slow_out = os.path.join(WORK, "slow")
p = subprocess.Popen([BOUNCE, "sweep", slow_path, "--out", slow_out, "--job", "reference/cornell-box/b0/f0000"],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
time.sleep(2.0)  # long enough to be rendering; the job needs minutes
check(p.poll() is None, "the slow job is still running when killed")
p.send_signal(signal.SIGKILL)
p.wait()
folder = os.path.join(slow_out, "reference/cornell-box/b0/f0000")
left = os.listdir(folder) if os.path.isdir(folder) else []
check("record.json" not in left and "image.exr" not in left, f"a killed job leaves nothing that looks finished ({left})")
listing = run("sweep", slow_path, "--out", slow_out, "--list")
check("pending  reference/cornell-box/b0/f0000" in listing.stdout, "and it is pending again")

# GNU parallel: the emitted lists, run by parallel, give the same records as the local run.
par = os.path.join(WORK, "parallel")
r = run("sweep", study_path, "--out", par, "--emit", "parallel", "--jobs", "2")
check(r.returncode == 0 and os.path.exists(os.path.join(par, "jobs/run-parallel.sh")), f"--emit parallel ({r.stdout.strip()})")
with open(os.path.join(par, "jobs/stage1.txt")) as f:
    stage1 = f.read().splitlines()
check(len(stage1) == 16 and all(" --job " in l for l in stage1), "stage 1 lists 16 job commands")
check(records(par) == {}, "emitting runs nothing")
r = subprocess.run([os.path.join(par, "jobs/run-parallel.sh")], capture_output=True, text=True)
check(r.returncode == 0, f"run-parallel.sh succeeds ({r.stderr.strip()[-300:]})")
rec_local, rec_par = records(local), records(par)
check(sorted(rec_local) == sorted(rec_par), "same jobs")
same = [j for j in rec_local if comparable(rec_local[j]) == comparable(rec_par.get(j, {"kind": "", "job": j}))]
check(len(same) == len(rec_local), f"same records ({len(rec_local) - len(same)} differ: "
      f"{[j for j in rec_local if j not in same][:3]})")
for job in ("reference/two-rooms/all/f0000", "render/cornell-box/ambient/radiance-0.1"):
    name = "image.exr" if job.startswith("reference") else "full.exr"
    with open(os.path.join(local, job, name), "rb") as a, open(os.path.join(par, job, name), "rb") as b:
        check(a.read() == b.read(), f"{job}/{name} is byte-identical")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
