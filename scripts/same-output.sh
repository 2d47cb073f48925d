#!/usr/bin/env bash
# Byte-for-byte comparison of two eyeadapt binaries on the three commands that share the frame
# pipeline: the demo's first frames (`sequence`), a still with every estimator (`render`) and
# `paper --quick`; then two chunks merged and reported, and `plan`. Both binaries run on this machine, so CPU-dependent bits (libm, FMA) cancel
# out; a difference is a change of behaviour.
#
#   scripts/same-output.sh OLD_BINARY NEW_BINARY [WORK_DIR]
#
# Prints one line per differing file and exits 1 when any differs (0 when all are identical).
# Run by hand before and after a refactoring; it takes about a minute on 2 busy cores.
set -euo pipefail
if [[ $# -lt 2 ]]; then
    echo "usage: $0 OLD_BINARY NEW_BINARY [WORK_DIR]" >&2
    exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
work=${3:-$(mktemp -d)}
mkdir -p "$work"

run() {
    local bin=$1 out=$2
    rm -rf "$out"
    mkdir -p "$out"
    "$bin" sequence --frames 0-2 --width 64 --height 36 --spp 4 --eye-samples 512 \
        --out "$out/sequence" --no-progress-bar >"$out/sequence.log" 2>&1
    "$bin" render builtin:cornell-box --width 48 --height 48 --spp 8 --estimators all \
        --eye-samples 512 --out "$out/render" >"$out/render.log" 2>&1
    # The interior: its sky and sun take the environment's and the sphere's sampling paths.
    "$bin" render builtin:interior --width 48 --height 27 --spp 8 --estimators all \
        --eye-samples 512 --out "$out/interior" >"$out/interior.log" 2>&1
    "$bin" paper --quick --out "$out/paper" --work "$out/paper-work" >"$out/paper.log" 2>&1
    # Two chunks of the same frames, merged and reported; the plan of a chunked run.
    for i in 0 1; do
        "$bin" sequence --frames 0-3 --chunk-size 2 --chunk-index "$i" --width 32 --height 18 \
            --spp 2 --eye-samples 128 --out "$out/chunks/$i" --no-progress-bar >"$out/chunk.log" 2>&1
    done
    "$bin" merge "$out/chunks/0" "$out/chunks/1" --frames 0-3 --out "$out/merged" >"$out/merge.log" 2>&1
    "$bin" report "$out/merged" >"$out/report.log" 2>&1
    "$bin" plan --frames 0-3 --chunk-size 3 >"$out/plan.txt" 2>&1
    # Logs hold timings; only the files the commands wrote are compared.
    rm "$out"/*.log
}

run "$old" "$work/old"
run "$new" "$work/new"
status=0
while IFS= read -r rel; do
    if [[ ! -f "$work/new/$rel" ]]; then
        echo "only in old: $rel"
        status=1
    elif ! cmp -s "$work/old/$rel" "$work/new/$rel"; then
        echo "differs: $rel"
        status=1
    fi
done < <(cd "$work/old" && find . -type f ! -name '.eyeadapt.lock' | sort)
while IFS= read -r rel; do
    [[ -f "$work/old/$rel" ]] || { echo "only in new: $rel"; status=1; }
done < <(cd "$work/new" && find . -type f ! -name '.eyeadapt.lock' | sort)
n=$(cd "$work/old" && find . -type f ! -name '.eyeadapt.lock' | wc -l)
if [[ $status == 0 ]]; then
    echo "identical: $n files in $work"
fi
exit $status
