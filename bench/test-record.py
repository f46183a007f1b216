#!/usr/bin/env python3
"""Runs GPU tests and keeps the values they measure (gtest RecordProperty) as a raw record.

Usage: bench/test-record.py NAME FILTER [BUILD]     e.g. bench/test-record.py vct-tests 'Vct*'

The tests assert bounds; the numbers a doc page quotes from them ("measured relMSE 0.11") come from
the record this writes to bench/results/NAME-<date>.json (command, commit, date, machine, GPU, and
per test its properties and pass/fail), so each quoted number has its raw record.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from record import new_record, write_record  # noqa: E402


def main():
    if len(sys.argv) < 3:
        print("usage: bench/test-record.py NAME FILTER [BUILD]", file=sys.stderr)
        sys.exit(1)
    name, pattern = sys.argv[1], sys.argv[2]
    build = sys.argv[3] if len(sys.argv) > 3 else os.path.join(ROOT, "build")
    binary = os.path.join(build, "tests", "bounce_gpu_tests")
    bounce = os.path.join(build, "src", "app", "bounce")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "tests.json")
        run = subprocess.run([binary, f"--gtest_filter={pattern}", f"--gtest_output=json:{out}"], capture_output=True, text=True)
        with open(out) as f:
            report = json.load(f)
    tests = {}
    for suite in report["testsuites"]:
        for t in suite["testsuite"]:
            props = {k: v for k, v in t.items() if k not in ("name", "status", "result", "timestamp", "time", "classname", "file", "line", "failures")}
            tests[f"{suite['name']}.{t['name']}"] = {"passed": "failures" not in t, "time": t.get("time"), "properties": props}
    record = new_record(name, f"bench/test-record.py {name} '{pattern}'", bounce)
    record.update({"exitCode": run.returncode, "tests": tests})
    print("wrote", write_record(record), "exit", run.returncode)
    sys.exit(run.returncode)


if __name__ == "__main__":
    main()
