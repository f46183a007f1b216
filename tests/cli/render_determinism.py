#!/usr/bin/env python3
"""`bounce render` is deterministic (ctest render_determinism; docs/reliability.md "Determinism").

Usage: render_determinism.py BOUNCE WORK

Every technique `bounce list` names (so a technique added later is tested without editing this
file) renders 3 frames of cornell-box-dynamic at 64x64 twice, the second time with llvmpipe on one
thread (LP_NUM_THREADS=1: a different rasterisation schedule; ignored by other drivers), and the two
EXR files must be byte-identical. A technique that refuses cornell-box-dynamic (the radiosity methods
and area-light shade area lights only) runs on the first scene of FALLBACK_SCENES it accepts; one
that accepts none fails the test, so its scene is chosen here on purpose.

A technique that cannot be bit-identical gets an entry in BOUNDS: its largest relative RMS
difference between the two runs, and its doc page, which must say why (the test checks the page
names the bound). isr has one: its cluster VPLs are appended by an atomic counter in thread order and
summed in that order (sorting them needed a CPU readback on the frame's path, which issue 18 removed),
so the image differs between runs in its last bits.
"""
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = "cornell-box-dynamic"
FALLBACK_SCENES = ["cornell-box-rotating", "area-screen"]
SIZE, FRAMES = "64x64", 3
# Techniques that keep state from frame to frame run longer: iir's VPL set diverged after about seven
# frames while CGAL's iteration order decided ties (docs/reliability.md "Determinism").
FRAMES_OF = {"iir": 10}
# technique -> (largest relative RMS between the two runs, doc page that explains it)
# The bound is text, as the page must spell it ("1e-5"; Python would print 1e-05).
BOUNDS = {"isr": ("1e-5", "docs/techniques/isr.md")}
# Settings that make a slow technique cheap: the same passes run, on fewer elements. radiosity-gather
# renders a hemicube per element per bounce: 47 s for these 3 frames at its defaults, 0.6 s here.
CHEAP_SETTINGS = {"radiosity-gather": ["elementSize=0.1", "dynamicElementSize=0.1", "bounces=2", "hemicubeSize=16"],
                  # The shooting methods' per-frame time budget (frameBudgetMs) cuts a frame's shooting where the
                  # host's clock says: by design not reproducible (docs/techniques/radiosity.md); maxIterations alone
                  # bounds their frames here. Measured with the budget on a loaded host: incremental 0.0018 and
                  # cross 0.006 relative RMS between two runs.
                  "radiosity-pr": ["frameBudgetMs=0"], "radiosity-incremental": ["frameBudgetMs=0"],
                  "radiosity-cross": ["frameBudgetMs=0"]}


def techniques(bounce):
    """Every registered technique, as `bounce list --techniques --names` prints them (one per line)."""
    out = subprocess.run([bounce, "list", "--techniques", "--names"], capture_output=True, text=True, check=True).stdout
    return out.split()


def render(bounce, technique, scene, out, single_thread):
    env = dict(os.environ)
    if single_thread:
        env["LP_NUM_THREADS"] = "1"
    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", SIZE, "--frames", str(FRAMES_OF.get(technique, FRAMES)), "--out", out]
    for setting in CHEAP_SETTINGS.get(technique, []):
        cmd += ["--set", setting]
    return subprocess.run(cmd, capture_output=True, text=True, env=env)


def check(bounce, work, technique):
    folder = os.path.join(work, technique)
    os.makedirs(folder)
    a, b = os.path.join(folder, "a.exr"), os.path.join(folder, "b.exr")
    refusals = []
    for scene in [SCENE] + FALLBACK_SCENES:
        r = render(bounce, technique, scene, a, single_thread=False)
        if r.returncode == 0:
            break
        # A technique refusing a scene says so in one line naming itself (Pipeline::create).
        if f"technique '{technique}'" not in r.stderr:
            return technique, scene, f"render failed: {r.stderr.strip()}"
        refusals.append(f"{scene}: {r.stderr.strip()}")
    else:
        return technique, None, "refuses every scene the test knows: " + "; ".join(refusals)
    r = render(bounce, technique, scene, b, single_thread=True)
    if r.returncode != 0:
        return technique, scene, f"second render failed: {r.stderr.strip()}"
    with open(a, "rb") as fa, open(b, "rb") as fb:
        if fa.read() == fb.read():
            return technique, scene, None
    metrics = json.loads(subprocess.run([bounce, "compare", "--json", a, b], capture_output=True, text=True,
                                        check=True).stdout)["metrics"]
    rel = metrics["relRms"]
    if technique not in BOUNDS:
        return technique, scene, f"the two runs differ (relative RMS {rel:.3g}) and BOUNDS has no entry for it"
    bound, page = BOUNDS[technique]
    with open(os.path.join(ROOT, page), encoding="utf-8") as f:
        if bound not in f.read():
            return technique, scene, f"{page} does not state the bound {bound}"
    if rel > float(bound):
        return technique, scene, f"relative RMS {rel:.3g} between runs exceeds the bound {bound} of {page}"
    return technique, scene, None


def main():
    if len(sys.argv) != 3:
        print("usage: render_determinism.py BOUNCE WORK", file=sys.stderr)
        return 2
    bounce, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    names = techniques(bounce)
    if len(names) < 2:
        print(f"`bounce list` named {len(names)} technique(s): the list format changed?", file=sys.stderr)
        return 1
    failures = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for technique, scene, problem in pool.map(lambda t: check(bounce, work, t), names):
            print(f"{'FAIL' if problem else 'ok':4} {technique:22} {scene or '-':22} {problem or 'bit-identical'}")
            failures += problem is not None
    print(f"{len(names)} techniques, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
