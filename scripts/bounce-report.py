#!/usr/bin/env python3
# `bounce report RESULTS_DIR OUT.html`: the page of a study (docs/studies.md). bounce compiles this
# script in and runs it as `python3 - RESULTS_DIR OUT.html`; it can also be run directly.
#
# Reads every record.json under RESULTS_DIR (the folders of any number of machines copied together)
# and writes, atomically and together (a failure leaves none of them):
#   OUT.html       one self-contained page: images and matplotlib plots inlined as base64 PNG, no
#                  script or style from outside, so it opens offline from a file:// URL;
#   results.json   one flat object per (scene, technique, variant): what pandas.read_json reads;
#   results.csv    the same rows for a spreadsheet.
import base64
import csv
import html
import io
import json
import math
import os
import sys
import tempfile


def fail(message):
    print(f"bounce report: {message}", file=sys.stderr)
    sys.exit(1)


try:
    import matplotlib

    matplotlib.use("Agg")  # no display: plots are rendered to PNG in memory
    import matplotlib.pyplot as plt
except ImportError:
    fail("python3-matplotlib is missing (scripts/install-deps.sh installs it)")

# Display order of the image grid.
COMPONENTS = ["full", "direct", "indirect"]
# Metrics copied into results.json from a compare record, in column order; each with its
# reference-noise floor (METRIC_floor) and whether the measured error is within 2x of it
# (METRIC_insideFloor), docs/metrics.md "Reference noise floor".
METRICS = ["relMse", "relRms", "mse", "rmse", "mae", "nrmse", "psnr", "ssim", "flipLdr", "flipHdr", "rmsSum8", "energy"]
# The metrics whose floors the page shows (the plots' two and the table's).
FLOOR_SHOWN = ["relMse", "relRms", "flipLdr"]
# Matplotlib figure size (inches at 100 dpi): plots stay legible at the page's 900 px column.
PLOT_SIZE = (9.0, 3.6)
PLOT_DPI = 100


def write_all(files):
    """Writes every (path, text) pair to a temporary sibling, then renames them all: a failure (a full
    disk, a read-only folder) leaves none of them and names the file."""
    staged, in_place = [], []
    for path, data in files:
        target = os.path.realpath(path)  # a symbolic link is followed: its target is replaced
        # A device or FIFO (/dev/null, /dev/full) cannot be replaced by a rename: written in place, last.
        if os.path.exists(target) and not os.path.isfile(target) and not os.path.isdir(target):
            in_place.append((path, target, data))
    files = [(os.path.realpath(p), d) for p, d in files if p not in {x[0] for x in in_place}]
    try:
        for path, data in files:
            folder = os.path.dirname(os.path.abspath(path))
            try:
                fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
                staged.append(tmp)
                with os.fdopen(fd, "w") as f:
                    f.write(data)
                os.chmod(tmp, 0o644)
            except OSError as e:
                fail(f"{path}: cannot write: {e.strerror or e}")
        for path, target, data in in_place:
            try:
                with open(target, "w") as f:
                    f.write(data)
            except OSError as e:
                fail(f"{path}: cannot write: {e.strerror or e}")
        for tmp, (path, _data) in zip(staged, files):
            try:
                os.replace(tmp, path)
            except OSError as e:
                fail(f"{path}: cannot write: {e.strerror or e}")
    finally:
        for tmp in staged:
            if os.path.exists(tmp):
                os.remove(tmp)


def load_records(root):
    records, problems = [], []
    for folder, _dirs, files in os.walk(root):
        if "record.json" not in files:
            continue
        path = os.path.join(folder, "record.json")
        try:
            with open(path, encoding="utf-8") as f:
                r = json.load(f)
        except (OSError, ValueError) as e:
            problems.append(f"{os.path.relpath(path, root)}: {e}")
            continue
        if not isinstance(r, dict) or "job" not in r:
            continue
        r["_folder"] = folder
        records.append(r)
    return records, problems


def data_uri(path):
    try:
        with open(path, "rb") as f:
            return "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")
    except OSError:
        return None


def figure_uri(fig):
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=PLOT_DPI, bbox_inches="tight")
    plt.close(fig)
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def esc(text):
    return html.escape(str(text), quote=True)


def fmt(value, digits=4):
    if value is None:
        return "—"
    if isinstance(value, float):
        if math.isinf(value) or math.isnan(value):
            return str(value)
        return f"{value:.{digits}g}"
    return esc(value)


def split_id(job_id):
    # kind/scene/technique/variant (reference: kind/scene/scope/frame)
    parts = job_id.split("/")
    return parts + [""] * (4 - len(parts))


def pareto_front(points):
    # points: (time, error); the front is every point no other point beats on both.
    front = []
    for t, e in sorted(points):
        if not front or e < front[-1][1]:
            front.append((t, e))
    return front


def machine_lines(records):
    lines = set()
    for r in records:
        host = r.get("host", {})
        gpu = r.get("gpu", {})
        text = f"{host.get('hostname', '?')}: {host.get('cpu', '?')}, {host.get('cores', '?')} cores"
        if gpu:
            text += f"; GPU {gpu.get('renderer', '?')} ({gpu.get('vendor', '?')}, OpenGL {gpu.get('version', '?')}, {gpu.get('platform', '?')})"
        if r.get("kind") in ("render", "temporal") and gpu:
            lines.add(text)
    return sorted(lines)


def build_rows(renders, compares, temporals, references):
    rows = []
    for job_id, r in sorted(renders.items()):
        _, scene, technique, variant = split_id(job_id)
        spec = r.get("spec", {})
        row = {"scene": scene, "technique": technique, "variant": variant, "status": r.get("status"),
               "reason": r.get("reason", ""),
               "settings": ";".join(f"{k}={v}" for k, v in sorted(spec.get("settings", {}).items())),
               "width": spec.get("size", [0, 0])[0], "height": spec.get("size", [0, 0])[1],
               "frames": spec.get("frames"), "startFrame": spec.get("startFrame")}
        scope = r.get("scope") or {}
        row["scopeComponent"] = scope.get("component")
        median = r.get("median_ms", {})
        row["frame_ms"] = median.get("frame")
        row["cpu_ms"] = median.get("cpu")
        for name, value in sorted(median.items()):
            if name not in ("frame", "cpu"):
                row[f"pass_{name}_ms"] = value
        frames = r.get("frames") or []
        if frames:
            for name, value in sorted((frames[-1].get("counters") or {}).items()):
                row[f"counter_{name}"] = value
        gpu = r.get("gpu", {})
        row["gpu"] = gpu.get("renderer")
        row["host"] = r.get("host", {}).get("hostname")
        leak = r.get("leak")
        if leak:
            row["leak_full"] = leak.get("full") if not isinstance(leak.get("full"), dict) else None
        c = compares.get(f"compare/{scene}/{technique}/{variant}")
        if c:
            row["compare_status"] = c.get("status")
            row["reference"] = c.get("reference")
            ref = references.get(c.get("reference"))
            if ref:
                row["reference_spp"] = (ref.get("result") or {}).get("samplesPerPixel")
            for m in METRICS:
                row[m] = (c.get("metrics") or {}).get(m)
                row[f"{m}_floor"] = (c.get("floor") or {}).get(m)
                row[f"{m}_insideFloor"] = (c.get("insideFloor") or {}).get(m)
            row["relMseCorrected"] = (c.get("metrics") or {}).get("relMseCorrected")
            row["reference_noise"] = (c.get("referenceNoise") or {}).get("meanPixelRelativeStdError")
            row["reference_scope"] = split_id(c.get("reference", ""))[2] if c.get("reference") else None
            cl = c.get("leak") or {}
            if cl:
                row["leak_test"] = cl.get("test") if not isinstance(cl.get("test"), dict) else None
                row["leak_reference"] = cl.get("reference") if not isinstance(cl.get("reference"), dict) else None
        t = temporals.get(f"temporal/{scene}/{technique}/{variant}")
        if t:
            row["temporal_status"] = t.get("status")
            row["flicker"] = t.get("flicker")
            row["referenceFlicker"] = t.get("referenceFlicker")
            conv = t.get("convergence") or {}
            row["convergenceLatencyFrames"] = conv.get("latencyFrames")
            row["convergenceSettled"] = conv.get("settled")
            row["convergenceEventFrame"] = conv.get("eventFrame")
            row["convergenceAnimation"] = conv.get("animation")
        rows.append(row)
    return rows


def inside_any(row):
    """True when the row's error is within 2x the reference-noise floor on a metric the page shows."""
    return any(row.get(f"{m}_insideFloor") for m in FLOOR_SHOWN)


def scatter_plot(scene, rows):
    fig, axes = plt.subplots(1, 2, figsize=PLOT_SIZE)
    techniques = sorted({r["technique"] for r in rows})
    cmap = plt.get_cmap("tab20")
    for ax, metric, label in ((axes[0], "relMse", "relMSE (linear)"), (axes[1], "flipLdr", "LDR-FLIP (displayed)")):
        # The reference-noise floor of each reference scope as a band up to 2x the floor: a point
        # inside it cannot be told from the reference's noise, so it is drawn hollow and grey.
        # Only positive floors: a 1-spp reference has no variance estimate (floor 0), nothing to draw,
        # and a zero on the log axis would stretch the figure past matplotlib's size limit.
        floors = sorted({(r.get("reference_scope") or "", r[f"{metric}_floor"]) for r in rows
                         if isinstance(r.get(f"{metric}_floor"), (int, float)) and math.isfinite(r[f"{metric}_floor"])
                         and r[f"{metric}_floor"] > 0})
        values = [r[metric] for r in rows if r.get(metric) is not None] + [f for _, f in floors]
        bottom = min(values) / 3 if metric == "relMse" and values and min(values) > 0 else 0.0
        # Floors within 20% of each other share one label (scopes of about the same noise).
        labels = []
        for scope, floor in floors:
            if labels and floor <= labels[-1][1] * 1.2:
                labels[-1] = (labels[-1][0] + ", " + scope, labels[-1][1])
            else:
                labels.append((scope, floor))
        for i, (scope, floor) in enumerate(floors):
            ax.axhspan(bottom, 2 * floor, color="0.5", alpha=0.12, zorder=1, linewidth=0,
                       label="noise floor x2" if i == 0 else None)
            ax.axhline(floor, color="0.45", linewidth=0.8, linestyle=":", zorder=1)
        for scope, floor in labels:
            ax.annotate(scope, xy=(1.0, floor), xycoords=("axes fraction", "data"), fontsize=6, color="0.35",
                        ha="right", va="bottom")
        for i, technique in enumerate(techniques):
            points = [(r["frame_ms"], r[metric], bool(r.get(f"{metric}_insideFloor"))) for r in rows
                      if r["technique"] == technique and r.get("frame_ms") is not None and r.get(metric) is not None]
            if not points:
                continue
            colour = cmap(i % 20)
            outside = [p for p in points if not p[2]]
            inside = [p for p in points if p[2]]
            if outside:
                ax.scatter([p[0] for p in outside], [p[1] for p in outside], color=colour, label=technique, s=22, zorder=3)
            if inside:
                ax.scatter([p[0] for p in inside], [p[1] for p in inside], facecolors="0.85", edgecolors=colour, s=22,
                           zorder=3, label=None if outside else technique)
            front = pareto_front([(p[0], p[1]) for p in points])
            if len(front) > 1:
                ax.step([p[0] for p in front], [p[1] for p in front], where="post", color=colour, linewidth=1.2, zorder=2)
        ax.set_xlabel("median GPU frame time (ms)")
        ax.set_ylabel(label)
        ax.set_xscale("log")
        if metric == "relMse":
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=8)
    fig.suptitle(f"{scene}: error vs time, Pareto front per technique (steps); grey band: 2x the reference-noise floor, "
                 "hollow grey points inside it", fontsize=9)
    return figure_uri(fig)


def temporal_plot(scene, records):
    fig, axes = plt.subplots(1, 2, figsize=PLOT_SIZE)
    for job_id, t in sorted(records.items()):
        _, _, technique, variant = split_id(job_id)
        frames = t.get("frames") or []
        xs = [f["frame"] for f in frames]
        label = f"{technique} {variant}"
        axes[0].plot(xs, [f.get("relRms") for f in frames], marker=".", label=label)
        axes[1].plot(xs, [f.get("flicker") if f.get("flicker") is not None else float("nan") for f in frames],
                     marker=".", label=label)
    if records:
        first = next(iter(sorted(records.items())))[1]
        ref = [f.get("referenceFlicker") if f.get("referenceFlicker") is not None else float("nan")
               for f in first.get("frames") or []]
        axes[1].plot([f["frame"] for f in first.get("frames") or []], ref, "k--", label="reference")
        # Each scope's per-frame relative RMS floor: the error an exact image would show (docs/metrics.md).
        scopes = {}
        for t in records.values():
            key = json.dumps(t.get("scope"), sort_keys=True)
            scopes.setdefault(key, t)
        for i, t in enumerate(scopes.values()):
            frames = t.get("frames") or []
            if frames and frames[0].get("relRmsFloor") is not None:
                axes[0].plot([f["frame"] for f in frames], [f.get("relRmsFloor") for f in frames], color="0.4",
                             linestyle=":", label="reference-noise floor" if i == 0 else None)
    axes[0].set_ylabel("relative RMS error vs reference")
    axes[1].set_ylabel("flicker (mean |ΔY| / mean Y)")
    for ax in axes:
        ax.set_xlabel("frame")
        ax.grid(True, alpha=0.3)
    handles, labels = axes[1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=8)
    fig.suptitle(f"{scene}: per-frame error and flicker")
    return figure_uri(fig)


CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1400px; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
.machine { color: #555; font-size: 0.9em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
th { background: #f0f0f0; } td.name, th.name { text-align: left; }
.grid td { text-align: center; vertical-align: top; }
.grid img { width: 128px; height: auto; image-rendering: pixelated; cursor: zoom-in; display: block; margin: auto; }
img.plot { max-width: 100%; height: auto; display: block; }
.refused { color: #a33; font-size: 0.85em; max-width: 20em; text-align: left; }
#zoom { position: fixed; inset: 0; background: rgba(0,0,0,0.85); display: flex; align-items: center;
        justify-content: center; cursor: zoom-out; }
#zoom img { max-width: 95vw; max-height: 95vh; width: 90vmin; image-rendering: pixelated; }
button { margin: 0.3em 0; }
.inside { color: #999; font-style: italic; }
p.floor { color: #555; font-size: 0.9em; }
"""

# The page's own checks (tests/study/report_chromium.py reads data-selftest): every image decoded
# completely and laid out with a non-zero size, and no script error or console.error while loading.
SCRIPT = """
window.bounceErrors = [];
window.addEventListener('error', function (e) { window.bounceErrors.push(String(e.message || e)); }, true);
(function () {
  var original = console.error;
  console.error = function () {
    window.bounceErrors.push(Array.prototype.join.call(arguments, ' '));
    return original.apply(console, arguments);
  };
})();
function bounceToggleHeat(button) {
  var on = button.getAttribute('aria-pressed') !== 'true';
  button.setAttribute('aria-pressed', on ? 'true' : 'false');
  button.textContent = on ? 'show images' : 'show FLIP heat maps';
  var images = document.querySelectorAll('img[data-heat]');
  for (var i = 0; i < images.length; ++i) {
    var img = images[i];
    if (!img.dataset.image) img.dataset.image = img.src;
    img.src = on ? img.dataset.heat : img.dataset.image;
  }
}
function bounceZoom(img) {
  var overlay = document.createElement('div');
  overlay.id = 'zoom';
  var big = document.createElement('img');
  big.src = img.src;
  big.alt = 'zoomed ' + img.alt;
  overlay.appendChild(big);
  overlay.addEventListener('click', function () { overlay.remove(); });
  document.body.appendChild(overlay);
}
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  // Every image is an opaque PNG: a truncated or corrupt one decodes partly (its size is in the
  // header) and leaves its last rows transparent, so the last pixel must be opaque.
  var canvas = document.createElement('canvas');
  var context = canvas.getContext('2d', {willReadFrequently: true});
  function complete(i) {
    canvas.width = i.naturalWidth;
    canvas.height = i.naturalHeight;
    context.clearRect(0, 0, canvas.width, canvas.height);
    context.drawImage(i, 0, 0);
    return context.getImageData(canvas.width - 1, canvas.height - 1, 1, 1).data[3] === 255;
  }
  var bad = images.filter(function (i) {
    var r = i.getBoundingClientRect();
    return !(i.complete && i.naturalWidth > 0 && r.width > 0 && r.height > 0 && complete(i));
  }).map(function (i) { return i.alt; });
  document.body.setAttribute('data-selftest', JSON.stringify({
    images: images.length, plots: document.querySelectorAll('img.plot').length, grids: document.querySelectorAll('img.cell').length,
    bad: bad, errors: window.bounceErrors }));
});
"""


def floor_cell(row, metric):
    """The measured value with its floor beside it; a <span class="inside"> when within 2x of the floor."""
    value, floor = row.get(metric), row.get(f"{metric}_floor")
    text = fmt(value) + (f' <small>({fmt(floor, 2)})</small>' if floor is not None else "")
    return f'<span class="inside" title="within 2x the reference-noise floor">{text}</span>' if row.get(f"{metric}_insideFloor") else text


def img_tag(uri, alt, css_class, heat=None):
    extra = f' data-heat="{heat}"' if heat else ""
    click = ' onclick="bounceZoom(this)"' if css_class == "cell" else ""
    return f'<img class="{css_class}" src="{uri}" alt="{esc(alt)}"{extra}{click}>'


def table(headers, rows, name_columns=1):
    out = ["<table><tr>"]
    out += [f'<th class="{"name" if i < name_columns else ""}">{esc(h)}</th>' for i, h in enumerate(headers)]
    out.append("</tr>")
    for row in rows:
        out.append("<tr>" + "".join(f'<td class="{"name" if i < name_columns else ""}">{cell}</td>'
                                    for i, cell in enumerate(row)) + "</tr>")
    out.append("</table>")
    return "".join(out)


def main():
    if len(sys.argv) != 3:
        fail("usage: bounce-report.py RESULTS_DIR OUT.html")
    root, out_path = sys.argv[1], sys.argv[2]
    if not os.path.isdir(root):
        fail(f"{root}: not a folder")
    records, problems = load_records(root)
    if not records:
        fail(f"{root}: no job records (record.json) found: run `bounce sweep STUDY.json` first")
    by_kind = {"render": {}, "reference": {}, "compare": {}, "temporal": {}}
    for r in records:
        by_kind.setdefault(r.get("kind"), {})[r["job"]] = r
    renders, references, compares, temporals = (by_kind[k] for k in ("render", "reference", "compare", "temporal"))
    study_name = records[0].get("study", "study")
    study_copy = os.path.join(root, "study.json")
    expected_jobs = None
    if os.path.exists(study_copy):
        try:
            with open(study_copy, encoding="utf-8") as f:
                expected_jobs = [j["id"] for j in json.load(f).get("jobs", [])]
        except (OSError, ValueError, KeyError, TypeError):
            problems.append("study.json: unreadable")

    rows = build_rows(renders, compares, temporals, references)
    out_dir = os.path.dirname(os.path.abspath(out_path))
    outputs = [(os.path.join(out_dir, "results.json"), json.dumps(rows, indent=1) + "\n")]
    columns = []
    for row in rows:
        for k in row:
            if k not in columns:
                columns.append(k)
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: ("" if v is None else v) for k, v in row.items()})
    outputs.append((os.path.join(out_dir, "results.csv"), buffer.getvalue()))

    page = [f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>bounce study {esc(study_name)}</title>",
            f"<style>{CSS}</style><script>{SCRIPT}</script></head><body>"]
    page.append(f"<h1>Study <code>{esc(study_name)}</code></h1>")
    for line in machine_lines(records):
        page.append(f'<p class="machine">Machine: {esc(line)}</p>')
    finished = {r["job"] for r in records}
    counts = {k: len(v) for k, v in by_kind.items() if k in ("render", "reference", "compare", "temporal")}
    refused = sum(1 for r in records if r.get("status") != "ok")
    summary = ", ".join(f"{n} {k}" for k, n in counts.items())
    page.append(f"<p>{len(records)} finished jobs ({summary}); {refused} refused or skipped.")
    if expected_jobs is not None:
        missing = [j for j in expected_jobs if j not in finished]
        page.append(f" {len(missing)} of {len(expected_jobs)} jobs of the study have no record yet"
                    + (f" (first: <code>{esc(missing[0])}</code>)" if missing else "") + ".")
    page.append(" Results as <a href=\"results.json\">results.json</a> and <a href=\"results.csv\">results.csv</a>.</p>")
    if problems:
        page.append("<p>Unreadable records: " + esc("; ".join(problems)) + "</p>")
    compared = [r for r in rows if r.get("relMse") is not None]
    if compared:
        inside = [r for r in compared if inside_any(r)]
        spp = sorted({r.get("reference_spp") for r in compared if r.get("reference_spp") is not None})
        page.append(f'<p class="floor">Reference noise: {len(inside)} of {len(compared)} comparisons are within 2x the '
                    f"reference-noise floor on relMSE, relRMS or LDR-FLIP (references at {', '.join(map(str, spp))} spp); "
                    "those are drawn hollow and grey in the plots and their table cells grey. docs/metrics.md "
                    '"Reference noise floor" defines the floors.</p>')
    page.append('<button type="button" aria-pressed="false" onclick="bounceToggleHeat(this)">show FLIP heat maps</button>'
                " Click an image to zoom; the heat map replaces each technique's compared component.")

    scenes = sorted({r["scene"] for r in rows})
    for scene in scenes:
        scene_rows = [r for r in rows if r["scene"] == scene]
        page.append(f"<h2>Scene <code>{esc(scene)}</code></h2>")
        measured = [r for r in scene_rows if r.get("relMse") is not None]
        if measured:
            page.append(img_tag(scatter_plot(scene, measured), f"{scene} error vs time", "plot"))
        grid = []
        for r in scene_rows:
            job = f"render/{scene}/{r['technique']}/{r['variant']}"
            render = renders[job]
            compare = compares.get(f"compare/{scene}/{r['technique']}/{r['variant']}", {})
            name = f"<b>{esc(r['technique'])}</b><br>{esc(r['variant'])}"
            if render.get("status") != "ok":
                grid.append([name] + [f'<div class="refused">refused: {esc(render.get("reason", ""))}</div>'] + [""] * 3)
                continue
            heat = None
            if compare.get("status") == "ok":
                heat = data_uri(os.path.join(compare["_folder"], compare.get("heatmap", {}).get("path", "heatmap.png")))
            cells = [name]
            for c in COMPONENTS:
                uri = data_uri(os.path.join(render["_folder"], (render.get("images") or {}).get(c, c + ".png")))
                if uri is None:
                    cells.append("missing")
                    continue
                compared = c == r.get("scopeComponent")
                cells.append(img_tag(uri, f"{scene} {r['technique']} {r['variant']} {c}", "cell",
                                     heat if compared else None) + (" <i>compared</i>" if compared else ""))
            ref = references.get(compare.get("reference", ""))
            ref_uri = data_uri(os.path.join(ref["_folder"], "image.png")) if ref else None
            cells.append(img_tag(ref_uri, f"{scene} reference {split_id(ref['job'])[2]}", "cell") +
                         f"<br>{esc(split_id(ref['job'])[2])}, {fmt((ref.get('result') or {}).get('samplesPerPixel'))} spp"
                         if ref_uri else "no reference yet")
            grid.append(cells)
        page.append('<table class="grid"><tr><th class="name">technique / variant</th>' +
                    "".join(f"<th>{c}</th>" for c in COMPONENTS) + "<th>reference (its scope)</th></tr>")
        for cells in grid:
            page.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
        page.append("</table>")

        measured = [r for r in scene_rows if r.get("relMse") is not None]
        if measured:
            inside = [r for r in measured if inside_any(r)]
            page.append(f'<p class="floor">{len(inside)} of {len(measured)} comparisons have an error within 2x the '
                        "reference-noise floor on relMSE, relRMS or LDR-FLIP (grey cells, what an exact image would "
                        "score against the same reference beside each value): their ranking there is the reference's "
                        "noise.</p>")
            page.append(table(["technique", "variant", "frame ms", "relMSE (floor)", "relMSE bias-corrected", "relRMS (floor)",
                               "SSIM", "FLIP LDR (floor)", "FLIP HDR", "PSNR", "reference noise / pixel"],
                              [[esc(r["technique"]), esc(r["variant"]), fmt(r.get("frame_ms")), floor_cell(r, "relMse"),
                                fmt(r.get("relMseCorrected")), floor_cell(r, "relRms"), fmt(r.get("ssim")),
                                floor_cell(r, "flipLdr"), fmt(r.get("flipHdr")), fmt(r.get("psnr")),
                                fmt(r.get("reference_noise"))] for r in measured], 2))

        leaks = [r for r in scene_rows if r.get("leak_test") is not None or r.get("leak_full") is not None]
        if leaks:
            page.append("<h3>Light leak (dark room / lit room mean luminance; truth 0)</h3>")
            page.append(table(["technique", "variant", "leak (full)", "leak (compared component)", "reference's leak"],
                              [[esc(r["technique"]), esc(r["variant"]), fmt(r.get("leak_full")), fmt(r.get("leak_test")),
                                fmt(r.get("leak_reference"))] for r in leaks], 2))

        scene_temporal = {k: v for k, v in temporals.items() if split_id(k)[1] == scene and v.get("status") == "ok"}
        if scene_temporal:
            page.append("<h3>Temporal</h3>")
            page.append(img_tag(temporal_plot(scene, scene_temporal), f"{scene} temporal", "plot"))
            page.append(table(["technique", "variant", "flicker", "reference flicker", "convergence latency (frames after the event)",
                               "settled", "event frame", "animation"],
                              [[esc(split_id(k)[2]), esc(split_id(k)[3]), fmt(t.get("flicker")), fmt(t.get("referenceFlicker")),
                                fmt((t.get("convergence") or {}).get("latencyFrames")),
                                fmt((t.get("convergence") or {}).get("settled")),
                                fmt((t.get("convergence") or {}).get("eventFrame")),
                                esc(str((t.get("convergence") or {}).get("animation", "play")))] for k, t in sorted(scene_temporal.items())], 2))

        page.append("<h3>Per-pass GPU times (median ms) and counters (last frame)</h3>")
        for technique in sorted({r["technique"] for r in scene_rows if r["status"] == "ok"}):
            trs = [r for r in scene_rows if r["technique"] == technique and r["status"] == "ok"]
            passes = sorted({k for r in trs for k in r if k.startswith("pass_")})
            counters = sorted({k for r in trs for k in r if k.startswith("counter_")})
            headers = ["variant", "frame"] + [p[5:-3] for p in passes] + [c[8:] for c in counters]
            page.append(f"<h4><code>{esc(technique)}</code></h4>")
            page.append(table(headers, [[esc(r["variant"]), fmt(r.get("frame_ms"))] + [fmt(r.get(p)) for p in passes] +
                                        [fmt(r.get(c)) for c in counters] for r in trs]))
    page.append("<p class=\"machine\">Generated by <code>bounce report</code>; metric definitions: docs/metrics.md.</p>")
    page.append("</body></html>\n")
    outputs.append((out_path, "".join(page)))
    write_all(outputs)  # the page and its two tables together, or none of them
    print(os.path.abspath(out_path))


if __name__ == "__main__":
    try:
        main()
    except SystemExit:
        raise
    except Exception as e:  # one line, as every bounce error
        fail(f"{type(e).__name__}: {e}")
