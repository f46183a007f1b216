#!/bin/bash
# Nichols (2010) R6 / Figs. 4.9 and 4.13 on cornell-box at 64^2: the million-VPL gather (rsm, every
# texel of a 1024^2 RSM), the million-VPL multiresolution gather (isr with the same 1M VPLs: eye-space
# clustering alone), and hisr (maxDepth x tau), isr light clusters (lightFinest) and the regular rsm
# gather against them. Writes EXRs and run records into OUT, then prints the table (analyze.py).
# Usage: bench/nichols-r6/run.sh [BOUNCE_BINARY] [OUT_DIR]   (about 8 minutes on llvmpipe, 2 cores)
set -euo pipefail
B=${1:-build/src/app/bounce}
OUT=${2:-out/nichols-r6}
B=$(realpath "$B")
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
cd "$OUT"
R="$B render --scene cornell-box --size 64x64 --component indirect --set renderer.shadowMapSize=256"
$R --technique direct --out zero.exr --stats zero.json
$R --technique rsm --set rsmSize=1024 --set vplGrid=1024 --out full1m.exr --stats full1m.json
$R --technique isr --set vplMode=regular --set rsmSize=1024 --set vplGrid=1024 --out multires1m.exr --stats multires1m.json
for d in 1 2 3; do
  for t in 0.001 0.003 0.01 0.03 0.1 0.3; do
    $R --technique hisr --set maxDepth=$d --set tau=$t --out hisr_d${d}_t${t}.exr --stats hisr_d${d}_t${t}.json
  done
done
for f in 16 32 64 128 256; do
  $R --technique isr --set lightFinest=$f --out isr_f${f}.exr --stats isr_f${f}.json
done
for g in 16 32 64; do
  $R --technique rsm --set vplGrid=$g --out rsm_g${g}.exr --stats rsm_g${g}.json
done
python3 "$HERE/analyze.py" "$B" . full1m.exr multires1m.exr
