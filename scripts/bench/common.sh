# Shared by the benchmark scripts (sourced, not run): the eyeadapt binary, the Python venv and
# the Markdown sections of docs/benchmarks/*.md (BENCHMARKS.md is their index).

# Sets BIN to $1 if given, else builds the release binary of the repository $REPO.
eyeadapt_binary() {
    if [ -n "${1:-}" ]; then
        BIN="$1"
    else
        (cd "$REPO" && cargo build --release --bin eyeadapt >&2)
        BIN="$REPO/target/release/eyeadapt"
    fi
}

# append_markdown FILE TITLE COMMAND REPORT: appends REPORT (a file) as a dated section.
append_markdown() {
    local md="$1" title="$2" cmd="$3" report="$4"
    {
        echo
        echo "## $title, $(date -u '+%Y-%m-%d %H:%M') UTC, eyeadapt $(git -C "$REPO" rev-parse --short HEAD)"
        echo
        echo "\`$cmd\`, load average at the end $(cut -d' ' -f1-3 /proc/loadavg)"
        echo
        echo '```text'
        cat "$report"
        echo '```'
    } >>"$md"
    echo "appended to $md" >&2
}

# Sets VENV (default scripts/bench/.venv-bench, git-ignored) to a venv with mitsuba and numpy,
# creating it and pip-installing them when missing.
bench_venv() {
    VENV="${VENV:-$HERE/.venv-bench}"
    if [ ! -x "$VENV/bin/python" ]; then
        echo "creating $VENV" >&2
        python3 -m venv "$VENV"
    fi
    if ! "$VENV/bin/python" -c "import mitsuba, numpy" 2>/dev/null; then
        "$VENV/bin/pip" install --quiet mitsuba numpy
    fi
}
