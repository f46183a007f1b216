#!/usr/bin/env python3
"""Independent SSIM of an 8-bit PNG pair, straight from Wang, Bovik, Sheikh & Simoncelli, "Image Quality
Assessment: From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004, Sec. III-B/C:

  * an 11x11 circular-symmetric Gaussian weighting window w, standard deviation 1.5 samples,
    normalised to unit sum (eq. 14-16 use it for the local statistics);
  * mu_x = sum w_i x_i, sigma_x^2 = sum w_i (x_i - mu_x)^2, sigma_xy = sum w_i (x_i - mu_x)(y_i - mu_y);
  * SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2)),
    C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1 (pixel values are the stored 8-bit values / 255);
  * the map covers the windows lying wholly inside the image, and the mean SSIM is its average.

Each of R, G and B is evaluated on its own and the three maps are averaged, as bounce does
(docs/metrics.md). Double precision, Python standard library only (a PNG reader for 8-bit RGB without
interlace is included). The statistics are computed directly from their definitions, not with the
E[x^2] - mu^2 shortcut or separable filtering that bounce uses.

Usage: ssim_reference.py test.png reference.png  ->  prints the mean and the map (rows of the valid region).
"""
import math
import struct
import sys
import zlib


def read_png_rgb8(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 2 and interlace == 0, "8-bit RGB, no interlace only"
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = 3 * w
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, [[[rows[y][3 * x + k] / 255.0 for x in range(w)] for y in range(h)] for k in range(3)]


def ssim_map(x, y, w, h, sigma=1.5, radius=5):
    g = [[math.exp(-(i * i + j * j) / (2 * sigma * sigma)) for i in range(-radius, radius + 1)]
         for j in range(-radius, radius + 1)]
    total = sum(sum(r) for r in g)
    g = [[v / total for v in r] for r in g]
    c1, c2 = (0.01 * 1.0) ** 2, (0.03 * 1.0) ** 2
    out = []
    for cy in range(radius, h - radius):
        row = []
        for cx in range(radius, w - radius):
            win = [(g[j][i], x[cy + j - radius][cx + i - radius], y[cy + j - radius][cx + i - radius])
                   for j in range(2 * radius + 1) for i in range(2 * radius + 1)]
            mx = sum(wt * a for wt, a, _ in win)
            my = sum(wt * b for wt, _, b in win)
            vx = sum(wt * (a - mx) ** 2 for wt, a, _ in win)
            vy = sum(wt * (b - my) ** 2 for wt, _, b in win)
            cov = sum(wt * (a - mx) * (b - my) for wt, a, b in win)
            row.append((2 * mx * my + c1) * (2 * cov + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2)))
        out.append(row)
    return out


def main():
    w, h, test = read_png_rgb8(sys.argv[1])
    w2, h2, ref = read_png_rgb8(sys.argv[2])
    assert (w, h) == (w2, h2)
    maps = [ssim_map(test[k], ref[k], w, h) for k in range(3)]
    rows = [[sum(maps[k][r][c] for k in range(3)) / 3 for c in range(len(maps[0][0]))] for r in range(len(maps[0]))]
    mean = sum(sum(r) for r in rows) / (len(rows) * len(rows[0]))
    print(f"# valid region: x, y in [5, {w - 6}] (windows wholly inside the {w}x{h} image)")
    print(f"# mean {mean:.12g}")
    for r in rows:
        print(" ".join(f"{v:.12g}" for v in r))


if __name__ == "__main__":
    main()
