#!/usr/bin/env python3
"""Device selection, the device profile and measured runs from the command line (issue 29; docs/gpu.md).

- `--gpu N` past the EGL device enumeration fails with one line naming the device count, before any
  work; a bad BOUNCE_EGL_DEVICE or BOUNCE_PROFILE too.
- `bounce info --json` lists the EGL devices and says which one the context uses, and its profile.
- `render --stats` records a non-debug context, the device and the profile; BOUNCE_PROFILE=gpu gives
  rsm's GPU batch default, and --set still wins over it.
- `bounce list` shows per-profile defaults.

Usage: gpu_cli_test.py BOUNCE WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

BOUNCE, WORK = sys.argv[1], sys.argv[2]
failures = []


def run(args, env=None, ok=True):
    e = dict(os.environ)
    for k in ("BOUNCE_EGL_DEVICE", "BOUNCE_PROFILE", "BOUNCE_EGL_PLATFORM", "BOUNCE_PORTABLE_LIMITS"):
        e.pop(k, None)
    e.update(env or {})
    p = subprocess.run([BOUNCE] + args, capture_output=True, text=True, env=e)
    if ok and p.returncode != 0:
        failures.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
    return p


def check(cond, what):
    if not cond:
        failures.append(what)


def one_line_error(p, args, *needles):
    lines = [l for l in p.stderr.splitlines() if l.strip()]
    check(p.returncode == 1, f"{args}: exit {p.returncode}, expected 1")
    check(len(lines) == 1, f"{args}: {len(lines)} stderr lines, expected one: {p.stderr!r}")
    for n in needles:
        check(n in p.stderr, f"{args}: error does not name {n!r}: {p.stderr!r}")


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

info = json.loads(run(["info", "--json"]).stdout or "{}")
devices = info.get("egl_devices", [])
count = len(devices)
check(all({"index", "name", "software"} <= set(d) for d in devices), f"device entries lack fields: {devices}")
check(info.get("profile") in ("llvmpipe", "gpu"), f"info --json profile: {info.get('profile')}")
check(info.get("debug_context") is True, "bounce info's context should be the default (debug) one")
noun = "1 EGL device" if count == 1 else f"{count} EGL devices" if count else "no EGL device"
one_line_error(run(["--gpu", "99", "info"], ok=False), "--gpu 99 info", "--gpu 99", noun)
# Checked before the command's work: even a command without a context refuses it.
one_line_error(run(["--gpu", "99", "list", "--scenes", "--names"], ok=False), "--gpu 99 list", noun)
one_line_error(run(["--gpu", "-1", "info"], ok=False), "--gpu -1 info", "--gpu")
one_line_error(run(["info"], env={"BOUNCE_EGL_DEVICE": "two"}, ok=False), "BOUNCE_EGL_DEVICE=two", "BOUNCE_EGL_DEVICE")
one_line_error(run(["info"], env={"BOUNCE_EGL_DEVICE": "99"}, ok=False), "BOUNCE_EGL_DEVICE=99", "BOUNCE_EGL_DEVICE 99", noun)
one_line_error(run(["info"], env={"BOUNCE_PROFILE": "fast"}, ok=False), "BOUNCE_PROFILE=fast", "BOUNCE_PROFILE")
if count:
    chosen = json.loads(run(["--gpu", str(count - 1), "info", "--json"]).stdout or "{}")
    check(chosen.get("device") == count - 1 and chosen.get("platform") == "egl-device",
          f"--gpu {count - 1}: device {chosen.get('device')} platform {chosen.get('platform')}")
    text = run(["--gpu", str(count - 1), "info"]).stdout
    check("<- in use" in text, "`bounce info` does not mark the device in use")
check(json.loads(run(["info", "--json"], env={"BOUNCE_PROFILE": "gpu"}).stdout or "{}").get("profile") == "gpu",
      "BOUNCE_PROFILE=gpu not shown by info --json")


def render_record(extra, env=None):
    stats = os.path.join(WORK, "run.json")
    run(["render", "--scene", "cornell-box", "--technique", "rsm", "--size", "16x16", "--out",
         os.path.join(WORK, "o.exr"), "--stats", stats] + extra, env=env)
    with open(stats) as f:
        return json.load(f)


r = render_record([])
check(r["gpu"].get("debug_context") is False, f"render --stats ran on a debug context: {r['gpu']}")
check(r["gpu"].get("profile") == info.get("profile"), f"record profile {r['gpu'].get('profile')} != info's")
check("device" in r["gpu"], "record lacks the device")
llvmpipe_batch = r["settings"]["vplBatch"] if r["gpu"].get("profile") == "llvmpipe" else None
g = render_record([], env={"BOUNCE_PROFILE": "gpu"})
check(g["gpu"]["profile"] == "gpu" and g["settings"]["vplBatch"] == 1024,
      f"BOUNCE_PROFILE=gpu: profile {g['gpu']['profile']}, vplBatch {g['settings']['vplBatch']} (expected 1024)")
l = render_record([], env={"BOUNCE_PROFILE": "llvmpipe"})
check(l["settings"]["vplBatch"] == 32768, f"BOUNCE_PROFILE=llvmpipe: vplBatch {l['settings']['vplBatch']}")
s = render_record(["--set", "vplBatch=64"], env={"BOUNCE_PROFILE": "gpu"})
check(s["settings"]["vplBatch"] == 64, f"--set vplBatch=64 under the gpu profile gave {s['settings']['vplBatch']}")

listing = run(["list", "--techniques"]).stdout
check("llvmpipe 32768, gpu 1024" in listing, "`bounce list` does not show rsm's per-profile vplBatch")
check("device profile:" in listing, "`bounce list` does not say where the profile comes from")

for f in failures:
    print("FAIL:", f, file=sys.stderr)
print(f"gpu_cli_test: {len(failures)} failure(s); {count} EGL device(s), profile {info.get('profile')}")
sys.exit(1 if failures else 0)
