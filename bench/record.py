"""The raw-record envelope every bounce benchmark script writes (bench/results/NAME-DATE.json):
benchmark name, command, git commit, UTC date, machine and GPU, then the script's own fields."""
import datetime
import json
import os
import platform
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def new_record(name, command, bounce):
    info = subprocess.run([bounce, "info"], capture_output=True, text=True).stdout.splitlines()
    return {
        "benchmark": name,
        "command": command,
        "commit": subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "machine": f"{platform.node()} {platform.machine()} {cpu_model()}, {os.cpu_count()} cores",
        "gpu": " ".join(l.split(None, 1)[1] for l in info if l.startswith("renderer")),
    }


def write_record(record):
    """Writes bench/results/<benchmark>-<date>.json atomically and returns its path relative to the repo."""
    os.makedirs(os.path.join(ROOT, "bench/results"), exist_ok=True)
    path = os.path.join(ROOT, "bench/results", f"{record['benchmark']}-{record['date'][:10]}.json")
    with open(path + ".tmp", "w") as f:
        json.dump(record, f, indent=1)
    os.replace(path + ".tmp", path)
    return os.path.relpath(path, ROOT)
