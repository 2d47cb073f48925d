#!/usr/bin/env python3
"""Writes the benchmark suite's ≥ 1 M-triangle scene: DIR/big-mesh.ply and DIR/big-mesh.xml.

    python3 scripts/bench/make_big_mesh.py DIR [--segments 1024]

A closed room (3 m × 2.5 m × 3 m: white walls, a red and a green one, a 0.8 m square ceiling
light) with a displaced sphere in the middle: a UV sphere of `segments` around and
segments/2 rings (1024: 1 046 528 triangles), its radius modulated by three octaves of
products of sines of the unit direction (no seam, no pole artefact), with area-weighted
vertex normals, as a binary little-endian PLY (x y z nx ny nz, triangle faces). Every
surface is two-sided diffuse (not rough plastic: eyeadapt's `roughplastic` renders 1-45 %
brighter than Mitsuba's for alpha 0.01-0.6, which would make the speed ratio meaningless). Both renderers read the same XML;
its sampler and film size are what suite.py replaces. Deterministic: the same bytes on
every run (numpy, no randomness). Needs numpy (the benchmark venv has it).
"""
import argparse
import os
import sys

import numpy as np

RADIUS = 0.6
CENTRE = (0.0, 0.78, 0.0)

XML = """<scene version="3.0.0">
  <!-- Written by scripts/bench/make_big_mesh.py (segments {segments}: {triangles} triangles) -->
  <integrator type="path"><integer name="max_depth" value="8"/><integer name="rr_depth" value="5"/></integrator>
  <sensor type="perspective">
    <string name="fov_axis" value="y"/>
    <float name="fov" value="55"/>
    <transform name="to_world"><lookat origin="0.35, 1.35, 1.4" target="0, 0.7, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="256"/><integer name="height" value="256"/>
      <rfilter type="box"/><string name="pixel_format" value="rgb"/></film>
  </sensor>
  <bsdf type="twosided" id="white"><bsdf type="diffuse"><rgb name="reflectance" value="0.75, 0.75, 0.72"/></bsdf></bsdf>
  <bsdf type="twosided" id="red"><bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.08, 0.06"/></bsdf></bsdf>
  <bsdf type="twosided" id="green"><bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.45, 0.12"/></bsdf></bsdf>
  <bsdf type="twosided" id="blob"><bsdf type="diffuse"><rgb name="reflectance" value="0.55, 0.35, 0.2"/></bsdf></bsdf>
{walls}  <shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="90"/><scale value="0.4"/><translate value="0, 2.49, 0"/></transform>
    <ref id="white"/>
    <emitter type="area"><rgb name="radiance" value="14, 12, 9"/></emitter>
  </shape>
  <shape type="ply">
    <string name="filename" value="big-mesh.ply"/>
    <ref id="blob"/>
  </shape>
</scene>
"""

# The room's six walls: (bsdf, to_world of the [-1, 1]² rectangle).
WALLS = [
    ("white", '<rotate x="1" angle="-90"/><scale x="1.5" y="1.5"/>'),  # floor, y = 0
    ("white", '<rotate x="1" angle="90"/><scale x="1.5" y="1.5"/><translate y="2.5"/>'),  # ceiling
    ("white", '<scale x="1.5" y="1.25"/><translate y="1.25" z="-1.5"/>'),  # back wall
    ("white", '<rotate y="1" angle="180"/><scale x="1.5" y="1.25"/><translate y="1.25" z="1.5"/>'),
    ("red", '<rotate y="1" angle="90"/><scale x="1.5" y="1.25"/><translate x="-1.5" y="1.25"/>'),
    ("green", '<rotate y="1" angle="-90"/><scale x="1.5" y="1.25"/><translate x="1.5" y="1.25"/>'),
]


def displacement(d):
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    return (0.08 * np.sin(7 * x + 2) * np.sin(6 * y) * np.sin(5 * z + 1)
            + 0.05 * np.sin(19 * x) * np.cos(17 * y + 1) * np.sin(23 * z)
            + 0.02 * np.sin(53 * x + 3 * y) * np.sin(47 * z - 2 * y))


def mesh(segments):
    """Vertices (float64 n×3) and triangles (int n×3) of the displaced UV sphere."""
    nu, nv = segments, segments // 2
    theta = np.pi * np.arange(1, nv) / nv
    phi = 2 * np.pi * np.arange(nu) / nu
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    ring = np.stack([st * np.cos(phi), np.broadcast_to(ct, (nv - 1, nu)), st * np.sin(phi)], -1)
    dirs = np.concatenate([[[0.0, 1.0, 0.0]], ring.reshape(-1, 3), [[0.0, -1.0, 0.0]]])
    verts = dirs * (RADIUS * (1 + displacement(dirs)))[:, None] + np.array(CENTRE)
    top, bottom = 0, len(dirs) - 1
    idx = lambda j, i: 1 + j * nu + (i % nu)  # noqa: E731  (ring j, segment i)
    i = np.arange(nu)
    # Counter-clockwise seen from outside (front side outwards).
    tris = [np.stack([np.full(nu, top), idx(0, i + 1), idx(0, i)], -1)]
    for j in range(nv - 2):
        a, b, c, d = idx(j, i), idx(j, i + 1), idx(j + 1, i + 1), idx(j + 1, i)
        tris += [np.stack([a, b, c], -1), np.stack([a, c, d], -1)]
    tris.append(np.stack([np.full(nu, bottom), idx(nv - 2, i), idx(nv - 2, i + 1)], -1))
    return verts, np.concatenate(tris)


def normals(verts, tris):
    p = verts[tris]
    fn = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])  # length = 2 × area: area-weighted
    n = np.zeros_like(verts)
    for k in range(3):
        np.add.at(n, tris[:, k], fn)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def write_ply(path, verts, nrm, tris):
    header = ("ply\nformat binary_little_endian 1.0\ncomment scripts/bench/make_big_mesh.py\n"
              f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n")
    v = np.concatenate([verts, nrm], 1).astype("<f4")
    f = np.zeros(len(tris), dtype=[("n", "u1"), ("i", "<i4", 3)])
    f["n"], f["i"] = 3, tris
    with open(path, "wb") as out:
        out.write(header.encode())
        out.write(v.tobytes())
        out.write(f.tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--segments", type=int, default=1024)
    a = ap.parse_args()
    if a.segments < 8 or a.segments % 2:
        ap.error("--segments must be an even number >= 8")
    os.makedirs(a.dir, exist_ok=True)
    verts, tris = mesh(a.segments)
    p = verts[tris]
    outward = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                        p.mean(1) - np.array(CENTRE)) > 0
    assert outward.mean() > 0.99, "triangle winding: the front side must face outwards"
    write_ply(os.path.join(a.dir, "big-mesh.ply"), verts, normals(verts, tris), tris)
    walls = "".join(f'  <shape type="rectangle">\n    <transform name="to_world">{t}</transform>\n'
                    f'    <ref id="{b}"/>\n  </shape>\n' for b, t in WALLS)
    with open(os.path.join(a.dir, "big-mesh.xml"), "w") as f:
        f.write(XML.format(segments=a.segments, triangles=len(tris), walls=walls))
    print(f"wrote {a.dir}/big-mesh.xml and big-mesh.ply ({len(tris)} triangles)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
