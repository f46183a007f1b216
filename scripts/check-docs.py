#!/usr/bin/env python3
"""The technique doc pages agree with the code's settings (ctest docs_settings; docs/architecture.md).

Usage: check-docs.py BOUNCE [ROOT]

`bounce list --techniques` prints every technique's settings as the code declares them
(visitSettings). For each technique, its doc page (docs/techniques/<name>.md; the four radiosity
methods share radiosity.md) must
  - name every setting the technique declares (as a word, e.g. `maxLights` or maxLights=256), and
  - name only settings that exist where it writes them qualified: `technique.setting` for a registered
    technique (iir.maxLights, rsm-splat.radius), `renderer.NAME` or `viewer.NAME`.
The qualified names are checked in every page under docs/ and in README.md, since any of them may
quote another technique's settings; a qualified name the code writes as a string literal (a GL
object's label, a debug view), a view of a technique's debugView setting, a placeholder (NAME) and
NOT_SETTINGS's entries are something else. The essays that open the technique sources
(src/techniques/*/*Technique.{cpp,h}) may name settings as `name` or name=value: each must be a
setting of some technique and the value one it accepts. Exits 1 and lists every disagreement; prints nothing else but a
one-line summary when all agree. Needs no GPU: `bounce list` opens no context.
"""
import os
import re
import subprocess
import sys

# The pages of techniques that share one (the radiosity methods' base and machinery are one folder).
SHARED_PAGES = {"radiosity-gather": "radiosity", "radiosity-pr": "radiosity",
                "radiosity-incremental": "radiosity", "radiosity-cross": "radiosity"}


# Qualified names the docs use for something else, with what they are.
NOT_SETTINGS = {
    "renderer.shadingKernel": "the reference's run-record field (reference/ReferenceJob.cpp), docs/reference.md",
    "rsm.vplgrid": "docs/scene.md's example of a misspelt setting that a scene file is refused for",
}


def declared_settings(bounce):
    """{technique: [setting, ...]} plus {"renderer": [...], "viewer": [...]} from `bounce list`, and the
    values of choice settings {(technique, setting): [value, ...]}."""
    out = subprocess.run([bounce, "list"], capture_output=True, text=True, check=True).stdout
    settings, choices, current = {}, {}, None
    for line in out.splitlines():
        tech = re.match(r"^  (\S+) +\S", line)  # "  iir              incremental instant ..."
        setting = re.match(r"^    (\S+)\s+(int|float|bool|choice|text)\s+default\s+\S+\s+\[([^\]]*)\]", line)
        if line.startswith("renderer settings"):
            current = "renderer"
            settings[current] = []
        elif line.startswith("viewer settings"):
            current = "viewer"
            settings[current] = []
        elif line and not line.startswith(" "):
            current = None if not line.startswith("techniques") else current
        elif setting and current:
            name = setting.group(1)
            if setting.group(2) == "choice":
                choices[(current, name)] = setting.group(3).split("|")
            settings[current].append(name.split(".", 1)[1] if current in ("renderer", "viewer") else name)
        elif tech and not line.startswith("    "):
            current = tech.group(1)
            settings[current] = []
    return settings, choices


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    bounce = sys.argv[1]
    root = sys.argv[2] if len(sys.argv) == 3 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    names = subprocess.run([bounce, "list", "--techniques", "--names"], capture_output=True, text=True, check=True).stdout.split()
    settings, choices = declared_settings(bounce)
    problems = []
    missing = [t for t in names if t not in settings]
    if missing or "renderer" not in settings:
        print(f"check-docs.py: could not read the settings of {missing or ['renderer']} from `bounce list` (format changed?)",
              file=sys.stderr)
        return 1

    # Every declared setting is named on its technique's page.
    for tech in names:
        page = os.path.join(root, "docs", "techniques", SHARED_PAGES.get(tech, tech) + ".md")
        if not os.path.exists(page):
            problems.append(f"{tech}: no doc page {os.path.relpath(page, root)}")
            continue
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for s in settings[tech]:
            if not re.search(r"(?<![\w.-])" + re.escape(s) + r"(?![\w-])", text):
                problems.append(f"{os.path.relpath(page, root)}: does not name {tech}'s setting {s}")

    # Every qualified `technique.setting` (or renderer./viewer.) named in the docs exists.
    known = set(names) | {"renderer", "viewer"}
    pattern = re.compile(r"(?<![\w./-])(" + "|".join(sorted((re.escape(k) for k in known), key=len, reverse=True))
                         + r")\.([A-Za-z][A-Za-z0-9]*)\b")
    pages = [os.path.join(root, "README.md")]
    for folder, _, files in os.walk(os.path.join(root, "docs")):
        pages += [os.path.join(folder, f) for f in files if f.endswith(".md")]
    # The code's string literals: a qualified name the code writes as a literal ("iir.vpls", the label of a
    # buffer; "rsm.flux", a debug view; "hisr.tree.depth{}") names that, not a setting.
    literals = ""
    for folder, _, files in os.walk(os.path.join(root, "src")):
        for f in files:
            if f.endswith((".cpp", ".h")):
                with open(os.path.join(folder, f), encoding="utf-8") as src:
                    literals += "\n".join(re.findall(r'"[^"\n]*', src.read()))
    for page in sorted(pages):
        with open(page, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                for m in pattern.finditer(line):
                    owner, name = m.group(1), m.group(2)
                    if name in ("md", "json", "exr", "png", "cpp", "h", "glsl", "frag", "comp", "vert", "py"):
                        continue  # a file name (iir.md), not a setting
                    if name.isupper() or f'"{owner}.{name}' in literals:
                        continue  # a placeholder (renderer.NAME), or a GL object's label or a debug view's name
                    if name in choices.get((owner, "debugView"), []):
                        continue  # a debug view the technique's debugView setting selects (vct.occupancy)
                    if f"{owner}.{name}" in NOT_SETTINGS:
                        continue
                    if name not in settings[owner]:
                        problems.append(f"{os.path.relpath(page, root)}:{number}: {owner}.{name} is not a setting of {owner}")

    # The essays that open the technique sources (src/techniques/*/*Technique.{cpp,h}) name settings as
    # `name` or name=value: each is a setting some technique declares (an essay may quote another
    # technique's, as multires-splat quotes `rsm glossy=true`), a value one of its choices.
    all_settings = {}
    for tech in names:
        for name in settings[tech]:
            all_settings.setdefault(name, []).append(tech)
    def accepts(name, value):
        for tech in all_settings.get(name, []):
            values = choices.get((tech, name))
            if values is None or value in values:
                return True
        return False
    essays = 0
    for folder, _, files in sorted(os.walk(os.path.join(root, "src", "techniques"))):
        for f in sorted(files):
            if not re.match(r"\w+Technique\.(cpp|h)$", f):
                continue
            path = os.path.join(folder, f)
            essay = []
            with open(path, encoding="utf-8") as src:
                for line in src:
                    if not line.startswith("//") and line.strip() not in ("", "#pragma once"):
                        break
                    essay.append(line)
            essays += 1
            text = "".join(essay)
            where = os.path.relpath(path, root)
            for m in re.finditer(r"(?<![\w.-])([a-z][A-Za-z0-9]*)=([A-Za-z0-9][\w.-]*)", text):
                if m.group(1) not in all_settings:
                    problems.append(f"{where}: essay names {m.group(0)}, but no technique has a setting {m.group(1)}")
                elif not accepts(m.group(1), m.group(2).rstrip(".")):
                    problems.append(f"{where}: essay names {m.group(0)}, a value {m.group(1)} does not take")
            for m in re.finditer(r"`([a-z][A-Za-z0-9]*)`", text):
                if m.group(1) not in all_settings and m.group(1) not in names:
                    problems.append(f"{where}: essay names `{m.group(1)}`, neither a technique nor a setting")

    for p in problems:
        print(p)
    print(f"check-docs.py: {len(names)} techniques, {sum(len(settings[t]) for t in names)} settings, "
          f"{len(pages)} pages, {essays} essays: {len(problems)} disagreement(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
