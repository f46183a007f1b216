#!/usr/bin/env python3
"""Generates the README's tables from the raw benchmark records under bench/results/.

Usage: bench/tables.py [--check]
Replaces the text between `<!-- bench:NAME -->` and `<!-- /bench:NAME -->` in README.md with the
table built from the newest bench/results/NAME-*.json. --check exits 1 when README.md is stale.
Every number in those sections therefore has its raw record (command, commit, date, machine).
"""
import glob
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def newest(name):
    files = sorted(glob.glob(os.path.join(ROOT, "bench/results", f"{name}-*.json")))
    if not files:
        return None, None
    with open(files[-1]) as f:
        return json.load(f), os.path.relpath(files[-1], ROOT)


def med(s):
    return s["median"]


def rng(s):
    return f"{s['median']:.1f} ({s['min']:.1f}–{s['max']:.1f})"


def vct_table(rec, path):
    r = rec["results"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`, {rec['reps']} interleaved repetitions of {rec['frames']} frames, median (min–max) "
             "of the per-run medians; llvmpipe times are indicative, the ratios are the result.", ""]
    lines += ["Voxelization (binary, 6-separating, as thesis Table 4.1), ms:", "",
              "| scene @ N³ | triangles | triangle-parallel | fragment-parallel | hybrid (pass 1 / pass 2 triangles) | hybrid vs better single | thesis |",
              "|---|---|---|---|---|---|---|"]
    for key, e in r["voxelizers"].items():
        t, f, h = med(e["triangle"]["voxelize_ms"]), med(e["fragment"]["voxelize_ms"]), med(e["hybrid"]["voxelize_ms"])
        best = min(t, f)
        lines.append(f"| `{key}` | {e['triangles']} | {rng(e['triangle']['voxelize_ms'])} | {rng(e['fragment']['voxelize_ms'])} | "
                     f"{rng(e['hybrid']['voxelize_ms'])} ({int(e['hybrid']['trianglesPass1'])} / {int(e['hybrid']['trianglesPass2'])}) | "
                     f"{best / h:.2f}× | R4: 1.5–9.6× on mixed scenes |")
    lines += ["", "Storage formats on `cornell-box`, 64³, 256² image, ms (R8, R11, R12, R14):", "",
              "| storage / diffuse tracer | bytes/voxel (R8) | frame | voxelize | post | mipmap | diffuse+AO | specular |",
              "|---|---|---|---|---|---|---|---|"]
    for label, e in r["storages"].items():
        lines.append(f"| `{label}` | {e['bytesPerVoxel']:.0f} | {rng(e['frame_ms'])} | {rng(e['voxelize_ms'])} | {rng(e['post_ms'])} | "
                     f"{rng(e['mipmap_ms'])} | {rng(e['diffuse_ao_ms'])} | {rng(e['specular_ms'])} |")
    st = r["storages"]
    sh_gen, sh_spec = med(st["sh-f32/generic"]["diffuse_ao_ms"]), med(st["sh-f32/specialised"]["diffuse_ao_ms"])
    lines += ["", f"R12 specialised 60° tracer vs generic, SH-F32 diffuse+AO: {sh_gen / sh_spec:.2f}× (thesis > 1.5×).", ""]
    lines += ["Mipmapping over N (`cornell-box`, 128² image), ms (R11: SH mip below half the aniso mip):", "",
              "| N³ | aniso | sh-f32 | sh-u8 | sh-f32 / aniso |", "|---|---|---|---|---|"]
    for res, e in r["mipmap"].items():
        a, s, u = med(e["aniso"]["mipmap_ms"]), med(e["sh-f32"]["mipmap_ms"]), med(e["sh-u8"]["mipmap_ms"])
        lines.append(f"| {res} | {rng(e['aniso']['mipmap_ms'])} | {rng(e['sh-f32']['mipmap_ms'])} | {rng(e['sh-u8']['mipmap_ms'])} | {s / a:.2f} |")
    if "cutoff" in r:
        lines += ["", "Hybrid voxelization time over the cutoff (`atrium`, 100K triangles, 128³; thesis Figs. 4.16/4.17: a broad basin, optimum a few voxels²):", "",
                  "| cutoff (voxels²) | triangles in pass 2 | voxelize ms | pass 1 | pass 2 |", "|---|---|---|---|---|"]
        for c, e in r["cutoff"].items():
            lines.append(f"| {c} | {int(e['trianglesPass2'])} | {rng(e['voxelize_ms'])} | {rng(e['pass1_ms'])} | {rng(e['pass2_ms'])} |")
    if "shadowCone" in r:
        lines += ["", "Shadow cone (Eq. 6.3) time over aperture, `cornell-box`, 256², 64³ (R13: falls as the aperture grows): " +
                  ", ".join(f"{a}° {rng(e['shadow_ms'])} ms" for a, e in r["shadowCone"].items()) + "."]
    if "lightLeak" in r:
        lines += ["", f"`two-rooms` light-leak score (dark-room / lit-room mean luminance, 0 = no leak; `{r['lightLeakCommand']}`): " +
                  ", ".join(f"`{k}` {v:.4f}" for k, v in r["lightLeak"].items()) + "."]
    lines += ["", f"Indirect light vs `{r['quality_reference']}`, 128², relMSE / LDR-FLIP:", ""]
    scenes = list(r["quality"].keys())
    lines += ["| technique | " + " | ".join(f"`{s}`" for s in scenes) + " |", "|---|" + "---|" * len(scenes)]
    for label in r["quality"][scenes[0]].keys():
        cells = [f"{r['quality'][s][label]['relMse']:.3f} / {r['quality'][s][label]['flipLdr']:.3f}" for s in scenes]
        lines.append(f"| `{label}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)


GENERATORS = {"vct": vct_table}


def main():
    readme_path = os.path.join(ROOT, "README.md")
    with open(readme_path) as f:
        readme = f.read()
    updated = readme
    for name, gen in GENERATORS.items():
        rec, path = newest(name)
        if rec is None:
            continue
        body = gen(rec, path)
        pattern = re.compile(rf"(<!-- bench:{name} -->\n)(?:.*?\n)?(<!-- /bench:{name} -->)", re.S)
        updated = pattern.sub(lambda m: m.group(1) + body + "\n" + m.group(2), updated)
    if "--check" in sys.argv:
        sys.exit(0 if updated == readme else 1)
    with open(readme_path + ".tmp", "w") as f:
        f.write(updated)
    os.replace(readme_path + ".tmp", readme_path)


if __name__ == "__main__":
    main()
