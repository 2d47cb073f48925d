#!/usr/bin/env python3
"""An instanced scene for the build-time benchmark: DIR/instanced.xml and four PLY meshes.

    python3 scripts/bench/make_instanced_meshes.py DIR [--segments 720,640,560,480]

make_big_mesh.py's room with, instead of its one displaced sphere, one such sphere per
--segments value (720, 640, 560, 480: 516 960 + 408 320 + 312 480 + 229 440 triangles), each
a Mitsuba `shapegroup` placed twice by `instance` shapes, scaled to 0.35: a two-level scene
(each mesh gets its own BVH, built once however often it is placed) of 1.47 M distinct and
2.93 M placed triangles. Time the load with a tiny render, e.g.

    hyperfine -N "eyeadapt render DIR/instanced.xml --spp 1 --width 8 --height 8 --out /tmp/o"

and read the "BVH … triangles in … s" line of one render. Deterministic, like make_big_mesh.py;
needs numpy (the benchmark venv has it).
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--segments", default="720,640,560,480")
    a = ap.parse_args()
    sizes = [int(s) for s in a.segments.split(",")]
    os.makedirs(a.dir, exist_ok=True)
    for s in sizes:
        subprocess.run([sys.executable, os.path.join(HERE, "make_big_mesh.py"),
                        os.path.join(a.dir, f"m{s}"), "--segments", str(s)], check=True)
    room = open(os.path.join(a.dir, f"m{sizes[-1]}", "big-mesh.xml")).read()
    cut = room.index('  <shape type="ply">')
    parts = [room[:cut]]
    for k, s in enumerate(sizes):
        parts.append(f'  <shape type="shapegroup" id="g{s}">\n'
                     f'    <shape type="ply"><string name="filename" value="m{s}/big-mesh.ply"/>'
                     '<ref id="blob"/></shape>\n  </shape>\n')
        for z in (-0.6, 0.5):
            x = -0.8 + 0.5 * k
            parts.append(f'  <shape type="instance"><ref id="g{s}"/>\n'
                         '    <transform name="to_world"><translate y="-0.78"/><scale value="0.35"/>'
                         f'<translate x="{x}" y="0.3" z="{z}"/></transform>\n  </shape>\n')
    parts.append("</scene>\n")
    with open(os.path.join(a.dir, "instanced.xml"), "w") as f:
        f.write("".join(parts))
    print(f"wrote {a.dir}/instanced.xml ({len(sizes)} meshes, each placed twice)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
