#!/usr/bin/env python3
"""The bad-input matrix (ctest cli_bad_input_matrix; docs/reliability.md "Bad-input matrix").

Usage: run_matrix.py BOUNCE WORK [TABLE] [--only SUBSTRING]

Reads TABLE (default: matrix.txt beside this script), one case per line:

    command | class | expected text | arguments [| options]

and runs `BOUNCE arguments` for each, asserting: exit status 1; exactly one line on stderr; every
`&`-separated part of the expected text in it (the file, key or value at fault); and nothing new or
changed in the case's folder afterwards (no output, no temporary sibling), nor a new dot-file beside
an output outside it (/dev, /proc). `n/a` as the expected text marks a combination that does not
apply; the arguments column then says why. Every command x class of the table's @commands and
@classes lines must have a case or an n/a line.

Each case runs in a fresh folder WORK/cases/NNN-command-class holding a copy of this folder's
fixtures and the generated images, with these placeholders in the arguments:
  {W}                the case's folder
  {UNREADABLE:name}  `unreadable-name`: a copy of fixture `name` with mode 000, or, where mode 000
                     does not stop reading (root, CAP_DAC_OVERRIDE), a directory of that name: a
                     directory cannot be read as a file by anyone
  {UNREADABLE_DIR:name}  the same for a folder input: the fixture folder with mode 000, or, where
                     that does not stop listing it, a regular file of that name
  {RODIR}            a folder where no file can be created: `ro` with mode 555, or, where mode 555
                     does not stop writing (root), /proc (which refuses new files to root as well)
  {FULL:name}        `name`, a symbolic link to /dev/full (every write fails with ENOSPC)
  {RESULTS}          `results`, a copy of a finished tiny study's output folder
Options (space-separated): fsize=BYTES (RLIMIT_FSIZE: a write past it fails with EFBIG, a full disk
for regular files), as=BYTES (RLIMIT_AS; K/M/G suffixes), leaves=GLOB,... (paths under the case's
folder a case may leave, fnmatch globs, `*` crossing `/`, a trailing `/` for folders only, e.g. a sweep's resumable output folder), full=NAME (the case's folder gets
NAME, a link to /dev/full, without it being an argument: a later frame of a pattern). `view` cases run without DISPLAY:
they are the inputs checked before the window opens (a check moved after it would fail on the
missing display, and the message would not name the input).
"""
import concurrent.futures
import fnmatch
import os
import re
import resource
import shlex
import shutil
import stat
import struct
import subprocess
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
TIMEOUT_S = 120  # per case; a case that hangs is a failure in itself


def fail_setup(message):
    print(f"run_matrix.py: {message}", file=sys.stderr)
    sys.exit(2)


# ---- generated image fixtures -------------------------------------------------------------------

def exr_bytes(width, height, pixel, data_window=None, scanlines=True):
    """An uncompressed scanline OpenEXR file with FLOAT channels B, G, R (the format's own layout)."""
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    x0, y0, x1, y1 = data_window or (0, 0, width - 1, height - 1)
    header = (attr("channels", "chlist", chlist) + attr("compression", "compression", b"\0") +
              attr("dataWindow", "box2i", struct.pack("<iiii", x0, y0, x1, y1)) +
              attr("displayWindow", "box2i", struct.pack("<iiii", 0, 0, max(width - 1, 0), max(height - 1, 0))) +
              attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    out = struct.pack("<ii", 20000630, 2) + header
    if not scanlines:
        return out
    w, rows = x1 - x0 + 1, y1 - y0 + 1
    lines = []
    for y in range(rows):
        values = [pixel(x, y) for x in range(w)]
        data = b"".join(struct.pack(f"<{w}f", *[v[c] for v in values]) for c in (2, 1, 0))  # B, G, R
        lines.append(struct.pack("<ii", y0 + y, len(data)) + data)
    offset = len(out) + 8 * rows
    table = b""
    for line in lines:
        table += struct.pack("<Q", offset)
        offset += len(line)
    return out + table + b"".join(lines)


def png_bytes(width, height, rgb, idat=None):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in rgb(x, y)) for y in range(height)) if idat is None else b""
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw) if idat is None else idat) + chunk(b"IEND", b""))


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def make_images(folder):
    grey = lambda x, y: (0.25 + 0.01 * x, 0.5, 0.75 - 0.01 * y)
    write(os.path.join(folder, "good.exr"), exr_bytes(8, 8, grey))
    write(os.path.join(folder, "small.exr"), exr_bytes(4, 4, grey))
    write(os.path.join(folder, "nan.exr"), exr_bytes(8, 8, lambda x, y: (float("nan"), 0.5, 0.5) if (x, y) == (3, 5) else grey(x, y)))
    write(os.path.join(folder, "empty.exr"), exr_bytes(8, 8, grey, data_window=(0, 0, -1, -1)))  # 0 x 0 pixels
    # A header claiming 100000 x 100000 pixels (120 GB of float RGB), its line offset table, no pixels.
    header = exr_bytes(100000, 100000, grey, scanlines=False)
    write(os.path.join(folder, "huge.exr"), header + struct.pack("<Q", len(header) + 8 * 100000) * 100000)
    write(os.path.join(folder, "good.png"), png_bytes(8, 8, lambda x, y: (64, 128 + x, 192 - y)))
    write(os.path.join(folder, "huge.png"), png_bytes(100000, 100000, None, idat=zlib.compress(b"\0" * 64)))
    write(os.path.join(folder, "garbage.exr"), bytes((i * 97 + 13) % 256 for i in range(300)))
    write(os.path.join(folder, "garbage.png"), b"\x89PNG\r\n\x1a\n" + bytes((i * 31 + 7) % 256 for i in range(300)))


# ---- environment probes -------------------------------------------------------------------------

def mode_000_stops_reading(work):
    probe = os.path.join(work, "probe-read")
    write(probe, b"x")
    os.chmod(probe, 0)
    try:
        with open(probe, "rb"):
            return False
    except PermissionError:
        return True
    finally:
        os.chmod(probe, 0o600)
        os.remove(probe)


def mode_555_stops_writing(work):
    probe = os.path.join(work, "probe-write")
    os.mkdir(probe)
    os.chmod(probe, 0o555)
    try:
        with open(os.path.join(probe, "x"), "wb"):
            pass
        os.remove(os.path.join(probe, "x"))
        return False
    except PermissionError:
        return True
    finally:
        os.chmod(probe, 0o755)
        shutil.rmtree(probe)


# ---- the table ----------------------------------------------------------------------------------

class Case:
    def __init__(self, number, line, command, klass, expect, args, options):
        self.number, self.line, self.command, self.klass = number, line, command, klass
        self.expect, self.args, self.options = expect, args, options

    @property
    def applies(self):
        return self.expect != "n/a"


def read_table(path):
    commands, classes, cases = [], [], []
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            if line.startswith("@commands "):
                commands = line.split()[1:]
                continue
            if line.startswith("@classes "):
                classes = line.split()[1:]
                continue
            cols = [c.strip() for c in line.split(" | ")]
            if len(cols) not in (4, 5):
                fail_setup(f"{path}:{number}: expected 'command | class | expected text | arguments [| options]', got {len(cols)} columns")
            command, klass, expect, args = cols[:4]
            if command not in commands or klass not in classes:
                fail_setup(f"{path}:{number}: command '{command}' or class '{klass}' is not declared in @commands / @classes")
            options = {}
            for opt in (cols[4].split() if len(cols) == 5 else []):
                key, _, value = opt.partition("=")
                if key not in ("fsize", "as", "leaves", "full"):
                    fail_setup(f"{path}:{number}: unknown option '{key}' (known: fsize, as, leaves, full)")
                options[key] = value
            cases.append(Case(len(cases) + 1, number, command, klass, expect, args, options))
    return commands, classes, cases


def parse_bytes(text):
    m = re.fullmatch(r"(\d+)([KMG]?)", text)
    if not m:
        fail_setup(f"'{text}' is not a byte count")
    return int(m.group(1)) * {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30}[m.group(2)]


def snapshot(folder):
    state = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            st = os.lstat(path)
            # A folder's size and time change when a file is created and removed in it (a
            # writability probe, a temporary file): only files' contents count.
            content = (0, 0) if stat.S_ISDIR(st.st_mode) else (st.st_size, st.st_mtime_ns)
            state[os.path.relpath(path, folder)] = (stat.S_IFMT(st.st_mode),) + content
    return state


def dot_entries(folder):
    try:
        return {n for n in os.listdir(folder) if n.startswith(".")}
    except OSError:
        return set()


class Runner:
    def __init__(self, bounce, work):
        self.bounce, self.work = bounce, work
        self.fixtures = os.path.join(work, "fixtures")
        self.results = None
        self.unreadable_by_mode = mode_000_stops_reading(work)
        self.readonly_by_mode = mode_555_stops_writing(work)

    def prepare(self, cases):
        os.makedirs(self.fixtures)
        for name in os.listdir(HERE):
            source = os.path.join(HERE, name)
            if name in ("matrix.txt", "run_matrix.py", "__pycache__"):
                continue
            if os.path.isdir(source):
                shutil.copytree(source, os.path.join(self.fixtures, name))
            else:
                shutil.copy(source, self.fixtures)
        make_images(self.fixtures)
        if any("{RESULTS}" in c.args or "{UNREADABLE_DIR:results}" in c.args for c in cases if c.applies):
            # A finished tiny study: one render, its reference and their compare.
            study = os.path.join(self.work, "tiny-study.json")
            with open(study, "w") as f:
                f.write('{"name": "tiny", "size": "8x8", "scenes": ["cornell-box"], "techniques": ["direct"], '
                        '"reference": {"spp": 1}}\n')
            self.results = os.path.join(self.work, "results")
            r = subprocess.run([self.bounce, "sweep", study, "--out", self.results], capture_output=True, text=True,
                               timeout=TIMEOUT_S)
            if r.returncode != 0:
                fail_setup(f"the tiny study for {{RESULTS}} failed: {r.stderr.strip()}")

    def substitute(self, case, folder):
        def unreadable(m):
            name = m.group(1)
            path = os.path.join(folder, "unreadable-" + name)
            if self.unreadable_by_mode:
                shutil.copy(os.path.join(self.fixtures, name), path)
                os.chmod(path, 0)
            else:
                os.mkdir(path)
            return path

        def unreadable_dir(m):
            name = m.group(1)
            path = os.path.join(folder, "unreadable-" + name)
            if self.unreadable_by_mode:
                shutil.copytree(self.results if name == "results" else os.path.join(self.fixtures, name), path)
                os.chmod(path, 0)
            else:
                write(path, b"not a folder\n")
            return path

        def full(m):
            path = os.path.join(folder, m.group(1))
            os.symlink("/dev/full", path)
            return path

        if "full" in case.options:  # a link to /dev/full among the outputs, not in the arguments
            os.symlink("/dev/full", os.path.join(folder, case.options["full"]))
        text = case.args
        text = re.sub(r"\{UNREADABLE:([^}]+)\}", unreadable, text)
        text = re.sub(r"\{UNREADABLE_DIR:([^}]+)\}", unreadable_dir, text)
        text = re.sub(r"\{FULL:([^}]+)\}", full, text)
        if "{RODIR}" in text:
            if self.readonly_by_mode:
                os.mkdir(os.path.join(folder, "ro"), 0o555)
                text = text.replace("{RODIR}", os.path.join(folder, "ro"))
            else:
                text = text.replace("{RODIR}", "/proc")
        if "{RESULTS}" in text:
            shutil.copytree(self.results, os.path.join(folder, "results"))
            text = text.replace("{RESULTS}", os.path.join(folder, "results"))
        return shlex.split(text.replace("{W}", folder))

    def run(self, case):
        folder = os.path.join(self.work, "cases", f"{case.number:03d}-{case.command}-{case.klass}")
        shutil.copytree(self.fixtures, folder)
        args = self.substitute(case, folder)
        before = snapshot(folder)
        outside = {os.path.dirname(a) for a in args if a.startswith("/") and not a.startswith(folder) and a != self.bounce}
        outside |= {"/dev"}
        outside_before = {d: dot_entries(d) for d in outside}
        env = dict(os.environ)
        if case.command == "view":
            env.pop("DISPLAY", None)
            env.pop("WAYLAND_DISPLAY", None)
        limits = []
        if "fsize" in case.options:
            limits.append((resource.RLIMIT_FSIZE, parse_bytes(case.options["fsize"])))
        if "as" in case.options:
            limits.append((resource.RLIMIT_AS, parse_bytes(case.options["as"])))

        def preexec():
            for which, value in limits:
                resource.setrlimit(which, (value, value))

        start = time.monotonic()
        try:
            r = subprocess.run([self.bounce] + args, capture_output=True, text=True, env=env, timeout=TIMEOUT_S,
                               preexec_fn=preexec if limits else None)
            rc, err = r.returncode, r.stderr
        except subprocess.TimeoutExpired:
            rc, err = None, f"(timed out after {TIMEOUT_S} s)"
        seconds = time.monotonic() - start
        problems = []
        if rc != 1:
            problems.append(f"exit status {rc}, expected 1")
        lines = err.strip().splitlines()
        if len(lines) != 1:
            problems.append(f"{len(lines)} lines on stderr, expected exactly one")
        for part in (p.strip() for p in case.expect.split("&")):
            if part not in err:
                problems.append(f"stderr does not name '{part}'")
        allowed = [g for g in case.options.get("leaves", "").split(",") if g]
        after = snapshot(folder)
        for path, state in sorted(after.items()):
            name = path + "/" if stat.S_ISDIR(state[0]) else path  # a glob ending in / matches folders only
            if before.get(path) != state and not any(fnmatch.fnmatch(name, g) for g in allowed):
                problems.append(f"left {'a new' if path not in before else 'a changed'} {path}")
        for d, names in outside_before.items():
            for name in sorted(dot_entries(d) - names):
                problems.append(f"left {os.path.join(d, name)}")
        for root, dirs, files in os.walk(folder):  # let the next run's cleanup remove mode-000 entries
            for name in dirs + files:
                p = os.path.join(root, name)
                if not os.path.islink(p):
                    os.chmod(p, 0o755)
        return case, args, rc, err.strip(), problems, seconds


def main():
    argv = sys.argv[1:]
    only = None
    if "--only" in argv:
        i = argv.index("--only")
        only = argv[i + 1]
        del argv[i:i + 2]
    # --sanitized: bounce is the sanitizer preset's build (cmake/Sanitize.cmake). AddressSanitizer
    # reserves terabytes of shadow address space at start-up, so a case under an address-space limit
    # (as=) would test ASan's start-up, not bounce: those cases are left to the ordinary build.
    sanitized = "--sanitized" in argv
    if sanitized:
        argv.remove("--sanitized")
    if len(argv) not in (2, 3):
        fail_setup("usage: run_matrix.py BOUNCE WORK [TABLE] [--only SUBSTRING] [--sanitized]")
    bounce, work = os.path.abspath(argv[0]), os.path.abspath(argv[1])
    table = argv[2] if len(argv) == 3 else os.path.join(HERE, "matrix.txt")
    commands, classes, cases = read_table(table)
    if os.path.exists(work):
        for root, dirs, files in os.walk(work):
            for name in dirs:
                os.chmod(os.path.join(root, name), 0o755)
        shutil.rmtree(work)
    os.makedirs(work)
    runner = Runner(bounce, work)
    runner.prepare(cases)
    print(f"mode 000 stops reading here: {runner.unreadable_by_mode} (else a directory stands for the unreadable file); "
          f"mode 555 stops writing here: {runner.readonly_by_mode} (else /proc stands for the read-only folder)")

    failures = 0
    selected = [c for c in cases if c.applies and (only is None or only in f"{c.command} {c.klass} {c.args}")]
    if sanitized:
        limited = [c for c in selected if "as" in c.options]
        selected = [c for c in selected if "as" not in c.options]
        print(f"--sanitized: {len(limited)} case(s) under an address-space limit left to the ordinary build "
              f"(ASan's shadow memory does not fit one)")
    with concurrent.futures.ThreadPoolExecutor(max_workers=min(4, os.cpu_count() or 1)) as pool:
        for case, args, rc, err, problems, seconds in pool.map(runner.run, selected):
            status = "FAIL" if problems else "ok"
            print(f"{status:4} {case.command:10} {case.klass:19} {seconds:5.2f} s  {err}")
            if problems:
                failures += 1
                print(f"     {table}:{case.line}: bounce {shlex.join(args)}")
                for p in problems:
                    print(f"     - {p}")

    # Coverage: every command x class has a case or an n/a line with its reason.
    print("\nmatrix (cases per command and class; n/a = does not apply, see the table):")
    width = max(len(c) for c in classes)
    print(" " * width + "  " + " ".join(f"{c:>10}" for c in commands))
    missing = []
    for klass in classes:
        cells = []
        for command in commands:
            rows = [c for c in cases if c.command == command and c.klass == klass]
            if not rows:
                missing.append(f"{command} x {klass}")
                cells.append("MISSING")
            elif all(not c.applies for c in rows):
                cells.append("n/a")
            else:
                cells.append(str(sum(c.applies for c in rows)))
        print(f"{klass:<{width}}  " + " ".join(f"{c:>10}" for c in cells))
    if missing:
        print(f"\n{len(missing)} combination(s) have neither a case nor an n/a line: {', '.join(missing)}")
    print(f"\n{len(selected)} cases, {failures} failed")
    return 1 if failures or missing else 0


if __name__ == "__main__":
    sys.exit(main())
