#!/usr/bin/env python3
"""Near-field bound of Eq. 5.2 (area-light, Nichols 2010 ch. 5): how a 16 x 16 VPL sum over a uniform
square light compares with the exact polygon irradiance on a parallel plane at heights down to a
fraction of a VPL cell, for three per-VPL terms:
  point  A cos_x cos_y / r^2                  (Eq. 5.2 as written)
  disk   A cos_x cos_y / (r^2 + A / pi)       (radiosity's disk form, pi A / (pi r^2 + A) on axis)
  clamp  A cos_x cos_y / max(r^2, A / pi)     (area-light: the point form, bounded by a full hemisphere)
Receivers: a grid over the light's footprint and 25 % beyond it (offset from the VPL grid). Per height:
the sum's energy over the exact one, the largest pixel ratio and the relMSE (bounce's epsilon 0.01 on
radiances of order 1). No renderer: the exact irradiance is Lambert's contour formula.

Usage: bench/area_light/nearfield.py [BOUNCE]  (BOUNCE, for the record's envelope, defaults to
build/src/app/bounce; needs numpy). Writes bench/results/area-light-nearfield-<date>.json.
"""
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from record import new_record, write_record  # noqa: E402

SIDE = 1.0           # m, the square light
VPLS_PER_SIDE = 16   # the thesis's 256 VPLs
RADIANCE = 1.0
HEIGHTS_IN_CELLS = [0.08, 0.32, 0.5, 0.8, 1.1, 1.6, 2.4, 3.2, 4.8]
RECEIVERS = 61       # per axis over 1.5 sides (the footprint and 25 % beyond each edge)


def exact_irradiance(px, pz, h):
    """Lambert's contour formula for the square at height h above (px, 0, pz), facing down."""
    half = 0.5 * SIDE
    corners = [(-half, -half), (half, -half), (half, half), (-half, half)]
    v = [np.array([cx - px, h, cz - pz]) for cx, cz in corners]
    total = 0.0
    for i in range(4):
        a, b = v[i] / np.linalg.norm(v[i]), v[(i + 1) % 4] / np.linalg.norm(v[(i + 1) % 4])
        g = np.cross(a, b)
        total += np.arccos(np.clip(a @ b, -1.0, 1.0)) * g[1] / np.linalg.norm(g)
    return RADIANCE * 0.5 * abs(total)


def main():
    bounce = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/src/app/bounce"))
    n = VPLS_PER_SIDE
    cell = SIDE / n
    area = cell * cell
    centres = (np.arange(n) + 0.5) * cell - 0.5 * SIDE
    vx, vz = np.meshgrid(centres, centres)
    # Receivers offset by a third of a cell from the VPL grid, so that none sits exactly under a VPL.
    xs = np.linspace(-0.75 * SIDE, 0.75 * SIDE, RECEIVERS) + cell / 3.0
    forms = {
        "point": lambda r2: r2,
        "disk": lambda r2: r2 + area / np.pi,
        "clamp": lambda r2: np.maximum(r2, area / np.pi),
    }
    rows = []
    for hc in HEIGHTS_IN_CELLS:
        h = hc * cell
        exact, sums = [], {k: [] for k in forms}
        for px in xs:
            for pz in xs:
                dx, dz = vx - px, vz - pz
                r2 = dx * dx + dz * dz + h * h
                cos2 = h * h / r2  # cos_x cos_y: parallel planes
                for k, f in forms.items():
                    sums[k].append(RADIANCE * float((area * cos2 / f(r2)).sum()))
                exact.append(exact_irradiance(px, pz, h))
        e = np.array(exact)
        row = {"heightInCells": hc, "height_m": h}
        for k, s in sums.items():
            s = np.array(s)
            # relMSE on the receivers' radiance (albedo 1: E / pi), bounce's epsilon 0.01.
            rel = float(np.mean((s / np.pi - e / np.pi) ** 2 / ((e / np.pi) ** 2 + 0.01)))
            row[k] = {"energy": float(s.sum() / e.sum()), "maxRatio": float((s / np.maximum(e, 1e-9)).max()), "relMse": rel}
        rows.append(row)
        print(f"h = {hc:4.2f} cells: " + "  ".join(f"{k} energy {row[k]['energy']:.3f} max {row[k]['maxRatio']:.2f} relMSE {row[k]['relMse']:.4f}" for k in forms))
    record = new_record("area-light-nearfield", " ".join(["bench/area_light/nearfield.py"] + sys.argv[1:]), bounce)
    record.update({"lightSide_m": SIDE, "vplsPerSide": n, "receiversPerAxis": RECEIVERS, "rows": rows})
    print(write_record(record))


if __name__ == "__main__":
    main()
