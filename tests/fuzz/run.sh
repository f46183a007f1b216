#!/usr/bin/env bash
# One bounded libFuzzer run (ctest fuzz_NAME; docs/reliability.md "Fuzzing"):
#   run.sh TARGET_BINARY NAME SECONDS WORK
# Replays tests/fuzz/corpus/NAME and tests/fuzz/regressions/NAME, then fuzzes for SECONDS from a fixed
# seed (BOUNCE_FUZZ_SEED, default 1) and an empty WORK/corpus: libFuzzer's inputs are then a function of
# the binary, the committed corpus and the seed, and time only decides how far along that sequence a
# run gets: a run that was clean for 240 s here is clean for 60 s on CI unless bounce changed
# (docs/reliability.md "Fuzzing"). Set
# BOUNCE_FUZZ_SEED=0 for a random seed (libFuzzer prints the one it took) to explore further. A crash, an
# abort (BOUNCE_CHECK, a sanitizer report, an invariant of the target), a leak, an input slower than
# 10 s or a process above 2 GB fails the run; the input is saved under WORK/artifacts and the message
# says how to keep it as a regression.
set -euo pipefail
binary=$1 name=$2 seconds=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
seed=${BOUNCE_FUZZ_SEED:-1}
rm -rf "$work/corpus" "$work/artifacts"
mkdir -p "$work/corpus" "$work/artifacts"
seeds=("$here/corpus/$name")
# Regression inputs are kept as real files (.ply, .exr: the unit tests and `bounce` read them by their
# names); the model and image targets take the format from a first byte, so they get a copy with the
# byte their extension stands for.
if [[ -d $here/regressions/$name ]]; then
  case $name in
    model|image)
      rm -rf "$work/regressions" && mkdir -p "$work/regressions"
      for f in "$here/regressions/$name"/*; do
        case ${f##*.} in obj|exr) b=0 ;; ply|png) b=1 ;; gltf) b=2 ;; glb) b=3 ;; *) continue ;; esac
        { printf '%s' "$b"; cat "$f"; } >"$work/regressions/$(basename "$f").in"
      done
      seeds+=("$work/regressions") ;;
    *) seeds+=("$here/regressions/$name") ;;
  esac
fi
# -close_fd_mask=1: the targets' standard output (compare's JSON) is not the fuzzer's; standard error
# stays open for the sanitizers' reports (the targets keep their own error lines off it); -timeout: assimp once hung on a PLY header (tests/fuzz/regressions/model); -rss_limit_mb:
# the image size limit (core/Image.h) keeps valid inputs far below it.
set +e
"$binary" "$work/corpus" "${seeds[@]}" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 \
  -close_fd_mask=1 -artifact_prefix="$work/artifacts/" -print_final_stats=1 2>"$work/log.txt"
status=$?
set -e
tail -n 25 "$work/log.txt"
if [[ $status -ne 0 ]]; then
  echo "fuzz_$name: libFuzzer exited with $status; the input is in $work/artifacts/:" >&2
  ls -l "$work/artifacts" >&2
  echo "keep it: copy it to tests/fuzz/regressions/$name/ with a name saying what it broke, fix bounce, and add a test" \
       "to tests/unit/FuzzRegressionTest.cpp (docs/reliability.md \"Fuzzing\")" >&2
  exit 1
fi
