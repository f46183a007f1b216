#!/usr/bin/env python3
# Light leaks of scene files (ctest study_leaks): a JSON scene that declares leak regions, swept (leak
# scores and masks like the built-in two-rooms), and `bounce compare --leak-scene` on the sweep's
# images agreeing with the sweep's own scores, and refusing a camera that sees no dark region.
#
# usage: leaks_test.py BOUNCE WORK
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_support import check, failures, load, runner, write_json  # noqa: E402

BOUNCE, WORK = sys.argv[1], sys.argv[2]
run = runner(BOUNCE)


def png_channels(path):
    # The leak masks (8-bit RGB or RGBA PNG, no interlace) decoded with zlib: red = dark, green = lit.
    with open(path, "rb") as f:
        data = f.read()
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6), (depth, colour)
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return [[(row[x * channels], row[x * channels + 1]) for x in range(width)] for row in rows]


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)

# ---- leak regions declared by a scene file ----
# A floor (x in [-2, 2]) crossed by a wall at x = -0.5 that is higher than the point light: the floor
# beyond it gets no light in truth. The dark box (x > -0.47) contains the origin on purpose: pixels
# where the camera sees no surface have G-buffer position 0 and must not count as dark.
obj = ["v -2 0 -1", "v 2 0 -1", "v 2 0 1", "v -2 0 1"]
for x in (-0.52, -0.48):
    for y in (0, 1):
        for z in (-1, 1):
            obj.append(f"v {x} {y} {z}")
obj += ["o floor", "f 1 4 3", "f 1 3 2", "o wall",
        "f 5 6 8", "f 5 8 7", "f 9 11 12", "f 9 12 10", "f 5 7 11", "f 5 11 9",
        "f 6 10 12", "f 6 12 8", "f 7 8 12", "f 7 12 11", "f 5 9 10", "f 5 10 6"]
with open(os.path.join(WORK, "rooms.obj"), "w") as f:
    f.write("\n".join(obj) + "\n")
scene = {
    "objects": [{"name": "rooms", "model": "rooms.obj", "material": {"baseColor": 0.7}}],
    "lights": [{"name": "bulb", "type": "point", "position": [-1.3, 0.6, 0], "intensity": 2}],
    "camera": {"position": [0, 5, 0.01], "target": [0, 0, 0], "up": [0, 0, -1], "fovDegrees": 60},
    "leakRegions": {"dark": {"min": [-0.47, -1, -2], "max": [3, 2, 2]}, "lit": {"min": [-3, -1, -2], "max": [-0.53, 2, 2]}},
}
write_json(os.path.join(WORK, "rooms.json"), scene)
leaks = {"name": "leaks", "size": "40x40", "scenes": [{"file": "rooms.json"}, "two-rooms"],
         "techniques": ["direct", {"name": "ambient", "settings": {"radiance": 0.1}}], "reference": {"spp": 4, "seed": 2}}
leaks_path = os.path.join(WORK, "leaks.json")
write_json(leaks_path, leaks)
leaks_out = os.path.join(WORK, "leaks-out")
r = run("sweep", leaks_path, "--out", leaks_out, "--jobs", "2")
check(r.returncode == 0, f"the leak study runs ({r.stderr.strip()[-300:]})")
render_direct = load(os.path.join(leaks_out, "render/rooms/direct/default/record.json"))
compare_direct = load(os.path.join(leaks_out, "compare/rooms/direct/default/record.json"))
compare_ambient = load(os.path.join(leaks_out, "compare/rooms/ambient/radiance-0.1/record.json"))
check("leak" in render_direct and "leak" in compare_direct, "a scene file's declared regions give leak scores")
mask = png_channels(os.path.join(leaks_out, "render/rooms/direct/default/leak-mask.png"))
dark = sum(1 for row in mask for px in row if px[0] > 127)
lit = sum(1 for row in mask for px in row if px[1] > 127)
background = sum(1 for x in (0, 39) for y in range(40) if mask[y][x] == (0, 0))
check(dark == render_direct["leak"]["darkPixels"] and lit == render_direct["leak"]["litPixels"] and dark > 100 and lit > 100,
      f"leak-mask.png holds the record's masks ({dark} dark, {lit} lit)")
# The floor spans x in [-2, 2] and the camera sees 2.9 m either side: the side columns are background.
check(background == 80, f"pixels without a surface are in neither mask although the dark box holds the origin ({background} of 80)")
# A point light's cube shadow map blocks the wall exactly here (the floor behind it lies far from the
# wall's shadow edge); the truth is 0 and the path tracer's reference is 0 too (nothing above the wall).
check(compare_direct["leak"]["test"] == 0 and compare_direct["leak"]["reference"] == 0, f"direct: no leak ({compare_direct['leak']})")
check(compare_ambient["leak"]["test"] > 0.05, f"ambient lights the dark side: a leak ({compare_ambient['leak']})")

# ---- bounce compare --leak-scene on the sweep's images ----
def compare_leak(scene_arg, render_id, reference_id, *extra):
    r = run("compare", os.path.join(leaks_out, render_id, "full.exr"), os.path.join(leaks_out, reference_id, "image.exr"),
            "--json", "--leak-scene", scene_arg, *extra)
    return r, (json.loads(r.stdout) if r.returncode == 0 else None)


r, c = compare_leak(os.path.join(WORK, "rooms.json"), "render/rooms/ambient/radiance-0.1", "reference/rooms/all/f0000")
check(r.returncode == 0 and "leak" in c, f"compare --leak-scene FILE ({r.stderr.strip()})")
if c:
    sweep_full = load(os.path.join(leaks_out, "render/rooms/ambient/radiance-0.1/record.json"))["leak"]["full"]
    # Ray-cast masks against the rasteriser's: the same pixel centres, so the same pixels but for
    # pixels whose centre lies on an edge; at most 1 % of either mask may differ.
    check(abs(c["leak"]["darkPixels"] - dark) <= 0.01 * dark and abs(c["leak"]["litPixels"] - lit) <= 0.01 * lit,
          f"its masks are the sweep's ({c['leak']['darkPixels']}/{dark} dark, {c['leak']['litPixels']}/{lit} lit)")
    check(abs(c["leak"]["test"] - sweep_full) <= 0.01 * sweep_full, f"and so is the score ({c['leak']['test']} vs {sweep_full})")
r, c = compare_leak("two-rooms", "render/two-rooms/ambient/radiance-0.1", "reference/two-rooms/all/f0000")
check(r.returncode == 0 and c["leak"]["test"] > 0.05 and c["leak"]["reference"] < 0.01,
      f"compare --leak-scene two-rooms: the ambient leak, a reference near 0 ({c and c['leak']})")
r = run("compare", os.path.join(leaks_out, "render/two-rooms/direct/default/full.exr"),
        os.path.join(leaks_out, "reference/two-rooms/b0/f0000/image.exr"), "--leak-scene", "two-rooms")
check(r.returncode == 0 and "leak       0 " in r.stdout, f"the console line ({r.stdout.strip().splitlines()[-1:]})")
# The camera sees no dark region: an error naming it, exit 1, no heat map.
heat = os.path.join(WORK, "heat.png")
away = dict(scene, camera={"position": [-1.5, 5, 0.01], "target": [-1.5, 0, 0], "up": [0, 0, -1], "fovDegrees": 10})
write_json(os.path.join(WORK, "away.json"), away)
r = run("compare", os.path.join(leaks_out, "render/rooms/direct/default/full.exr"),
        os.path.join(leaks_out, "reference/rooms/b0/f0000/image.exr"), "--leak-scene", os.path.join(WORK, "away.json"),
        "--heatmap", heat)
check(r.returncode == 1 and len(r.stderr.strip().splitlines()) == 1 and "sees 0 pixels of the dark region" in r.stderr
      and not os.path.exists(heat), f"a camera that sees no dark region: one-line error, no heat map ({r.stderr.strip()})")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
