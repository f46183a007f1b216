"""What the study tests share: the check list, running bounce, JSON files (events_test.py, leaks_test.py)."""
import json
import subprocess

failures = []


def check(condition, message):
    print(f"{'ok' if condition else 'FAIL'}: {message}")
    if not condition:
        failures.append(message)


def runner(bounce):
    def run(*args):
        return subprocess.run([bounce, *args], capture_output=True, text=True)
    return run


def write_json(path, value):
    with open(path, "w") as f:
        json.dump(value, f, indent=1)


def load(path):
    with open(path) as f:
        return json.load(f)
