"""Helpers the benchmark scripts share: running `bounce render` with a run record, comparing images,
summaries. Every command is recorded relative to the repository (rel)."""
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rel(cmd):
    return " ".join(os.path.relpath(c, ROOT) if os.path.isabs(c) and c.startswith(ROOT) else c for c in cmd)


def option(args, name, default, kind=int):
    """Removes `name VALUE` from args and returns VALUE (as kind), or default."""
    if name in args:
        i = args.index(name)
        value = args[i + 1]
        del args[i:i + 2]
        return kind(value)
    return default


def render(bounce, scene, technique, size, frames, settings=None, params=None, out=None, component=None):
    """Runs `bounce render --stats`; returns (run record, command). `size`: N (N x N) or "WxH"."""
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "run.json")
        dims = size if isinstance(size, str) else f"{size}x{size}"
        cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", dims,
               "--frames", str(frames), "--out", out or os.path.join(tmp, "o.exr"), "--stats", stats]
        for p in params or []:
            cmd += ["--scene-param", p]
        for k, v in (settings or {}).items():
            cmd += ["--set", f"{k}={v}"]
        if component:
            cmd += ["--component", component]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        with open(stats) as f:
            return json.load(f), rel(cmd)


def compare(bounce, test, ref, keys=None):
    """`bounce compare --json test ref`'s metrics: all of them, or those named in `keys` (in that order)."""
    out = subprocess.run([bounce, "compare", "--json", test, ref], check=True, capture_output=True, text=True).stdout
    metrics = json.loads(out)["metrics"]
    return metrics if keys is None else {k: metrics[k] for k in keys}


def later(record):
    """The frames after the first (the first compiles shaders on llvmpipe and fills caches)."""
    return record["frames"][1:] or record["frames"]


def summary(values, n=True):
    """min, median, max (and the count n unless n=False) of `values`."""
    values = list(values)
    s = {"min": min(values), "median": statistics.median(values), "max": max(values)}
    if n:
        s["n"] = len(values)
    return s


def pass_ms(record, scope):
    return [f["gpu_ms"].get(scope, 0.0) for f in later(record)]


def counter_mean(record, name):
    frames = later(record)
    return sum(f["counters"].get(name, 0.0) for f in frames) / len(frames)
