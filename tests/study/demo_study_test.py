#!/usr/bin/env python3
# The demo study (scripts/demo-study.json, `make demo`, docs/studies.md "A complete example") is the
# issue's "done when" study: at least three scenes x every registered technique x two settings each
# (ctest study_demo_covers_registry). A technique added to the registry without a line in the demo
# study fails here instead of silently missing from the example.
#
# usage: demo_study_test.py BOUNCE DEMO_STUDY
import subprocess
import sys

BOUNCE, STUDY = sys.argv[1], sys.argv[2]
names = subprocess.run([BOUNCE, "list", "--techniques", "--names"], capture_output=True, text=True, check=True).stdout.split()
listing = subprocess.run([BOUNCE, "sweep", STUDY, "--list"], capture_output=True, text=True, check=True).stdout
renders = [line.split()[3].split("/") for line in listing.splitlines() if line.split()[1] == "render"]
scenes = sorted({r[1] for r in renders})
failures = []
if len(scenes) < 3:
    failures.append(f"{len(scenes)} scenes ({scenes}), at least 3 wanted")
if not names:
    failures.append("bounce list --techniques --names printed no technique")
for scene in scenes:
    for technique in names:
        variants = {r[3] for r in renders if r[1] == scene and r[2] == technique}
        if len(variants) < 2:
            failures.append(f"{scene}: technique '{technique}' has {len(variants)} settings variants, 2 wanted")
for f in failures:
    print(f"FAIL: {f}")
if failures:
    sys.exit(1)
print(f"ok: {len(scenes)} scenes x {len(names)} techniques x >= 2 variants ({len(renders)} renders)")
