#!/usr/bin/env python3
"""Converts the scanned statue of paper case 4 (docs/paper.md, "Case 4"): called by
statue-mesh.sh, which fetches it. Usage: statue_mesh.py IN.off OUT.obj

The input is CGAL's `data/meshes/ChineseDragon-10kv.off` (a scan of a seated Chinese guardian
lion statue, 10 000 vertices, 19 994 triangles, y up, facing +z). It is
- decimated to 4 000 triangles with fast-simplification 0.2.0 (quadric error metric);
- scaled to 0.70 m high, its base on the pedestal's top (y = 0.5 m), its bounding box centred
  on the pedestal (x = 0, z = -1.0 m);
- written as OBJ with 4 decimals (0.1 mm).
statue-mesh.sh then runs spot_design.py, which designs the red spot from the written mesh.
"""
import sys

import fast_simplification
import numpy as np

HEIGHT = 0.70
BASE_Y = 0.5
CENTRE_XZ = (0.0, -1.0)
TRIANGLES = 4000


def read_off(path):
    toks = []
    for line in open(path):
        line = line.split("#")[0].strip()
        if line:
            toks += line.split()
    assert toks[0] == "OFF", path
    nv, nf = int(toks[1]), int(toks[2])
    i = 4
    v = np.array(toks[i : i + 3 * nv], dtype=np.float64).reshape(nv, 3)
    i += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(toks[i])
        idx = [int(x) for x in toks[i + 1 : i + 1 + n]]
        faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, n - 1)]
        i += 1 + n
    return v, np.array(faces, dtype=np.int64)


def place(v):
    lo, hi = v.min(axis=0), v.max(axis=0)
    s = HEIGHT / (hi[1] - lo[1])
    c = (lo + hi) / 2
    out = (v - c) * s
    out[:, 1] = (v[:, 1] - lo[1]) * s + BASE_Y
    out[:, 0] += CENTRE_XZ[0]
    out[:, 2] += CENTRE_XZ[1]
    return out


def main():
    src, dst = sys.argv[1], sys.argv[2]
    v, f = read_off(src)
    vs, fs = fast_simplification.simplify(
        v.astype(np.float32), f.astype(np.int32), target_reduction=1 - TRIANGLES / len(f)
    )
    vs = place(vs.astype(np.float64))
    with open(dst, "w") as o:
        o.write(
            "# Paper case 4's statue: a scanned Chinese guardian lion (CGAL's data/meshes/\n"
            "# ChineseDragon-10kv.off, Debian package libcgal-demo 5.5.1-2; CC0 1.0 per CGAL's\n"
            "# LICENSE for files without a copyright notice). Decimated, scaled and placed by\n"
            "# scripts/paper/statue-mesh.sh; docs/paper.md has the provenance.\n"
        )
        o.write(f"# {len(vs)} vertices, {len(fs)} triangles, metres, y up, facing +z.\n")
        for p in vs:
            o.write("v {:.4f} {:.4f} {:.4f}\n".format(*p))
        for t in fs:
            o.write("f {} {} {}\n".format(*(t + 1)))
    lo, hi = vs.min(axis=0), vs.max(axis=0)
    print(f"{dst}: {len(vs)} vertices, {len(fs)} triangles, box {lo.round(4)} .. {hi.round(4)}")


if __name__ == "__main__":
    main()
