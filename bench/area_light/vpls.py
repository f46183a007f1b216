#!/usr/bin/env python3
"""256 vs 16,384 VPLs of `area-light` (Nichols 2010 Figs. 5.14 and 5.15), through the CLI's run records.

Usage: bench/area_light/vpls.py [BOUNCE] [--size N]   (BOUNCE defaults to build/src/app/bounce, N to 256)

The thesis (sec. 5.4.7): 16^2 to 128^2 VPLs on an ordinary video show "no perceptible difference"
(Fig. 5.14), but a white square bouncing on a black screen is undersampled by the fixed 16 x 16 grid
(Fig. 5.15). Both sides render with the same brute-force voxel visibility (every VPL tested at every
pixel), so the only difference is the light's sampling: the 256-VPL image (vplsPerSide 16) is compared
with the 16,384-VPL one (vplsPerSide 128, the converged sampling) on
  cornell-box-area              an untextured light (diffuse reference case),
  area-screen                   the colour-bar video (Fig. 5.14's ordinary content),
  area-screen square 0.25       a bouncing square spanning 4 x 4 VPL cells,
  area-screen square 0.0625     a bouncing square of one VPL cell (Fig. 5.15's pathological case).
An earlier run of this row in bench/area_light/run.py used V = 1 and only the 0.25 square, which hides
the artefacts (they are in the shadows: a square covered by one to four VPLs casts one to four hard
shadows). The raw record goes to bench/results/area-light-vpls-<date>.json; bench/tables.py puts it in
the README's area-light section.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import run  # noqa: E402  (the area-light benchmark's helpers: render, compare, gpu, summary)
from record import new_record, write_record  # noqa: E402  (run put bench/ on the path)

CASES = {
    "cornell-box-area": {"scene": "cornell-box-area", "params": []},
    "area-screen bars": {"scene": "area-screen", "params": []},
    "area-screen square 0.25": {"scene": "area-screen", "params": ["pattern=square", "squareSize=0.25"]},
    "area-screen square 0.0625": {"scene": "area-screen", "params": ["pattern=square", "squareSize=0.0625"]},
}
SIDES = [16, 128]  # vplsPerSide: 256 and 16,384 VPLs


def main():
    args = list(sys.argv[1:])
    size = 256
    if "--size" in args:
        size = int(args[args.index("--size") + 1])
        del args[args.index("--size"):args.index("--size") + 2]
    bounce = os.path.abspath(args[0] if args else os.path.join(run.ROOT, "build/src/app/bounce"))
    rec = new_record("area-light-vpls", f"bench/area_light/vpls.py --size {size}", bounce)
    rec["size"] = size
    rec["frames"] = run.FRAMES
    rec["visibility"] = "brute"
    import tempfile
    cases = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, case in CASES.items():
            entry, outs = {}, {}
            for side in SIDES:
                outs[side] = os.path.join(tmp, f"{side}.exr")
                r, c = run.render(bounce, case, size, {"vplsPerSide": str(side), "visibility": "brute"}, outs[side])
                entry[str(side * side)] = {"command": c, "frameMs": run.summary(run.gpu(r, "area-light"))}
            entry["256vs16384"] = run.compare(bounce, outs[16], outs[128])
            cases[name] = entry
            print(name, {k: round(v, 5) for k, v in entry["256vs16384"].items()}, flush=True)
    rec["cases"] = cases
    print(write_record(rec))


if __name__ == "__main__":
    main()
