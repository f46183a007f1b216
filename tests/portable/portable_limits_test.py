#!/usr/bin/env python3
"""The portable-limits CTest (issue 29; docs/gpu.md "Portable-limits mode").

Runs a subset of the GPU tests that builds every technique's programs (every technique on every
built-in scene at its defaults, and the debug views) with BOUNCE_PORTABLE_LIMITS=1: GpuInfo is clamped
to the GL 4.5 minimums and a program past a portable limit fails to link. Known findings are let
through by the allow-list; an allow-list line that no program hits any more fails the test (its
finding was fixed: remove the line). The assembled shader sources are dumped for the glslang test.

The same run checks memory barriers (BOUNCE_BARRIER_CHECK=1, src/gpu/BarrierTracker.h): a shader-written
buffer or texture read as a uniform block, sampler, indirect or vertex buffer or by a readback without
the matching glMemoryBarrier bit fails its test. Two technique tests whose CPU readbacks the
every-technique test does not make (photon-splat's rsm injection, area-light's counters) are added.

Usage: portable_limits_test.py GPU_TEST_BINARY ALLOW_LIST WORK_DIR [GTEST_FILTER]
"""
import os
import shutil
import subprocess
import sys

FILTER = ("PipelineGpuTest.EveryTechniqueRendersEveryBuiltinSceneWithFiniteOutput:DebugViewsGpuTest.*:"
          "PhotonSplatGpuTest.RsmInjectionCarriesTheSamePowerAsShotPhotons:"
          "AreaLightGpuTest.MatchesThePathTracersDirectLightOnCornellBoxArea")


def read_allow_list(path):
    entries = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            entries.append((words[0], words[1], words[2], n))
    return entries


def main():
    binary, allow, work = sys.argv[1:4]
    gtest_filter = sys.argv[4] if len(sys.argv) > 4 else FILTER
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    report = os.path.join(work, "report.tsv")
    env = dict(os.environ, BOUNCE_PORTABLE_LIMITS="1", BOUNCE_PORTABLE_ALLOW=allow, BOUNCE_PORTABLE_REPORT=report,
               BOUNCE_SHADER_DUMP=os.path.join(work, "shaders"), BOUNCE_BARRIER_CHECK="1")
    p = subprocess.run([binary, f"--gtest_filter={gtest_filter}"], env=env, capture_output=True, text=True)
    rows = []
    if os.path.exists(report):
        with open(report) as f:
            rows = [line.rstrip("\n").split("\t") for line in f if line.strip()]
    for status in ("allowed", "warn"):
        found = sorted({(r[1], r[2], r[3], r[4]) for r in rows if r[0] == status})
        print(f"{len(found)} {status} finding(s){' (past a portable limit, in the allow-list)' if status == 'allowed' else ' (past the GL minimum only)'}:")
        for program, key, value, minimum in found:
            print(f"  {program:36} {key:26} {value:>6} (GL 4.5 minimum {minimum})")
    if p.returncode != 0:
        failed = [l for l in p.stdout.splitlines()
                  if "FAILED" in l or "portable limit" in l or "Failure" in l or "missing memory barrier" in l]
        print(p.stdout[-6000:])
        print(p.stderr[-3000:], file=sys.stderr)
        print(f"portable-limits / barrier-check run failed (exit {p.returncode}); {len(failed)} failure line(s) above", file=sys.stderr)
        return 1
    hit = {(r[1], r[2]) for r in rows if r[0] == "allowed"}
    stale = [(prog, key, finding, n) for prog, key, finding, n in read_allow_list(allow)
             if key != "glslang" and (prog, key) not in hit]
    for prog, key, finding, n in stale:
        print(f"{allow}:{n}: stale: {prog} {key} (finding {finding}) was not hit: fixed? remove the line", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
