#!/usr/bin/env bash
# Same bits whatever the node's C library: runs scripts/same-output.sh with BINARY on this
# machine's glibc against the same BINARY on another Debian release's glibc (its libc6 package,
# downloaded from Debian's archive into target/glibc/SUITE and checked against the archive's
# index). A render farm mixes nodes of different releases; glibc 2.41 (Debian 13) replaced
# several f32 functions of 2.36 (Debian 12), which moved eyeadapt's bits until it stopped
# calling the C library's math (clippy.toml forbids it; crates/tracer/src/trig.rs).
#
#   scripts/glibc-determinism.sh BINARY [SUITE...]     (default suites: bookworm trixie)
#
# Exits 0 when every file is identical under every suite's glibc, 1 when one differs, 2 on
# bad arguments, 3 when a package cannot be fetched.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if [[ $# -lt 1 || ! -x $1 ]]; then
    echo "usage: $0 BINARY [SUITE...]  (BINARY must be an executable eyeadapt)" >&2
    exit 2
fi
bin=$(realpath "$1")
shift
suites=("$@")
[[ ${#suites[@]} -gt 0 ]] || suites=(bookworm trixie)
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
libgcc=$(ldd "$bin" | awk '/libgcc_s/ {print $3}')

# Unpacks SUITE's libc6 into target/glibc/SUITE (once) and prints that directory.
fetch_glibc() {
    local suite=$1 dir=target/glibc/$1
    if [[ ! -f $dir/unpacked ]]; then
        mkdir -p "$dir"
        curl -fsS -m 120 -o "$dir/Packages.gz" "$mirror/dists/$suite/main/binary-amd64/Packages.gz" || return 3
        local entry file sum
        entry=$(gzip -dc "$dir/Packages.gz" | awk '/^Package: libc6$/ {p = 1} p && /^$/ {exit} p')
        file=$(awk '/^Filename:/ {print $2}' <<<"$entry")
        sum=$(awk '/^SHA256:/ {print $2}' <<<"$entry")
        [[ -n $file && -n $sum ]] || { echo "no libc6 in $suite's index" >&2; return 3; }
        curl -fsS -m 300 -o "$dir/libc6.deb" "$mirror/$file" || return 3
        echo "$sum  $dir/libc6.deb" | sha256sum -c --quiet - || return 3
        rm -rf "$dir/root"
        dpkg-deb -x "$dir/libc6.deb" "$dir/root"
        # Debian 12 ships /lib/x86_64-linux-gnu, 13 /usr/lib/x86_64-linux-gnu.
        local libc
        libc=$(find "$dir/root" -name libc.so.6 -path '*x86_64-linux-gnu*' | head -1)
        [[ -n $libc ]] || { echo "no libc.so.6 in $suite's libc6" >&2; return 3; }
        # The binary also links libgcc_s (unwinding), which libc6 does not ship.
        cp "$libgcc" "$(dirname "$libc")/"
        dirname "$libc" >"$dir/unpacked"
    fi
    echo "$dir"
}

status=0
for suite in "${suites[@]}"; do
    dir=$(fetch_glibc "$suite") || { echo "cannot fetch $suite's libc6 from $mirror" >&2; exit 3; }
    dir=$(realpath "$dir")
    lib=$(realpath "$(cat "$dir/unpacked")")
    wrapper=$dir/eyeadapt
    printf '#!/bin/sh\nexec %q --library-path %q %q "$@"\n' "$lib/ld-linux-x86-64.so.2" "$lib" "$bin" >"$wrapper"
    chmod +x "$wrapper"
    version=$("$lib/ld-linux-x86-64.so.2" --version | head -1)
    echo "==> this machine's $(ldd --version | head -1) against $suite: $version"
    if ! bash scripts/same-output.sh "$bin" "$wrapper" "$dir/work"; then
        status=1
    fi
done
exit $status
