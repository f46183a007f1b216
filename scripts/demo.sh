#!/usr/bin/env bash
# Renders every built-in scene with every registered technique into OUT (PNG, tone-mapped).
set -euo pipefail
bounce="$1"; out="$2"; size="$3"
mkdir -p "$out"
scenes=$("$bounce" list --scenes --names)
techniques=$("$bounce" list --techniques --names)
for s in $scenes; do
  for t in $techniques; do
    "$bounce" render --scene "$s" --technique "$t" --size "$size" --frames 1 \
      --out "$out/$s-$t.png" --stats "$out/$s-$t.json"
  done
done
echo "demo: images are in $(cd "$out" && pwd)/ ($(ls "$out"/*.png | wc -l) PNG files, run records beside them)"
