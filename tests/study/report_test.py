#!/usr/bin/env python3
# `bounce report` on the tiny study of sweep_test.py (ctest study_report): results.json / .csv are
# readable tables, and headless Chromium loads the page from file:// with no console error, every
# image and plot decoded with a non-zero size, and a screenshot that is not blank.
#
# usage: report_test.py BOUNCE RESULTS_DIR CHROMIUM   (CHROMIUM empty: skipped, exit 77, unless CI=true)
import csv
import html
import json
import os
import re
import subprocess
import sys

BOUNCE, RESULTS, CHROMIUM = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def check(condition, message):
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


r = subprocess.run([BOUNCE, "report", RESULTS], capture_output=True, text=True)
page = os.path.join(RESULTS, "report.html")
check(r.returncode == 0 and r.stdout.strip() == os.path.abspath(page), f"bounce report prints the page's path ({r.stderr.strip()})")
with open(os.path.join(RESULTS, "results.json")) as f:
    rows = json.load(f)
check(isinstance(rows, list) and len(rows) == 8 and all(isinstance(x, dict) for x in rows),
      "results.json: one flat object per scene x variant (pandas.read_json reads a list of records)")
direct = [x for x in rows if x["scene"] == "two-rooms" and x["technique"] == "direct"][0]
check(direct["relMse"] > 0 and direct["frame_ms"] > 0 and direct["leak_test"] == 0.0, "rows carry metrics, times and leak")
check(direct["relMse_floor"] > 0 and isinstance(direct["relMse_insideFloor"], bool) and direct["reference_scope"] == "b0"
      and "relMseCorrected" in direct and direct["reference_noise"] > 0,
      "rows carry each metric's noise floor, its inside-2x flag, the corrected relMSE and the reference's noise")
with open(os.path.join(RESULTS, "results.csv"), newline="") as f:
    table = list(csv.DictReader(f))
check(len(table) == 8 and "relMse" in table[0] and "pass_gbuffer_ms" in table[0] and "flipLdr_floor" in table[0],
      "results.csv has the same rows and columns")
with open(page) as f:
    text = f.read()
check("reference-noise floor" in text and 'class="inside"' in text,
      "the page says which comparisons are inside the floor (grey cells)")

bad = subprocess.run([BOUNCE, "report", os.path.join(RESULTS, "no-such-folder")], capture_output=True, text=True)
check(bad.returncode != 0 and bad.stderr.count("\n") == 1 and "not a folder" in bad.stderr, "a bad folder: one-line error")

if not CHROMIUM:
    if os.environ.get("CI") == "true":
        print("FAIL: CI=true but chromium is missing (scripts/install-deps.sh installs it)")
        sys.exit(1)
    print("skipped: chromium is not installed (scripts/install-deps.sh installs it)")
    sys.exit(77)

# Root (CI, this machine) needs --no-sandbox; the virtual time budget lets every image decode and
# the load handler run before the DOM is dumped.
flags = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--hide-scrollbars",
         "--window-size=1280,1600", "--virtual-time-budget=10000", "--enable-logging=stderr", "--v=0",
         f"--user-data-dir={os.path.join(RESULTS, '.chromium-profile')}"]
url = "file://" + os.path.abspath(page)
dom = subprocess.run([CHROMIUM, *flags, "--dump-dom", url], capture_output=True, text=True, timeout=120)
check(dom.returncode == 0, "chromium --dump-dom ran")
console = [l for l in dom.stderr.splitlines() if "CONSOLE" in l]
check(not console, f"no console messages ({console[:2]})")
m = re.search(r'data-selftest="([^"]*)"', dom.stdout)
check(m is not None, "the page's load handler ran (data-selftest)")
if m:
    selftest = json.loads(html.unescape(m.group(1)))
    print(f"selftest: {selftest}")
    # 8 variants: 6 rendered rows x (3 components + reference) = 24 grid images; plots: 2 scatter + 1 temporal.
    check(selftest["grids"] == 24, f"24 grid images ({selftest['grids']})")
    check(selftest["plots"] == 3, f"2 error-vs-time plots and 1 temporal plot ({selftest['plots']})")
    check(not selftest["bad"], f"every image decoded with a non-zero size ({selftest['bad'][:3]})")
    check(not selftest["errors"], f"no script errors ({selftest['errors'][:2]})")

shot = os.path.join(RESULTS, "report-screenshot.png")
if os.path.exists(shot):
    os.remove(shot)
subprocess.run([CHROMIUM, *flags, f"--screenshot={shot}", url], capture_output=True, timeout=120)
check(os.path.exists(shot), "screenshot taken")
if os.path.exists(shot):
    import matplotlib.image

    pixels = matplotlib.image.imread(shot)
    # A blank page is one colour; text, tables and images give a spread far above 8-bit noise.
    check(pixels.shape[0] >= 1000 and pixels[..., :3].std() > 0.05, f"screenshot not blank (std {pixels[..., :3].std():.3f})")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
