#!/usr/bin/env python3
"""The glslang CTest (issue 29; docs/gpu.md "glslangValidator").

Every program and define combination the portable-limits run compiled (dumped by Program::build under
BOUNCE_SHADER_DUMP: the exact text the driver gets, includes and defines resolved) is compiled and
linked by glslangValidator, Khronos' reference front end, with resource limits at the GL 4.5 minimums
(gl45-minimum.conf: `glslangValidator -c` with the GL 4.5 minimum maxima where its defaults differ;
glslang enforces local sizes, max_vertices, sampler bindings and the gl_Max* built-ins from it).
Mesa accepts some GLSL that stricter compilers reject; this is a second opinion. A program named in
the allow-list with key `glslang` may fail (a known finding); a listed one that passes is stale.

Usage: glslang_test.py DUMP_DIR ALLOW_LIST LIMITS_CONF [GLSLANG]
Exit 77 (skipped) when glslangValidator is missing, except under CI=true (then a failure).
"""
import os
import shutil
import subprocess
import sys

STAGES = (".vert", ".geom", ".frag", ".comp")


def main():
    dump, allow, conf = sys.argv[1:4]
    glslang = sys.argv[4] if len(sys.argv) > 4 and sys.argv[4] else shutil.which("glslangValidator")
    if not glslang:
        print("glslangValidator not found (Debian: glslang-tools; scripts/install-deps.sh installs it)", file=sys.stderr)
        return 1 if os.environ.get("CI") == "true" else 77
    if not os.path.isdir(dump) or not os.listdir(dump):
        print(f"{dump}: no dumped programs (the gpu_portable_limits test writes them)", file=sys.stderr)
        return 1
    allowed = {}
    with open(allow) as f:
        for n, line in enumerate(f, 1):
            w = line.split()
            if len(w) >= 3 and not w[0].startswith("#") and w[1] == "glslang":
                allowed[w[0]] = (w[2], n)
    failures, failed_allowed, programs = [], set(), 0
    for folder in sorted(os.listdir(dump)):
        path = os.path.join(dump, folder)
        files = sorted(os.path.join(path, f) for f in os.listdir(path) if f.endswith(STAGES))
        if not files:
            continue
        with open(os.path.join(path, "program.txt")) as f:
            label = f.readline().strip()
        programs += 1
        p = subprocess.run([glslang, "-l", conf] + files, capture_output=True, text=True)
        errors = [l for l in (p.stdout + p.stderr).splitlines() if "ERROR" in l]
        if p.returncode == 0:
            continue
        if label in allowed:
            failed_allowed.add(label)
            print(f"known ({allowed[label][0]}): {label}: {errors[0] if errors else 'exit %d' % p.returncode}")
            continue
        failures.append((label, folder, errors[:3] or [f"exit {p.returncode}"]))
    print(f"glslangValidator: {programs} program variants, {len(failures)} failed")
    for label, folder, errors in failures:
        print(f"  {label} ({folder}):", file=sys.stderr)
        for e in errors:
            print(f"    {e}", file=sys.stderr)
    stale = [l for l in allowed if l not in failed_allowed]
    for l in stale:
        print(f"{allow}:{allowed[l][1]}: stale: no variant of {l} fails glslang now: remove the line", file=sys.stderr)
    return 1 if failures or stale else 0


if __name__ == "__main__":
    sys.exit(main())
