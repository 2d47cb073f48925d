#!/usr/bin/env python3
"""Runs every in-scope scene of a mitsuba-data checkout through eyeadapt (see mitsuba-data.sh).

A scene is every *.xml under docs/scenes, tests/scenes and scenes that no other file includes
and that is not in a `fragments/` or `include/` folder: those are fragments, not scenes (two of
them, scenes/cbox/fragments/bsdfs-white.xml and
tests/scenes/participating_media/include/preamble.xml, are included by no scene, but hold only
BSDFs or settings; counting them, as the issue's "114" did, gives two scenes more that can
never render). It is out of scope when it or a file it
includes, transitively, uses a plugin of polarisation, participating media, curves, SDF
grids, hair or measured BSDFs (OUT_OF_SCOPE). Each in-scope scene is rendered once, tiny, with
the $parameters Mitsuba's own harnesses give it (scene_params: `spp`, and for test scenes the
`integrator` their name ends with), as `-D name=value`;
"loads" means eyeadapt did not reject it as bad input (exit 2), "renders" that it exited 0.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOTS = ["docs/scenes", "tests/scenes", "scenes"]
# Plugin types (the `type` attribute) and element names that put a scene out of scope.
OUT_OF_SCOPE = {
    "polarisation": {"pplastic", "polarizer", "measured_polarized", "stokes"},
    "participating media": {"homogeneous", "heterogeneous", "volpath", "volpathmis", "<medium"},
    "curves": {"bsplinecurve", "linearcurve"},
    "SDF grid": {"sdfgrid"},
    "hair": {"hair"},
    "measured BSDF": {"measured"},
}
INCLUDE = re.compile(r'<include\s+filename="([^"]+)"')
TYPE = re.compile(r'type="([^"$]+)"')


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def includes(path):
    base = os.path.dirname(path)
    return [os.path.normpath(os.path.join(base, f)) for f in INCLUDE.findall(read(path))]


def plugins(path, seen=None):
    """Plugin types and <medium> elements of `path` and of everything it includes."""
    seen = set() if seen is None else seen
    if path in seen or not os.path.exists(path):
        return set()
    seen.add(path)
    text = read(path)
    out = set(TYPE.findall(text))
    if "<medium" in text:
        out.add("<medium")
    for inc in includes(path):
        out |= plugins(inc, seen)
    return out


def scenes(root):
    files = []
    for r in ROOTS:
        for dirpath, _, names in os.walk(os.path.join(root, r)):
            files += [os.path.join(dirpath, n) for n in names if n.endswith(".xml")]
    files.sort()
    included = {inc for f in files for inc in includes(f)}
    top = [
        f for f in files
        if f not in included and not {"fragments", "include"} & set(f.split(os.sep))
    ]
    return top, len(files) - len(top)


def out_of_scope(path):
    found = plugins(path)
    return [why for why, names in OUT_OF_SCOPE.items() if found & names]


def first_error(stderr, root):
    """The first located error; "the scene is empty" only when nothing else is wrong (it is
    the consequence of shapes that failed, and is reported at the file's start)."""
    errors = [l.replace(root.rstrip("/") + "/", "").removeprefix("eyeadapt: error: ")
              for l in stderr.splitlines() if "error" in l]
    for line in errors:
        if "the scene is empty" not in line:
            return line
    if errors:
        return errors[0]
    lines = [l for l in stderr.splitlines() if l.strip()]
    return lines[-1] if lines else ""


def scene_params(root, scene, spp):
    """The $parameters Mitsuba's own harnesses give a scene: its test suite
    (src/render/tests/test_renders.py) loads each tests/scenes file with `spp` and with
    `integrator` = the file name's last `_` part (test_spot_direct.xml: direct); its
    documentation renderer (docs/scenes/render_documentation_images.py) loads every docs
    scene with `spp`. Parameters a scene does not use change nothing."""
    params = {"spp": str(spp)}
    rel = os.path.relpath(scene, root)
    if rel.startswith("tests" + os.sep):
        params["integrator"] = os.path.splitext(os.path.basename(scene))[0].rsplit("_", 1)[-1]
    return params


def define_args(params):
    """`-D name=value` for each parameter, as `mitsuba -D` takes them."""
    return [a for k, v in params.items() for a in ("-D", f"{k}={v}")]


def run(binary, scene, args, tmp, root):
    out = os.path.join(tmp, "out")
    cmd = [binary, "render", scene, "--spp", str(args.spp), "--width", str(args.size),
           "--height", str(args.size), "--threads", "1", "--out", out]
    cmd += define_args(scene_params(root, scene, args.spp))
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        return None, f"timed out after {args.timeout} s"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir", help="a mitsuba-data checkout")
    ap.add_argument("--eyeadapt", required=True)
    ap.add_argument("--spp", type=int, default=1)
    ap.add_argument("--size", type=int, default=16)
    ap.add_argument("--timeout", type=int, default=300)
    ap.add_argument("--list", action="store_true", help="only list the in-scope scenes")
    args = ap.parse_args()
    root = os.path.abspath(args.dir)
    found, fragments = scenes(root)
    in_scope, skipped = [], []
    for s in found:
        why = out_of_scope(s)
        (skipped if why else in_scope).append((s, why))
    print(f"{len(found)} top-level scenes ({fragments} fragments not counted), "
          f"{len(skipped)} out of scope, {len(in_scope)} in scope")
    if args.list:
        for s, _ in in_scope:
            print(os.path.relpath(s, root))
        for s, why in skipped:
            print(f"out of scope ({', '.join(why)}): {os.path.relpath(s, root)}")
        return 0
    loads = renders = 0
    print()
    print("| scene | loads | renders | first error |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for s, _ in in_scope:
            code, stderr = run(args.eyeadapt, s, args, tmp, root)
            loaded = code is not None and code != 2
            rendered = code == 0
            loads += loaded
            renders += rendered
            err = "" if rendered else first_error(stderr, root).replace("|", "\\|")
            print(f"| {os.path.relpath(s, root)} | {'yes' if loaded else 'no'} | "
                  f"{'yes' if rendered else 'no'} | {err} |", flush=True)
    print()
    print(f"totals: {loads}/{len(in_scope)} load, {renders}/{len(in_scope)} render")
    return 0


if __name__ == "__main__":
    sys.exit(main())
