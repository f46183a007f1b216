#!/usr/bin/env python3
"""The viewer under real input events (ctest view_input): run inside xvfb-run, it starts `bounce view`
with tests/viewer/input.txt, sends X events through XTEST with xdotool (a left drag over the view, a
ctrl + left drag, key taps: `.` three times, `b`, F12, space) and checks that each had its effect on the
state the viewer reports (camera orbit, the selected light's position, frame, A/B mode, the F12
screenshot files, playing).

Usage: input.py BOUNCE IMAGE_CHECK SCRIPT WORKDIR
"""
import json
import math
import os
import shutil
import subprocess
import sys
import time

bounce, check, script, work = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)  # a fresh folder: the F12 files are numbered from 0000
os.makedirs(work)
os.chdir(work)
failures = []

# 660x400 window: the panel takes min(340, 660 / 2) = 330 pixels, the view is x in [330, 660).
WIDTH, HEIGHT, PANEL = 660, 400, 330
viewer = subprocess.Popen([bounce, "view", "--scene", "cornell-box-dynamic", "--technique", "direct", "--size", f"{WIDTH}x{HEIGHT}",
                           "--render-size", "128x128", "--screenshot-dir", ".", "--script", script])


def xdo(*args):
    subprocess.run(["xdotool", *args], check=True)


def wait_for(name, seconds=120):
    """Until the viewer wrote `name` (its state files are written atomically), or it exited."""
    end = time.time() + seconds
    while time.time() < end:
        if os.path.exists(name):
            with open(name) as f:
                return json.load(f)
        if viewer.poll() is not None:
            sys.exit(f"view_input: the viewer exited ({viewer.returncode}) before writing {name}")
        time.sleep(0.1)
    viewer.kill()
    sys.exit(f"view_input: {name} did not appear in {seconds} s")


def pause():
    # Much longer than a frame (128^2 direct on llvmpipe: about 30 ms, more on a loaded machine), so
    # that the viewer's once-a-frame reads of the button and cursor see each step of a drag (a drag
    # shorter than a frame is lost, as it would be for a person).
    time.sleep(1.0)


def signal(name):
    open(name, "w").close()


def expect(what, ok, detail):
    print(("ok: " if ok else "FAILED: ") + f"{what}: {detail}")
    if not ok:
        failures.append(what)


s0 = wait_for("in-0.json")
window = subprocess.run(["xdotool", "search", "--sync", "--name", "bounce view"], check=True, capture_output=True,
                        text=True).stdout.split()[0]

# Left drag 100 pixels to the right over the view: orbit yaw -= 100 px x 0.005 rad/px.
y = HEIGHT // 2
xdo("mousemove", "--window", window, str(PANEL + 60), str(y))
pause()
xdo("mousedown", "1")
pause()
xdo("mousemove", "--window", window, str(PANEL + 160), str(y))
pause()
xdo("mouseup", "1")
pause()
# One notch of the wheel up (X button 4) zooms in: distance x 0.9.
xdo("click", "4")
pause()
signal("go-orbit")
s1 = wait_for("in-orbit.json")
dyaw = s1["orbit"]["yaw"] - s0["orbit"]["yaw"]
# The cursor moves in whole pixels and the factor is exact: 1e-5 rad is float rounding of the angle.
expect("left drag orbits", abs(dyaw + 0.5) < 1e-5 and abs(s1["orbit"]["pitch"] - s0["orbit"]["pitch"]) < 1e-6,
       f"yaw changed by {dyaw:.6f} rad (expected -0.5), pitch by {s1['orbit']['pitch'] - s0['orbit']['pitch']:.2e}")
ratio = s1["orbit"]["distance"] / s0["orbit"]["distance"]
# 1e-6: one float multiplication.
expect("wheel zooms", abs(ratio - 0.9) < 1e-6, f"distance x {ratio:.7f} (expected 0.9)")
expect("left drag leaves the light", s1["lights"][0] == s0["lights"][0], f"light {s0['lights'][0]} -> {s1['lights'][0]}")

# Ctrl + left drag 50 pixels down: the selected light moves down the camera's up vector by
# 50 px x distance x 0.002 m/px (down: the spot sits just under the ceiling; up would put it above).
xdo("keydown", "ctrl")
pause()
xdo("mousedown", "1")
pause()
xdo("mousemove", "--window", window, str(PANEL + 160), str(y + 50))
pause()
xdo("mouseup", "1")
xdo("keyup", "ctrl")
pause()
signal("go-light")
s2 = wait_for("in-light.json")
moved = [b - a for a, b in zip(s1["lights"][0], s2["lights"][0])]
distance = math.sqrt(sum(d * d for d in moved))
expected = 50 * s1["orbit"]["distance"] * 0.002
# Relative 1e-4: float sums of a few terms of the light's coordinates (about 0.5 m) and the move.
expect("ctrl + drag moves the light", abs(distance - expected) < 1e-4 * max(expected, 1e-3) + 1e-6 and moved[1] < 0,
       f"moved {distance:.6f} m (expected {expected:.6f}), dy {moved[1]:.6f}")
expect("ctrl + drag does not orbit", s2["orbit"]["yaw"] == s1["orbit"]["yaw"], f"yaw {s1['orbit']['yaw']} -> {s2['orbit']['yaw']}")

# Key taps (press and release at once, shorter than any frame): `.` three times, then `b`.
xdo("key", "period", "period", "period", "b")
pause()
signal("go-keys")
s3 = wait_for("in-keys.json")
expect("`.` steps the animation", s3["frame"] == s2["frame"] + 3, f"frame {s2['frame']} -> {s3['frame']} (expected +3)")
expect("`b` opens the A/B split", s3["ab"] == "split", f"ab {s2['ab']} -> {s3['ab']}")

# F12: the view as PNG (the view's size, 330x400, both halves of the split) and side A's radiance as
# EXR (the render size, 128x128).
xdo("key", "F12")
pause()
signal("go-shot")
wait_for("in-shot.json")
for f, size in (("bounce-0000.png", (WIDTH - PANEL, HEIGHT)), ("bounce-0000.exr", (128, 128))):
    if not os.path.exists(f):
        expect(f"F12 writes {f}", False, "missing")
        continue
    r = subprocess.run([check, "size", f, str(size[0]), str(size[1])], capture_output=True, text=True)
    expect(f"F12 {f} size", r.returncode == 0, r.stdout.strip() or r.stderr.strip())
    # Non-blank: the Cornell box's walls and light (0.02, as the lab test's screenshots).
    r = subprocess.run([check, "nonblank", f, "0.02"], capture_output=True, text=True)
    expect(f"F12 {f} non-blank", r.returncode == 0, r.stdout.strip() or r.stderr.strip())

# Space starts the animation.
xdo("key", "space")
pause()
signal("go-end")
s5 = wait_for("in-end.json")
expect("space plays", s5["playing"] is True, f"playing {s5['playing']}")

rc = viewer.wait(timeout=120)
expect("viewer exit", rc == 0, f"exit {rc}")
if failures:
    sys.exit(f"view_input: {len(failures)} checks failed: {', '.join(failures)}")
