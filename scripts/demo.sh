#!/usr/bin/env bash
# Renders every built-in scene with every registered technique into OUT (PNG, tone-mapped).
# A technique that cannot shade a scene refuses it with a one-line error and exit status 1 (hemicube
# radiosity refuses textured area lights): that pair is listed as skipped. Any
# other failure (a crash, an abort) stops the demo.
set -euo pipefail
bounce="$1"; out="$2"; size="$3"
mkdir -p "$out"
scenes=$("$bounce" list --scenes --names)
techniques=$("$bounce" list --techniques --names)
skipped=0
# The rendering part aims at about 3 minutes on 2 llvmpipe cores (issue 30). The radiosity methods'
# cost is their element count and hemicubes, not the image: here they run with coarse elements (0.2 m;
# the automatic size gives the Cornell boxes 0.044 m) and 32^2 hemicubes; on furnished-room the shooting
# methods keep their automatic size (0.29 m there: 1,774 elements, about 2 s a pair); not on atrium and
# courtyard (the one-frame solution without a time budget is about a minute there); and the gather, the
# expensive reference (one hemicube per element and bounce; two-rooms 33 s, furnished-room 180 s
# here), on the two Cornell boxes of the thesis's kind only. `bounce render` runs any pair on request.
radiosity_demo=(--set elementSize=0.2 --set dynamicElementSize=0.2 --set hemicubeSize=32)
start=$(date +%s)
# Each pair's wall milliseconds (render or refusal), for bench/demo/run.py's record.
times="$out/demo-times.tsv"
printf 'scene\ttechnique\tstatus\tms\n' > "$times"
for s in $scenes; do
  for t in $techniques; do
    extra=()
    case "$t" in
      radiosity-*)
        extra=("${radiosity_demo[@]}")
        case "$t:$s" in
          radiosity-gather:cornell-box-area|radiosity-gather:cornell-box) ;;
          radiosity-gather:*|*:atrium|*:courtyard)
            echo "demo: skipped $s x $t: too many elements for the demo's time on llvmpipe"
            printf '%s\t%s\tskipped\t0\n' "$s" "$t" >> "$times"
            skipped=$((skipped + 1))
            continue ;;
          *:furnished-room) extra=() ;;
        esac
        # One frame is shown: the shooting methods without their time budget per frame, so the image is
        # the maxIterations-bounded solution (as before the budget), not the first 1.2 s of it.
        [ "$t" = radiosity-gather ] || extra+=(--set frameBudgetMs=0) ;;
    esac
    status=0
    pair_start=$(date +%s%N)
    message=$("$bounce" render --scene "$s" --technique "$t" --size "$size" --frames 1 "${extra[@]}" \
      --out "$out/$s-$t.png" --stats "$out/$s-$t.json" 2>&1) || status=$?
    printf '%s\t%s\t%s\t%s\n' "$s" "$t" "$status" "$(( ($(date +%s%N) - pair_start) / 1000000 ))" >> "$times"
    if [ "$status" -eq 1 ]; then
      echo "demo: skipped $s x $t: $message"
      skipped=$((skipped + 1))
    elif [ "$status" -ne 0 ]; then
      echo "$message" >&2
      echo "demo: $s x $t failed with status $status" >&2
      exit "$status"
    elif [ -n "$message" ]; then
      echo "$message"
    fi
  done
done
echo "demo: images are in $(cd "$out" && pwd)/ ($(ls "$out"/*.png | wc -l) PNG files, run records beside them; $skipped pairs skipped; $(( $(date +%s) - start )) s)"

# bench/demo/run.py --render-only times the rendering part alone.
if [ -n "${BOUNCE_DEMO_RENDER_ONLY:-}" ]; then exit 0; fi

# A small built-in study (scripts/demo-study.json, docs/studies.md): every technique with two settings
# on three scenes at 64x64, compared with shared references, temporal metrics, then the report page.
# About three minutes on two cores (its references at 1024 spp, docs/studies.md "Reference noise in
# the demo study"); a rerun reuses the finished jobs.
study_out="$out/study"
"$bounce" sweep "$(dirname "$0")/demo-study.json" --out "$study_out" --jobs 2
report=$("$bounce" report "$study_out")
echo "demo: study report: $report (results.json and results.csv beside it)"
