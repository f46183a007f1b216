#!/usr/bin/env bash
# One command for a GPU machine (issue 29; docs/gpu.md "GPU check"; README "Running on your GPU"):
# builds bounce (or uses a carried build), prints `bounce info`, runs the GPU test suite on the EGL
# device platform, then the interactive benchmark's sides and the fidelity survey at 1080p and every
# technique's image against llvmpipe's (bench/gpu_check.py), and writes bench/results/gpu-<date>.json
# naming the GPU and its driver. Designed to finish inside 8 minutes on one H100 with a carried build
# (stage budgets below); on llvmpipe it says so and runs a reduced version end to end.
#
# Usage: scripts/gpu-check.sh [--build-dir DIR] [--no-build] [--reduced] [--gpu N] [--out FILE]
#   --build-dir DIR  build folder (default: build); configured and built with cmake unless --no-build
#   --no-build       use DIR as it is (a build carried to the machine)
#   --reduced        the llvmpipe-sized run even on a GPU (a smoke test of this script)
#   --gpu N          the EGL device to use (`bounce info` lists them); default: the automatic choice
#   --out FILE       write the record there instead of bench/results/gpu-<date>.json
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build="$here/build"
do_build=1
reduced=0
gpu=""
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build=$(cd "$2" 2>/dev/null && pwd || echo "$2"); shift 2 ;;
    --no-build) do_build=0; shift ;;
    --reduced) reduced=1; shift ;;
    --gpu) gpu="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "gpu-check: unknown option '$1' (see --help)" >&2; exit 1 ;;
  esac
done
[ -n "$gpu" ] && export BOUNCE_EGL_DEVICE="$gpu"
python=/usr/bin/python3
[ -x "$python" ] || python=python3
start=$(date +%s)
stage() { echo "== gpu-check: $1 ($(( $(date +%s) - start )) s)"; }

# Stage budgets, seconds (8 minutes in all on an H100 with a carried build): tests 150, measurements 300.
tests_budget=150
bench_budget=300

if [ "$do_build" = 1 ]; then
  stage "build ($build)"
  if [ ! -f "$build/CMakeCache.txt" ]; then
    launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
    cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
  fi
  cmake --build "$build" -j "$(nproc)" --target bounce bounce_gpu_tests >/dev/null
fi
bounce="$build/src/app/bounce"
tests="$build/tests/bounce_gpu_tests"
for f in "$bounce" "$tests"; do
  [ -x "$f" ] || { echo "gpu-check: $f missing (build it, or drop --no-build)" >&2; exit 1; }
done

stage "bounce info"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bounce" info
"$bounce" info --json > "$work/info.json"
profile=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["profile"])' "$work/info.json")
if [ "$profile" != gpu ]; then
  echo "gpu-check: the renderer is not a GPU (profile '$profile'): running the reduced check on llvmpipe."
  echo "gpu-check: on a GPU machine, check that its EGL vendor library is installed (bounce info lists the EGL devices)."
  reduced=1
fi

stage "GPU tests (EGL device platform)"
# On a GPU the whole suite on the device platform (BOUNCE_EGL_PLATFORM=device: no silent llvmpipe), in
# parallel processes, stopped at the budget; on llvmpipe the portability tests only.
filter='*'
platform=device
if [ "$reduced" = 1 ]; then
  filter='PortabilityGpuTest.*:GpuFoundationGpuTest.*'
  [ "$profile" = gpu ] || platform=surfaceless
fi
"$python" - "$tests" "$filter" "$platform" "$tests_budget" "$work/tests.json" <<'PY'
import json, os, subprocess, sys, time, concurrent.futures as cf
binary, filt, platform, budget, out = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5]
env = dict(os.environ, CI="true", BOUNCE_EGL_PLATFORM=platform)
listing = subprocess.run([binary, "--gtest_list_tests", f"--gtest_filter={filt}"], capture_output=True, text=True, env=env).stdout
suites, names = None, []
for line in listing.splitlines():
    if not line.startswith(" "):
        suites = line.strip()
    elif suites:
        names.append(suites + line.strip().split()[0])
deadline = time.monotonic() + budget
def one(name):
    if time.monotonic() > deadline:
        return name, "skipped", 0.0, ""
    t0 = time.monotonic()
    try:
        p = subprocess.run([binary, f"--gtest_filter={name}"], capture_output=True, text=True, env=env,
                           timeout=max(deadline - time.monotonic(), 1))
        status = "passed" if p.returncode == 0 else "failed"
        tail = "" if p.returncode == 0 else "\n".join((p.stdout + p.stderr).splitlines()[-8:])
    except subprocess.TimeoutExpired:
        status, tail = "timeout", ""
    return name, status, time.monotonic() - t0, tail
workers = max(1, min(8, os.cpu_count() or 1))
with cf.ThreadPoolExecutor(workers) as pool:
    results = list(pool.map(one, names))
counts = {s: sum(1 for r in results if r[1] == s) for s in ("passed", "failed", "timeout", "skipped")}
failed = [{"test": n, "seconds": round(t, 2), "log": tail} for n, s, t, tail in results if s in ("failed", "timeout")]
json.dump({"filter": filt, "platform": platform, "budget_s": budget, "counts": counts, "failed": failed,
           "seconds": {n: round(t, 2) for n, s, t, _ in results if s != "skipped"}}, open(out, "w"), indent=1)
print(f"gpu tests: {counts['passed']} passed, {counts['failed']} failed, {counts['timeout']} timed out, "
      f"{counts['skipped']} not run (budget {budget:.0f} s)")
for f in failed:
    print(f"  FAILED {f['test']}")
PY

stage "benchmarks (bench/gpu_check.py)"
budget=$bench_budget
[ "$reduced" = 1 ] && budget=60
args=(--info "$work/info.json" --tests "$work/tests.json" --budget "$budget")
[ "$reduced" = 1 ] && args+=(--reduced)
[ -n "$out" ] && args+=(--out "$out")
"$python" "$here/bench/gpu_check.py" "$bounce" "${args[@]}"
stage "done"
[ "$profile" = gpu ] || echo "gpu-check: NOT A GPU: this record is llvmpipe's (reduced), not a GPU measurement."
# The record is written either way; the exit status says whether every GPU test that ran passed.
bad=$("$python" -c 'import json,sys; c=json.load(open(sys.argv[1]))["counts"]; print(c["failed"]+c["timeout"])' "$work/tests.json")
if [ "$bad" != 0 ]; then
  echo "gpu-check: $bad GPU test(s) failed or timed out (listed above and in the record)" >&2
  exit 1
fi
