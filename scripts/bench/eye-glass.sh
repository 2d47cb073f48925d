#!/usr/bin/env bash
# The eye sensor behind glass (issue 19): its reading against an independent estimate (a cube
# map of camera renders from the eye, integrated with the (1 + cos θ)/4 kernel, plus the delta
# lights' terms in closed form) on three scenes under a sky map: the sun seen directly past a
# glass sphere, the sun through a window pane, an area lamp and a point light behind a pane.
# The same checks as crates/tracer/tests/eye_glass.rs, with the note's budgets (2^21 eye paths,
# 6 × 96² px × 256 spp cube maps); prints one line per check (xy of both, Δxy, Y ratio).
# Takes a few minutes on 2 cores.
#
#   scripts/bench/eye-glass.sh
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$REPO"
EYE_GLASS_FULL=1 cargo test --release -p eyeadapt-tracer --test eye_glass -- --nocapture \
    --test-threads 1 2>&1 | grep -E "Δxy|test result|panicked"
