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
    # NAME-YYYY-MM-DD.json only (not NAME-tests-..., a different record kind).
    files = sorted(f for f in glob.glob(os.path.join(ROOT, "bench/results", f"{name}-*.json"))
                   if re.fullmatch(rf"{re.escape(name)}-\d{{4}}-\d{{2}}-\d{{2}}\.json", os.path.basename(f)))
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
    if "r9" in r:
        lines += ["", "R9 (Fig. 5.4) — voxelization per format and level-0 write mode, fragment-parallel voxelizer, 128³, ms "
                  "(thesis: iso max cheapest, the CAS average costly under contention, SH-U8 about iso's cost):", "",
                  "| scene | " + " | ".join(f"`{k}`" for k in next(iter(r["r9"].values())).keys()) + " | average / max (iso) |",
                  "|---|" + "---|" * (len(next(iter(r["r9"].values()))) + 1)]
        for scene, e in r["r9"].items():
            lines.append(f"| `{scene}` | " + " | ".join(rng(v["voxelize_ms"]) for v in e.values()) +
                         f" | {med(e['iso/average']['voxelize_ms']) / med(e['iso/max']['voxelize_ms']):.2f}× |")
    if "r10" in r:
        lines += ["", "R10 (Fig. 5.11) — voxelize + post-voxelize + mipmap with active-voxel lists (sparse) and without "
                  "(dense), 128³, ms (thesis: the lists win for every format but iso):", "",
                  "| scene | format | sparse | dense | dense / sparse |", "|---|---|---|---|---|"]
        for scene, e in r["r10"].items():
            for st in ("iso", "aniso", "sh-f32", "sh-u8"):
                sp, de = e[f"{st}/sparse"]["total_ms"], e[f"{st}/dense"]["total_ms"]
                lines.append(f"| `{scene}` | `{st}` | {rng(sp)} | {rng(de)} | {med(de) / med(sp):.2f}× |")
    if "cutoff" in r:
        lines += ["", "Hybrid voxelization time over the cutoff (`atrium`, 100K triangles, 128³; thesis Figs. 4.16/4.17: a broad basin, optimum a few voxels²):", "",
                  "| cutoff (voxels²) | triangles in pass 2 | voxelize ms | pass 1 | pass 2 |", "|---|---|---|---|---|"]
        for c, e in r["cutoff"].items():
            lines.append(f"| {c} | {int(e['trianglesPass2'])} | {rng(e['voxelize_ms'])} | {rng(e['pass1_ms'])} | {rng(e['pass2_ms'])} |")
    if "shadowCone" in r:
        lines += ["", "Shadow cone (Eq. 6.3) time over aperture, `cornell-box`, 256², 64³ (R13: falls as the aperture grows): " +
                  ", ".join(f"{a}° {rng(e['shadow_ms'])} ms" for a, e in r["shadowCone"].items()) + "."]
    if "lightLeak" in r:
        lines += ["", f"`two-rooms` light-leak score (dark-room / lit-room mean luminance, 0 = no leak; vct per storage@N, photon-splat at 1x and 3x bundle width, rsm without visibility; `{r['lightLeakCommand']}`): " +
                  ", ".join(f"`{k}` {v:.4f}" for k, v in r["lightLeak"].items()) + "."]
    lines += ["", f"Indirect light vs `{r['quality_reference']}`, 128², relMSE / LDR-FLIP:", ""]
    scenes = list(r["quality"].keys())
    lines += ["| technique | " + " | ".join(f"`{s}`" for s in scenes) + " |", "|---|" + "---|" * len(scenes)]
    for label in r["quality"][scenes[0]].keys():
        cells = [f"{r['quality'][s][label]['relMse']:.3f} / {r['quality'][s][label]['flipLdr']:.3f}" for s in scenes]
        lines.append(f"| `{label}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def photon_splat_table(rec, path):
    r = rec["results"]
    med_of = lambda rows, key: sorted(x[key] for x in rows)[len(rows) // 2]
    q = lambda rows, key: med_of([x["vsReference"] for x in rows], key)
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); `{rec['command']}`, "
             f"{rec['size']} images, interleaved repetitions, medians; errors against `bounce reference --bounces 1 --indirect-only` "
             "(energy = image mean / reference mean, relMSE, LDR-FLIP, the document's RMS on 8-bit values summed over R, G, B); "
             "photon-splat at its defaults (flux estimate, 2h = diagonal / 20, blur 5) but for the photons and bundle width; "
             "overlap = bundles per pixel over the pixels some bundle reached, median of the frames' means (largest). "
             "llvmpipe times are indicative.", ""]
    for scene, e in r.items():
        if not isinstance(e, dict) or "splat" not in e:
            continue
        hq = e["photonMapHq"]
        hq_cmd = re.sub(r" --(out|stats) \S+", "", hq["command"])
        lines += [f"`{scene}` — high-quality photon map (`{hq_cmd}`): {hq['render_ms']:.0f} ms, "
                  f"relMSE {hq['vsReference']['relMse']:.4f}, energy {hq['vsReference']['energy']:.3f}, RMS {hq['vsReference']['rmsSum8']:.1f}.", "",
                  "| method | photons | frame / render ms | energy | relMSE | FLIP | RMS (8-bit, Σ RGB) | RMS vs HQ photon map | overlap (M6) |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for label, rows in e["splat"].items():
            size, n = label.split("/")
            lines.append(f"| photon-splat, {'default bundles' if size == 'small' else '3x wider bundles'} | {n} | "
                         f"{med_of(rows, 'frame_ms'):.0f} (+{med_of(rows, 'cpu_ms'):.0f} CPU) | {q(rows, 'energy'):.3f} | {q(rows, 'relMse'):.4f} | "
                         f"{q(rows, 'flipLdr'):.3f} | {q(rows, 'rmsSum8'):.1f} | {med_of([x['vsPhotonMapHq'] for x in rows], 'rmsSum8'):.1f} | "
                         f"{med_of(rows, 'overlapMean'):.0f} ({med_of(rows, 'overlapMax'):.0f}) |")
        for label, rows in e["stratified"].items():
            g, n = label.split("/")
            lines.append(f"| photon-splat, stratified {g}³, 3x wider bundles (Graph 4) | {n} → {med_of(rows, 'photonsStratified'):.0f} | "
                         f"{med_of(rows, 'frame_ms'):.0f} (+{med_of(rows, 'cpu_ms'):.0f} CPU) | {q(rows, 'energy'):.3f} | {q(rows, 'relMse'):.4f} | "
                         f"{q(rows, 'flipLdr'):.3f} | {q(rows, 'rmsSum8'):.1f} | {med_of([x['vsPhotonMapHq'] for x in rows], 'rmsSum8'):.1f} | "
                         f"{med_of(rows, 'overlapMean'):.0f} ({med_of(rows, 'overlapMax'):.0f}) |")
        for label, rows in e["photonMap"].items():
            n, k = label.split("/")
            lines.append(f"| photon-map, {k} | {n} | {med_of(rows, 'render_ms'):.0f} | {q(rows, 'energy'):.3f} | {q(rows, 'relMse'):.4f} | "
                         f"{q(rows, 'flipLdr'):.3f} | {q(rows, 'rmsSum8'):.1f} | — | — |")
        m5 = e["mapResolution"]
        lines += ["", f"M5 depth maps 4² vs 32² (16384 photons): depth-maps (GPU, and the CPU's trace on llvmpipe) {med_of(m5['4'], 'depth_maps_ms'):.0f} vs "
                  f"{med_of(m5['32'], 'depth_maps_ms'):.0f} ms, splat {med_of(m5['4'], 'splat_ms'):.0f} vs {med_of(m5['32'], 'splat_ms'):.0f} ms, "
                  f"frame {med_of(m5['4'], 'frame_ms'):.0f} vs {med_of(m5['32'], 'frame_ms'):.0f} ms, relMSE {q(m5['4'], 'relMse'):.4f} vs "
                  f"{q(m5['32'], 'relMse'):.4f} (document, 5.3.1: \"Since we are dealing with thousands of light sources, even a slight "
                  "increase in resolution causes a large impact on the rendering times.\").", ""]
        sb = e["stepBack"]
        lines += [f"Step back (defaults): b = d (bounce) energy {sb['d']['vsReference']['energy']:.3f}, relMSE {sb['d']['vsReference']['relMse']:.4f}; "
                  f"b = h/4 (the document's \"small\" b) energy {sb['h/4']['vsReference']['energy']:.3f}, relMSE {sb['h/4']['vsReference']['relMse']:.4f}.", ""]
    if "bias" in r:
        lines += ["Remaining bias of the flux estimate (energy, mean of seeds, 32768 photons, no blur) over the bundle width 2h: " +
                  "; ".join(f"`{scene}` " + ", ".join(f"2h x {f}: {sum(x['energy'] for x in v) / len(v):.3f}"
                                                      for f, v in widths.items()) for scene, widths in r["bias"].items()) + ".", ""]
    if "memory" in r:
        m = r["memory"]
        lines += ["M1 memory (counters: what is allocated): " + f"{m['photonBytesPerPhoton']:.1f} B per stored photon (48-byte Photon, "
                  "the list's capacity; Table 1: 36 B); stratification grid " +
                  ", ".join(f"{g}³ {v['gridBytes'] / 1e3:.0f} KB" for g, v in m["gridBytes"].items()) +
                  " (one 16-byte entry per photon at any resolution; the document's dense grid: 576 MB at 256³)."]
    return "\n".join(lines)


RAD_METHODS = ["radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"]
RAD_SCENES = ["indirect-light", "cornell-large", "cornell-small", "low-quality"]
RAD_SCENE_TITLES = {"indirect-light": "Indirect light", "cornell-large": "Cornell, large", "cornell-small": "Cornell, small",
                    "low-quality": "Low quality"}


def radiosity_table(rec, path):
    sp, q = rec["speed"], rec["quality"]
    scenes = [s for s in RAD_SCENES if s in sp]
    idx = {s: RAD_SCENES.index(s) for s in scenes}
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`, {rec['size']}² images, methods interleaved, {rec['reps']} repetitions; frame time = the "
             "technique's GPU scope, median (min–max) over the frames after the first. Thesis: GTX 670, Table 5.2a. "
             "llvmpipe times are indicative; the orders and ratios are the result.", "",
             "R2 — frame time, ms (thesis ms in brackets), and hemicubes per frame:", "",
             "| method | " + " | ".join(RAD_SCENE_TITLES[s] for s in scenes) + " |", "|---|" + "---|" * len(scenes)]
    for m in RAD_METHODS:
        cells = [f"{rng(sp[s][m]['frameMs'])} [{rec['thesisMs'][m][idx[s]]}], {sp[s][m]['hemicubes']:.0f} hc" for s in scenes]
        lines.append(f"| `{m}` | " + " | ".join(cells) + " |")
    thesis_ratio = {s: rec["thesisMs"]["radiosity-pr"][idx[s]] / rec["thesisMs"]["radiosity-cross"][idx[s]] for s in scenes}
    lines.append("| cross over PR | " + " | ".join(
        f"{sp[s]['crossOverPr']:.2f}× (per rep {min(sp[s]['crossOverPrPerRep']):.2f}–{max(sp[s]['crossOverPrPerRep']):.2f}) [{thesis_ratio[s]:.1f}×]"
        for s in scenes) + " |")
    lines.append("| elements (static + moving, cross's moving) | " + " | ".join(
        f"{sp[s]['radiosity-pr']['elements']:.0f}, {sp[s]['radiosity-cross']['movingElements']:.0f}" for s in scenes) + " |")
    r1 = rec["r1"]
    sizes = list(r1["radiosity-cross"].keys())
    lines += ["", "R1 — `cornell-large`, moving patches fixed, static elements growing (`elementSize` " + ", ".join(sizes) + " m):", "",
              "| method | " + " | ".join(f"{r1['radiosity-cross'][z]['staticElements']:.0f} static" for z in sizes) + " | last / first |",
              "|---|" + "---|" * (len(sizes) + 1)]
    for m in ["radiosity-cross", "radiosity-incremental"]:
        d = r1[m]
        lines.append(f"| `{m}` | " + " | ".join(f"{rng(d[z]['frameMs'])} ms, {d[z]['hemicubes']:.0f} hc" for z in sizes) +
                     f" | {med(d[sizes[-1]]['frameMs']) / med(d[sizes[0]]['frameMs']):.2f}× |")
    lines += ["", "R8 — cross redistribution per moving patch (GPU scopes / patches; thesis: cross projection 0.172 ms, "
              "a hemicube 0.023–0.058 ms):", "", "| scene | patches | cross projection ms/patch | hemicubes ms/patch | ms/hemicube | gather hemicubes/s |",
              "|---|---|---|---|---|---|"]
    for s in scenes:
        r8 = sp[s]["r8"]
        hps = sp[s].get("gatherHemicubesPerSecond")
        lines.append(f"| {RAD_SCENE_TITLES[s]} | {r8['patches']:.0f} | {r8['crossProjectionMsPerPatch']:.3f} | {r8['hemicubeMsPerPatch']:.3f} | "
                     f"{r8['hemicubeMsPerHemicube']:.3f} | {hps:.0f} |" if hps else f"| {RAD_SCENE_TITLES[s]} | {r8['patches']:.0f} | "
                     f"{r8['crossProjectionMsPerPatch']:.3f} | {r8['hemicubeMsPerPatch']:.3f} | {r8['hemicubeMsPerHemicube']:.3f} | – |")
    qs = [s for s in scenes if s in q]
    lines += ["", "Table 5.1 — frame 12, NRMSE (RMS difference of the ACES display values / the reference's display range). "
              "First against `radiosity-gather` at high settings (`hemicubeSize=128`, 16–32 sweeps), the thesis's own metric, "
              "with the thesis's NRMSE against its high-quality gather in brackets; then against the path tracer (every bounce, "
              "Lambert) with its relMSE:", "",
              "| method | " + " | ".join(RAD_SCENE_TITLES[s] for s in qs) + " |", "|---|" + "---|" * len(qs)]
    for m in RAD_METHODS:
        lines.append(f"| `{m}` | " + " | ".join(
            f"vs gather-high {q[s][m]['vsGatherHigh']['nrmse']:.4f} [{rec['thesisNrmse'][m][idx[s]]:.4f}]; "
            f"vs path tracer {q[s][m]['vsReference']['nrmse']:.4f}, relMSE {q[s][m]['vsReference']['relMse']:.4f}" for s in qs) + " |")
    if all("crossOverPrNrmseVsGatherHigh" in q[s] for s in qs):
        th = {s: rec["thesisNrmse"]["radiosity-cross"][idx[s]] / rec["thesisNrmse"]["radiosity-pr"][idx[s]] for s in qs}
        lines.append("| cross / PR NRMSE | " + " | ".join(
            f"vs gather-high {q[s]['crossOverPrNrmseVsGatherHigh']:.2f}× [{th[s]:.2f}×]; vs path tracer {q[s]['crossOverPrNrmseVsReference']:.2f}×"
            for s in qs) + " |")
    lines.append("| gather-high | " + " | ".join(f"{q[s]['gatherHighVsReference']['nrmse']:.4f}; relMSE {q[s]['gatherHighVsReference']['relMse']:.4f}" for s in qs) + " |")
    lines.append("| reference noise (seed 1 vs 0) | " + " | ".join(f"{q[s]['referenceNoise']['nrmse']:.4f}; relMSE {q[s]['referenceNoise']['relMse']:.4f}" for s in qs) + " |")
    return "\n".join(lines)


def area_light_table(rec, path):
    fr, inc, vox, thr = rec["fractions"], rec["incremental"], rec["voxels"], rec["threshold"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`; `cornell-box-area` unless named; frame time = the technique's GPU scope, median "
             "(min–max) over the frames after the first; llvmpipe times are indicative, counts and ratios are the result.", "",
             f"R8 — cells rendered per level at {fr['size']}² (thesis: ~50 % of the 64² fragments, 10–15 % of the 1024² pixels); "
             f"partially visible VPLs per 3×3 neighbourhood {100 * fr['partiallyVisibleFraction']:.1f} % (thesis < 5 %):", "",
             "| level | " + " | ".join(v["cells"] for v in fr["levels"].values()) + " |",
             "|---|" + "---|" * len(fr["levels"]),
             "| rendered | " + " | ".join(f"{100 * v['renderedFraction']:.1f} % ({v['fragments']:.0f})" for v in fr["levels"].values()) + " |", ""]
    i, b = inc["incremental"], inc["brute"]
    sp = inc["gatherSpeedupPerRep"]
    lines += [f"Incremental vs brute-force visibility at {inc['size']}², interleaved, {rec['reps']} repetitions:", "",
              "| visibility | rays cast | rays reused | gather ms | frame ms |", "|---|---|---|---|---|",
              f"| incremental | {i['raysCast']:.0f} | {i['raysReused']:.0f} | {rng(i['gatherMs'])} | {rng(i['frameMs'])} |",
              f"| brute force | {b['raysCast']:.0f} | {b['raysReused']:.0f} | {rng(b['gatherMs'])} | {rng(b['frameMs'])} |",
              f"| ratio | {inc['raysCastRatio']:.2f} | | brute / incremental {min(sp):.2f}–{max(sp):.2f} per rep | |", ""]
    cols = [k for k in vox if k.isdigit()]
    lines += [f"Voxel grids at {vox['size']}² against `bounce reference --bounces 0` (thesis: 128²×128 \"almost indistinguishable\" from 1024²×128):", "",
              "| columns × 128 bits | relMSE | HDR-FLIP | voxelize ms | gather ms |", "|---|---|---|---|---|"]
    for k in cols:
        v = vox[k]
        lines.append(f"| {k}² | {v['vsReference']['relMse']:.4f} | {v['vsReference']['flipHdr']:.4f} | {rng(v['voxelizeMs'])} | {rng(v['gatherMs'])} |")
    vr, vpath = newest("area-light-vpls")
    if vr is not None:
        lines += ["", f"256 vs 16,384 VPLs at {vr['size']}², both with brute-force voxel visibility so that only the light's sampling "
                  f"differs: the 256-VPL image against the 16,384-VPL one (thesis Figs. 5.14/5.15: no perceptible difference on an "
                  f"ordinary video, artefacts for a small bouncing square). Raw record `{vpath}` (commit {vr['commit']}, {vr['date']}; "
                  f"`{vr['command']}`):", "",
                  "| scene | relMSE | HDR-FLIP | NRMSE | frame ms 256 | frame ms 16,384 |", "|---|---|---|---|---|---|"]
        for n, e in vr["cases"].items():
            c = e["256vs16384"]
            lines.append(f"| {n} | {c['relMse']:.5f} | {c['flipHdr']:.4f} | {c['nrmse']:.4f} | {rng(e['256']['frameMs'])} | {rng(e['16384']['frameMs'])} |")
    else:
        lines += ["", "256 vs 16,384 VPLs (V = 1, so only the light's sampling differs): the 256-VPL image against the 16,384-VPL one "
                  "(thesis Fig. 5.15: indistinguishable on diffuse surfaces, not for the bouncing square):", "",
                  "| scene | relMSE | HDR-FLIP | frame ms 256 | frame ms 16,384 |", "|---|---|---|---|---|"]
        for n, e in rec["vpls"].items():
            lines.append(f"| {n} | {e['256vs16384']['relMse']:.5f} | {e['256vs16384']['flipHdr']:.4f} | {rng(e['256']['frameMs'])} | {rng(e['16384']['frameMs'])} |")
    if "quality" in rec:
        qs = {k: v for k, v in rec["quality"].items() if isinstance(v, dict)}
        lines += ["", f"Quality at {rec['quality']['size']}² against `bounce reference --bounces 0` (relMSE / HDR-FLIP):", "",
                  "| scene | area-light | area-light, V = 1 | shared direct pass (centre shadow, mean texture) |", "|---|---|---|---|"]
        for n, e in qs.items():
            lines.append(f"| {n} | " + " | ".join(f"{e[k]['vsReference']['relMse']:.4f} / {e[k]['vsReference']['flipHdr']:.4f}"
                                                for k in ["area-light", "no visibility", "direct pass"]) + " |")
    if "baseline" in rec:
        bl = rec["baseline"]
        fr_ = bl["frameRatioPerRep"]
        lines += ["", f"Visibility at {bl['vpls']} VPLs, {bl['size']}², against the rasterized baseline of §5.4.6 (one 64² paraboloid shadow map per VPL), "
                  "interleaved; error against `bounce reference --bounces 0`:", "",
                  "| visibility | relMSE | HDR-FLIP | frame ms | gather ms | voxelize / maps ms |", "|---|---|---|---|---|---|"]
        for m in ["incremental", "brute", "shadow-maps"]:
            v = bl[m]
            extra = rng(v["mapsMs"]) if m == "shadow-maps" else rng(v["voxelizeMs"])
            lines.append(f"| {m} | {v['vsReference']['relMse']:.4f} | {v['vsReference']['flipHdr']:.4f} | {rng(v['frameMs'])} | {rng(v['visibilityMs'])} | {extra} |")
        lines.append(f"| shadow maps / incremental frame time | | | {min(fr_):.2f}–{max(fr_):.2f}× per rep | | |")
    lines += ["", f"Colour threshold at {rec['thresholdSize']}² (thesis: the threshold dominates the cost when low, 0.005):", "",
              "| colourThreshold | frame ms | rendered cells | rays cast |", "|---|---|---|---|"]
    for t, v in thr.items():
        lines.append(f"| {t} | {rng(v['frameMs'])} | {v['fragments']:.0f} | {v['raysCast']:.0f} |")
    return "\n".join(lines)


def vpl_visibility_table(rec, path):
    r = rec["results"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`: `{rec['scene']}` at {rec['size']}², each technique's defaults (RSM 256², 256 VPLs / "
             f"clusters / tree), `vplVisibility` off and on interleaved, {rec['reps']} repetitions of {rec['frames']} frames; "
             "ms = GPU scope, median (min–max) over the frames after the first. relMSE (ε = 0.01) of the indirect image "
             f"against `{rec['referenceCommand'].replace(' --out ' + rec['referenceCommand'].split(' --out ')[-1], '')}` "
             f"(a second seed of it: relMSE {rec['referenceNoise']['relMse']:.4f}). llvmpipe times are indicative; the "
             "ratios are the result.", "",
             "| technique | visibility | relMSE | RMSE | frame ms | voxelize ms | gather ms | gather draws | rays (blocked) | frame on / off, per rep |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for t, e in r.items():
        for v in ("off", "on"):
            x = e[v]
            rays = f"{x['visibilityRays']:.0f} ({100.0 * x['visibilityBlocked'] / x['visibilityRays']:.0f} %)" if x.get("visibilityRays") else "–"
            ratio = (f"{min(e['onOverOffPerRep']):.2f}–{max(e['onOverOffPerRep']):.2f}×" if v == "on" else "")
            lines.append(f"| `{t}` | {v} | {x['relMse'][0]:.4f} | {x['rmse'][0]:.4f} | {rng(x['frameMs'])} | "
                         f"{rng(x['voxelizeMs']) if v == 'on' else '–'} | {rng(x['gatherMs'])} | {x['gatherDraws']:.0f} | {rays} | {ratio} |")
    return "\n".join(lines)


def ratio_cell(s, digits=2):
    return f"{s['median']:.{digits}f}× ({s['min']:.{digits}f}–{s['max']:.{digits}f}, n = {s['n']})"


def iir_table(rec, path):
    c = rec["cases"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`: {rec['size']}² images (paper 1024×768), paraboloid maps 256², 4×4 tiles, atrium at "
             f"{c['atrium/256']['params'][0].split('=')[1]} triangles; comparison mode = `incremental=false` (all VPLs and maps "
             f"regenerated every frame). Each side is one `bounce render --frames {rec['frames']}` with `renderer.timing=finish` "
             f"(wall clock between glFinish calls at every pass boundary), interleaved incremental / comparison, "
             f"{rec['reps']} pairs; frames after the first (which fills the VPL budget in both modes); ratio = comparison / "
             "incremental per pair, median (min–max, pairs).", "",
             "| result | measured | maps rendered per frame, incremental / comparison (their ratio bounds R1) | paper |",
             "|---|---|---|---|"]
    def maps(e):
        m = e["mapsPerFrame"]
        return f"{m['incremental']:.1f} / {m['comparison']:.0f} ({ratio_cell(e['mapCountRatio'], 1)})"
    rows = [("R1 shadow-map time, `cornell-box-dynamic`", "cornell-box-dynamic/256", "smRatio", "41–45×"),
            ("R1 the same, `atrium` (static sun)", "atrium/256", "smRatio", "45×"),
            ("R2 frame speed-up, `cornell-box-dynamic` (34 triangles)", "cornell-box-dynamic/256", "frameSpeedup", "1.9× (CORNELL)"),
            ("R3 frame speed-up, `atrium`", "atrium/256", "frameSpeedup", "grows with complexity: 1.9× → 6.8×"),
            ("R6 1024 VPLs, frame speed-up, `cornell-box-dynamic`", "cornell-box-dynamic/1024", "frameSpeedup", "—"),
            ("R6 1024 VPLs, frame speed-up, `atrium`", "atrium/1024", "frameSpeedup", "15× (31 vs 2 fps, SIBENIK)"),
            ("R1 at 1024 VPLs, `atrium`", "atrium/1024", "smRatio", "—")]
    for label, case, key, paper in rows:
        e = c[case]
        lines.append(f"| {label} | {ratio_cell(e[key], 1)} | {maps(e)} | {paper} |")
    b = rec.get("bench", {}).get("benchmarks", {})
    if b:
        lines += ["", f"Once, through Google Benchmark (`{rec['bench']['command']}`):", "",
                  "| result | measured | paper |", "|---|---|---|"]
        o = b.get("BM_IirOmniVsSpot")
        if o:
            lines.append(f"| R5 VPL management CPU time, omni / spot | {o['omniMgmtMs']:.2f} / {o['spotMgmtMs']:.2f} ms = "
                         f"{o['R5_omniOverSpot']:.2f}× | 3–4.5× (does not reproduce: CGAL's spherical Delaunay, see iir.md) |")
        f = b.get("BM_IirFlicker")
        if f:
            lines.append(f"| flicker (mean \\|ΔI\\|/mean I, still camera, 30 frames), incremental vs comparison | "
                         f"{f['incFlicker']:.3f} vs {f['compFlicker']:.3f} | less flicker |")
        q = [(n, b.get(f"BM_IirQuality{k}")) for n, k in [("cornell-box", "Cornell"), ("cornell-box-dynamic", "CornellDynamic")]]
        cells = "; ".join(f"`{n}` {v['relMSE']:.3f} / {v['FLIP']:.3f} (mean {v['meanRatio']:.2f} of the reference)" for n, v in q if v)
        if cells:
            lines.append(f"| indirect vs `reference --bounces 1 --indirect-only`, 6 frames 10 apart, 128²: relMSE / FLIP | {cells} | — |")
    return "\n".join(lines)


def nichols_table(rec, path):
    r1, g, sp = rec["r1"], rec["gather"], rec["splat"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`: `cornell-box` unless named, RSM 256², 256 VPLs; each side one `bounce render --frames "
             f"{rec['frames']}` with `renderer.timing=finish` (wall clock between glFinish calls at every pass boundary), the "
             "second frame measured; sides interleaved (A B A B …); ratio per repetition, median (min–max, n)."
             + (" `multires-splat` is the thesis's: point splats and geometry-shader refinement "
                "(`splatPrimitive=points refinePass=geometry`, not bounce's defaults)." if "refinePass=geometry" in json.dumps(rec) else ""),
             "", "| result | measured | thesis |", "|---|---|---|",
             f"| R1 frame, `multires-splat` / `isr` (regular VPLs), {r1['size']}² | {ratio_cell(r1['frameRatio'])} | 5–10× |",
             f"| R1 light stage, (refine + splat) / (stencil set-up + gather), {r1['size']}² | {ratio_cell(r1['lightRatio'])} | "
             "18–20× (splat vs gather alone); Table 4.1's refine + splat vs stencil + gather: 14.7–18× |"]
    for k, v in g["speedupOverRsm"].items():
        lines.append(f"| `{k}` frame speed-up over the full `rsm` gather, `cornell-box-dynamic`, {g['size']}² | {ratio_cell(v)} | several times |")
    for k, v in sp["multiresSpeedup"].items():
        lines.append(f"| `multires-splat` frame speed-up over `{k}`, {sp['size']}² (matched: {sp['fragmentsPerVpl']:.0f} fragments per VPL) | {ratio_cell(v)} | 5–10× over full-screen splatting |")
    r2 = rec["r2"]
    sizes = [k for k in r2 if int(k) <= 256]
    lines.append("| R2 subsplats / full fill at " + " / ".join(f"{k}²" for k in sizes) + " (output = indirect resolution) | "
                 + " / ".join(f"{100 * r2[k]['fillFraction']:.1f} %" for k in sizes)
                 + (f" ({rec['big']}²: {100 * r2[str(rec['big'])]['fillFraction']:.1f} %)" if str(rec['big']) in r2 and int(rec['big']) > 256 else "")
                 + " | ≈ 46 / 21 / 10 / 5 % |")
    r3 = rec["r3"]["cases"]
    lines.append(f"| R3 `multires-splat` frame on `atrium`, " + " → ".join(f"{v['triangles'] / 1000:.0f}K" for v in r3.values())
                 + f" triangles, {rec['r3']['size']}² | " + " → ".join(f"{v['frameMs']['median']:.0f} ms" for v in r3.values())
                 + " | nearly flat (a CPU rasteriser pays per triangle) |")
    r4, r5 = rec["r4"], rec["r5"]
    lines.append(f"| R4 `normalThreshold` 0.25 / 1.4 frame time, {r4['size']}² (subsplats {r4['subsplats']['0.25']:.0f} / {r4['subsplats']['1.4']:.0f}) | {ratio_cell(r4['ratio'])} | ~4× (Buddha, 1024²) |")
    lines.append(f"| R5 `edgeNeighbours` off / on frame time, {r5['size']}² (subsplats {r5['subsplats']['off']:.0f} / {r5['subsplats']['on']:.0f}) | {ratio_cell(r5['ratio'])} | on costs up to 40 % |")
    r6, r6path = newest("nichols-r6")
    if r6 is not None:
        full, multi = r6["against"].get("full1m.exr", {}), r6["against"].get("multires1m.exr", {})
        def pct(rows, name):
            return f"{100 * rows[name]['relRms']:.2f} %" if name in rows else "–"
        lines.append(f"| R6 at {r6['size']}², relative RMS: eye clustering alone (`isr`, 1M VPLs) / `isr` light clusters to 256² "
                     f"vs the 1M-VPL gather; `hisr` depth 3, τ 0.001 vs the 1M multiresolution gather (`{r6path}`, commit {r6['commit']}) | "
                     f"{pct(full, 'multires1m.exr')} / {pct(full, 'isr_f256.exr')}; {pct(multi, 'hisr_d3_t0.001.exr')} "
                     f"(`isr` defaults: {pct(full, 'isr_f64.exr')}) | 2–3 % / 5–6 % combined; 3–4 % light hierarchy |")
    return "\n".join(lines)


def foundation_table(rec, path):
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`.", "",
             "`direct`, 512², median GPU frame time over 20 frames (run record `median_ms`, timestamp queries), median "
             "(min–max) over the repetitions:", "",
             "| scene | triangles | frame | G-buffer | direct light | command |", "|---|---|---|---|---|---|"]
    for scene, e in rec["direct"].items():
        ms = e["ms"]
        lines.append(f"| `{scene}` | {e['triangles']:,} | {rng(ms['frame'])} ms | {rng(ms['gbuffer'])} ms | "
                     f"{rng(ms['direct'])} ms | `{e['command']}` |")
    ref = rec["reference"]
    runs = {}
    for b in ref["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        runs.setdefault(b["run_name"], []).append(b)
    names = {"scene:0": "cornell-box", "scene:1": "two-rooms", "scene:2": "atrium"}
    lines += ["", f"The reference path tracer (`{ref['command']}`): `cornell-box-area` at 512², other scenes at 256², "
              "paths of at most 64 reflections; median (min–max) over the 5 repetitions, millions per second:", "",
              "| benchmark | scene | threads | SIMD kernel | camera paths/s | rays/s |", "|---|---|---|---|---|---|"]
    for name, bs in runs.items():
        parts = dict(p.split(":", 1) for p in name.split("/")[1:] if ":" in p)
        if name.startswith("BM_ReferencePathTracer"):
            scene = names.get(f"scene:{parts['scene']}", "?") if "scene" in parts else "cornell-box-area"
            threads = parts.get("threads", "0")
            threads = "all" if threads == "0" else threads
            paths = summary_of([b["paths/s"] * 1e-6 for b in bs])
            rays = summary_of([b.get("rays/s", 0.0) * 1e-6 for b in bs])
            lines.append(f"| `{name.split('/')[0]}` | `{scene}` | {threads} | {'on' if parts.get('vectorized') == '1' else 'off'} | "
                         f"{paths['median']:.2f} ({paths['min']:.2f}–{paths['max']:.2f}) | "
                         + (f"{rays['median']:.1f} ({rays['min']:.1f}–{rays['max']:.1f})" if rays['max'] > 0 else "–") + " |")
    casts = [(n, summary_of([b["rays/s"] * 1e-6 for b in bs])) for n, bs in runs.items() if n.startswith("BM_ReferenceRayCaster")]
    if casts:
        lines += ["", "Ray-casting service (random rays in the same box), M rays/s: "
                  + "; ".join(f"`{n.split('/')[0].replace('BM_ReferenceRayCaster', '')}` {c['median']:.1f} ({c['min']:.1f}–{c['max']:.1f})" for n, c in casts) + "."]
    return "\n".join(lines)


def soak_table(rec, path):
    t = rec["techniques"]
    cheap = ", ".join("`" + k + "` with " + " ".join(v) for k, v in rec["cheapSettings"].items())
    scenes = ", ".join("`" + s + "`" for s in rec["fallbackScenes"])
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`: each technique {rec['frames']} frames of `{rec['scene']}` at {rec['size']}² "
             f"(or the first of {scenes} it accepts), unless "
             f"{rec['budgetSeconds']:g} s of frames came first ('budget': the frame count then follows from a short "
             "probe run, so a frame time measured on a busy machine gives fewer frames); "
             f"{cheap}. "
             "Live GL objects and buffer / texture bytes are what the wrappers of src/gpu/ hold "
             "(`gl::liveResources`), RSS is /proc/self/statm; about 100 samples per run (`--stats-every`). "
             "Warm-up is the first third of the frames; flat = GL objects and bytes never above their value at the "
             f"end of warm-up, RSS growth after it at most {rec['rssGrowthBound'] / 1e6:.0f} MB (its floor: the smallest "
             "sample of the last third against the smallest of the first third). llvmpipe keeps textures in system "
             "memory, so RSS includes them.", "",
             "| technique | scene | frames | frame ms (wall) | GL objects (start → end of warm-up → end) | buffers MB | textures MB | "
             "RSS MB (end of warm-up → end) | RSS slope kB / 1000 frames | flat |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for name, e in t.items():
        if "error" in e:
            lines.append(f"| `{name}` | – | – | – | {e['error']} | | | | | no |")
            continue
        g, r = e["gl_objects"], e["rss_bytes"]
        frames = f"{e['frames']}" + (" (budget)" if e["limitedBy"] == "time budget" else "")
        lines.append(f"| `{name}` | `{e['scene']}` | {frames} | {e['frameMs']:.1f} | {g['first']} → {g['warmup']} → {g['last']} | "
                     f"{e['buffer_bytes']['last'] / 1e6:.3f} | {e['texture_bytes']['last'] / 1e6:.2f} | "
                     f"{r['warmup'] / 1e6:.1f} → {r['last'] / 1e6:.1f} ({r['growth'] / 1e6:+.2f}) | "
                     f"{r['slopeBytesPerFrame']:+.2f} | {'yes' if e['flat'] else 'no: ' + '; '.join(e['problems'])} |")
    return "\n".join(lines)


def summary_of(values):
    values = sorted(values)
    n = len(values)
    median = values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])
    return {"min": values[0], "median": median, "max": values[-1], "n": n}


def interactive_table(rec, path):
    """Issue 18: frame times and fps at interactive sizes: this build, the build it was measured against
    (interleaved), and the record taken when the issue was filed (`interactive-before-issue-*.json`)."""
    before = rec.get("before", {})
    start_files = sorted(glob.glob(os.path.join(ROOT, "bench/results", "interactive-before-issue-*.json")))
    start, start_path = ({}, None)
    if start_files:
        with open(start_files[-1]) as f:
            start = json.load(f)
        start_path = os.path.relpath(start_files[-1], ROOT)
    # The issue-start record's "before" column is the build before the issue; its "after" the first pass at it.
    issue = start.get("before", {})
    lines = [f"Raw record `{path}` (commit {rec['commit']}; before = commit {rec.get('beforeCommit', '—')}; {rec['date']}, "
             f"{rec['machine']}, {rec['gpu']}); `{rec['command']}`: `{rec['scene']}`, default settings unless the row says, "
             "default timers; frame = the run record's per-frame wall time (renderFrame to the glFinish ending the frame), "
             f"median over the frames after the first; both builds' sides interleaved, {rec['reps']} repetitions; ratio per "
             "repetition, median (min–max). llvmpipe times are indicative."
             + (f" \"issue filed\": commit {start.get('beforeCommit', '—')} from `{start_path}` (another run, same machine "
                "kind; compare its ratios, not its times)." if start_path else ""), "",
             "| size | technique | frame ms (fps) | before | issue filed | goal |", "|---|---|---|---|---|---|"]
    # Without an issue-start record the "issue filed" column would be empty: left out.
    drop = (lambda row: row) if start_path else (lambda row: "|".join(c for k, c in enumerate(row.split("|")) if k != 5))
    goals = {"isr": "≥ 10 fps at 256²", "hisr": "≥ 10 fps at 256²"}
    cell = lambda x: f"{x['frameMs']['median']:.1f} ({x['fps']:.1f})" if x else "—"
    for size in map(str, rec["sizes"]):
        for name, side in rec["after"][size]["sides"].items():
            b = before.get(size, {}).get("sides", {}).get(name)
            i = issue.get(size, {}).get("sides", {}).get(name)
            lines.append(f"| {size}² | `{name}` | {cell(side)} | {cell(b)} | {cell(i)} | {goals.get(name, '') if size == '256' else ''} |")
    lines += ["", "| size | speed-up | measured | before | issue filed | goal |", "|---|---|---|---|---|---|"]
    rgoals = {"isr over rsm": "≥ 2× (same VPLs: see the 1024-VPL row)", "isr over rsm 1024 VPLs": "≥ 2×",
              "hisr over rsm": "≥ 2× (same VPLs: see the 1024-VPL row)",
              "hisr over rsm 1024 VPLs": "≥ 2× (hisr's tree has 4096 leaves)", "multires-splat over rsm-splat": "> 1×",
              "multires-splat points over rsm-splat": "(the thesis's points)", "isr regular over rsm": "≥ 2× (same 256 VPLs)"}
    rcell = lambda r: ratio_cell(r) if r else "—"
    for size in map(str, rec["sizes"]):
        for key, r in rec["after"][size]["ratios"].items():
            b = before.get(size, {}).get("ratios", {}).get(key)
            i = issue.get(size, {}).get("ratios", {}).get(key)
            lines.append(f"| {size}² | {key} | {rcell(r)} | {rcell(b)} | {rcell(i)} | {rgoals.get(key, '')} |")
    first = next(k for k, line in enumerate(lines) if line.startswith("| size | technique"))
    lines = [drop(line) if line.startswith("|") and k >= first else line for k, line in enumerate(lines)]
    passes = rec.get("passes256") or {}
    if passes:
        lines += ["", "Per pass at 256² (this build, one run of 6 frames with `renderer.timing=finish`: a glFinish at every "
                  "pass boundary, so each pass's wall time is its own work; median over the frames after the first, ms):", "",
                  "| side | frame | the technique's passes | shared passes (G-buffer, shadow maps, direct, compose) |",
                  "|---|---|---|---|"]
        shared = ("gbuffer", "shadow-maps", "direct", "compose")
        for name, side in passes.items():
            ms = side["passMs"]
            own = sorted(((k.split("/", 1)[1], v) for k, v in ms.items() if "/" in k), key=lambda kv: -kv[1])
            lines.append(f"| `{name}` | {ms.get('frame', 0.0):.1f} | "
                         + ", ".join(f"{k} {v:.1f}" for k, v in own if v >= 0.05)
                         + f" | {sum(ms.get(k, 0.0) for k in shared):.1f} |")
    return "\n".join(lines)


def nichols_cap_table(rec, path):
    r2, r3, prim, r7 = rec["r2"], rec["r3"], rec["prim"], rec["r7"]
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); "
             f"`{rec['command']}`: `cornell-box` unless named, RSM 256², 256 VPLs; each side one `bounce render --frames "
             f"{rec['frames']}` with `renderer.timing=finish`, the second frame measured; sides interleaved (A B A B …); "
             "ratio per repetition, median (min–max, n). `indirectSize` caps the indirect resolution at a fixed output.", "",
             "| result | measured | thesis |", "|---|---|---|"]
    caps = [k for k in r2["cases"] if int(k) <= 256]
    lines.append(f"| R2 `multires-splat` subsplats / full fill at indirect " + " / ".join(f"{k}²" for k in caps)
                 + f", fixed {r2['output']}² output | " + " / ".join(f"{100 * r2['cases'][k]['fillFraction']:.1f} %" for k in caps)
                 + (f" ({r2['output']}²: {100 * r2['cases'][str(r2['output'])]['fillFraction']:.1f} %)" if str(r2['output']) in r2['cases'] and r2['output'] > 256 else "")
                 + " | ≈ 46 / 21 / 10 / 5 % (Table 3.1) |")
    cases = r3["cases"]
    lines.append(f"| R3 `multires-splat` frame on `atrium`, " + " → ".join(f"{v['triangles'] / 1000:.0f}K" for v in cases.values())
                 + f" triangles, {r3['output']}² output, indirect {r3['indirectSize']}² (n = {r3['reps']}) | "
                 + " → ".join(f"{v['frameMs']['median']:.0f} ms" for v in cases.values())
                 + " | nearly flat (Table 3.2) |")
    res = r3["resolution"]
    big = [k for k in res["frameMs"] if k != "128"][0]
    lines.append(f"| R3 indirect {big}² / 128² frame time, {r3['output']}² output ({res['frameMs']['128']['median']:.0f} → "
                 f"{res['frameMs'][big]['median']:.0f} ms) | {ratio_cell(res['ratio'])} | 2–3× fps for 128² → 1024² |")
    lines.append(f"| `splatPrimitive` quads / points, {prim['output']}², frame / splat pass; side medians: frame "
                 f"{prim['frameMs']['quads']['median']:.0f} / {prim['frameMs']['points']['median']:.0f} ms, splat "
                 f"{prim['splatMs']['quads']['median']:.0f} / {prim['splatMs']['points']['median']:.0f} ms | "
                 f"{ratio_cell(prim['frameRatio'])} / {ratio_cell(prim['splatRatio'])} | points ≈ 5 % faster (§3.4.1) |")
    lines += ["", f"R7, {r7['output']}², median over {r7['reps']} interleaved runs: the gather pass against the rest of the "
              "frame (G-buffer, direct light, RSM, VPL cache or tree, min-max mipmap, stencil set-up, upsampling), which "
              "does not depend on the VPL count:", "",
              "| configuration | VPLs / nodes per fragment | frame | gather (share) | rest of the frame | its largest passes |",
              "|---|---|---|---|---|---|"]
    for k, v in r7["cases"].items():
        frame = v["frameMs"]["median"]
        tech = k.split()[0]
        gather = v["passMs"].get(f"{tech}/gather", {"median": 0.0})["median"]
        rest = {n: m["median"] for n, m in v["passMs"].items() if n != f"{tech}/gather" and n != tech}
        top = sorted(rest.items(), key=lambda kv: -kv[1])[:3]
        count = f"{v['nodesPerFragment']:.0f} nodes" if tech == "hisr" else f"{v['vpls']:.0f} VPLs"
        lines.append(f"| `{k}` | {count} | {frame:.0f} ms | {gather:.0f} ms ({100 * gather / frame:.0f} %) | "
                     f"{frame - gather:.0f} ms | " + ", ".join(f"`{n.split('/', 1)[-1]}` {m:.0f}" for n, m in top) + " |")
    return "\n".join(lines)


def fidelity_overlays(rec):
    """Records `fidelity-rows-DATE[-N].json`: the same run for some techniques only (`--techniques`), rerun after
    their defaults changed; newer than the base record, each replaces its techniques' rows (oldest first)."""
    out = []
    for f in sorted(glob.glob(os.path.join(ROOT, "bench/results", "fidelity-rows-*.json"))):
        with open(f) as fh:
            r = json.load(fh)
        if r["date"] > rec["date"] and (r["size"], r["spp"]) == (rec["size"], rec["spp"]):
            out.append((r, os.path.relpath(f, ROOT)))
    return sorted(out, key=lambda rp: rp[0]["date"])


def fidelity_table(rec, path):
    """Technique x built-in scene: energy (image mean / reference mean) and relMSE against the declared scope."""
    res = {sc: dict(row) for sc, row in rec["results"].items()}
    scenes = list(res.keys())
    techniques = list(next(iter(res.values())).keys())
    tol = rec.get("energyTolerance", 0.15)
    overlays = []
    for r, rpath in fidelity_overlays(rec):
        rows = sorted({t for row in r["results"].values() for t in row})
        for sc, row in r["results"].items():
            if sc in res:
                res[sc].update(row)
        overlays.append(f"the rows of {', '.join(f'`{t}`' for t in rows)} from `{rpath}` (commit {r['commit']}, {r['date']}; "
                        f"`{r['command']}`)")
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); `{rec['command']}`: "
             f"each technique at its defaults, {rec['size']}², against `bounce reference` at {rec['spp']} spp in the scope `bounce list` "
             "declares for it. Cells: energy (image mean / reference mean) and relMSE; **bold** where the energy leaves "
             f"±{tol * 100:.0f} % or the relMSE is not below the no-GI image's (the shared direct pass's image of the same component); "
             "— where the technique refuses the scene (one-line error)"
             + (f"; *stopped* where a render ran past {rec['runTimeoutSeconds']:g} s" if rec.get("runTimeoutSeconds") else "")
             + ". The last rows are the no-GI relMSE of each reference scope."
             + ("".join(f" Replaced: {o}." for o in overlays)), "",
             "| technique | " + " | ".join(f"`{s}`" for s in scenes) + " |", "|---|" + "---|" * len(scenes)]
    nogi = {}  # (scope, component) -> scene -> the no-GI image's relMSE in that scope
    for t in techniques:
        cells = []
        for sc in scenes:
            e = res[sc][t]
            if "refused" in e:
                cells.append("—")
                continue
            if "timedOut" in e:
                cells.append("*stopped*")
                continue
            m = e["metrics"]
            nogi.setdefault((e["scope"], e["component"]), {}).setdefault(sc, e["noGi"]["relMse"])
            cell = f"{m['energy']:.2f} / {m['relMse']:.3f}"
            out = not e.get("baseline") and not e["withinBounds"]
            cells.append(f"**{cell}**" if out else cell)
        lines.append(f"| `{t}` | " + " | ".join(cells) + " |")
    # One no-GI row per reference scope: a technique is held to the row of the scope it declares.
    for (scope, component), row in sorted(nogi.items()):
        lines.append(f"| no-GI relMSE, `{scope or 'full image'}` ({component}) | "
                     + " | ".join(f"{row[sc]:.3f}" if sc in row else "—" for sc in scenes) + " |")
    return "\n".join(lines)


def large_scene_table(rec, path):
    """Issue 30: every technique's frame times at its defaults on the Sponza-class scene, sun and sky."""
    lights = list(rec["results"].keys())
    techniques = list(next(iter(rec["results"].values())).keys())
    lines = [f"Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); `{rec['command']}`: "
             f"`{rec['scene']}` at {rec['size']}², each technique at its defaults, {rec['frames']} frames (`radiosity-gather` one), "
             "one process each. Cells: first frame ms (shader compilation, first build) / median of the later frames ms "
             f"(wall, renderFrame to its glFinish); **bold** where a later frame exceeds the budget of the technique's kind "
             f"({rec['gpuBudgetMs']:.0f} ms for the GPU techniques, {rec['radiosityBudgetMs']:.0f} ms for the progressive radiosity "
             "methods; the gather is timed, not budgeted); — a one-line refusal; *stopped* a run past "
             f"{rec.get('runTimeoutSeconds', 0):.0f} s.", "",
             "| technique | " + " | ".join(f"`light={l}`" for l in lights) + " |", "|---|" + "---|" * len(lights)]
    for t in techniques:
        cells = []
        for l in lights:
            e = rec["results"][l].get(t, {})
            if "refused" in e:
                cells.append("—")
            elif "timedOut" in e:
                cells.append("*stopped*")
            elif "error" in e:
                cells.append("error: " + e["error"])
            else:
                later = "–" if e["medianLaterMs"] is None else f"{e['medianLaterMs']:.0f}"
                cell = f"{e['firstFrameMs']:.0f} / {later}"
                cells.append(f"**{cell}**" if e["withinBudget"] is False else cell)
        lines.append(f"| `{t}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def demo_table(rec, path):
    """Issue 30: `make demo`'s rendering part against its 3-minute budget, with the slowest pairs."""
    slow = sorted(rec["pairs"], key=lambda p: -p["ms"])[:3]
    study = "" if rec.get("studySeconds") is None else f", the study {rec['studySeconds']:.0f} s"
    return (f"`make demo`'s rendering part at {rec['size']}: {rec['renderSeconds']:.0f} s (budget {rec['renderBudgetSeconds']} s; "
            f"{rec['rendered']} images, {rec['refused']} one-line refusals, {rec['skipped']} pairs the demo skips{study}; slowest: "
            + ", ".join(f"{p['scene']} × {p['technique']} {p['ms'] / 1000:.1f} s" for p in slow)
            + f"). Raw record `{path}` (commit {rec['commit']}, {rec['date']}, {rec['machine']}, {rec['gpu']}); `{rec['command']}`.")


GENERATORS = {"vct": vct_table, "photon-splat": photon_splat_table, "radiosity": radiosity_table,
              "area-light": area_light_table, "vpl-visibility": vpl_visibility_table,
              "iir": iir_table, "nichols": nichols_table, "nichols-cap": nichols_cap_table, "foundation": foundation_table, "soak": soak_table,
              "interactive": interactive_table, "fidelity": fidelity_table,
              "large-scene": large_scene_table, "demo": demo_table}


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
