#!/usr/bin/env python3
"""Converts the scanned statue of paper case 4 (docs/paper.md, "Case 4"): called by
statue-mesh.sh, which fetches it. Usage: statue_mesh.py IN.off OUT.obj

The input is CGAL's `data/meshes/ChineseDragon-10kv.off` (a scan of a seated Chinese guardian
lion statue, 10 000 vertices, 19 994 triangles, y up, facing +z). It is
- decimated to 4 000 triangles with fast-simplification 0.2.0 (quadric error metric);
- scaled to 0.70 m high, its base on the pedestal's top (y = 0.5 m), its bounding box centred
  on the pedestal (x = 0, z = -1.0 m);
- written as OBJ with 4 decimals (0.1 mm).
Then it prints the red spot's design, computed from the converted mesh and the pedestal: the
aim (the statue's bounding-box centre) and the widest cone (in 0.5 degree steps) all of whose
rays, from the spot at (1.5, 1.7, 0), hit the statue first.
"""
import math
import sys

import fast_simplification
import numpy as np

HEIGHT = 0.70
BASE_Y = 0.5
CENTRE_XZ = (0.0, -1.0)
TRIANGLES = 4000
SPOT = np.array([1.5, 1.7, 0.0])
PEDESTAL = (np.array([-0.4, 0.0, -1.35]), np.array([0.4, 0.5, -0.65]))


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


def hits(o, d, tri):
    """Möller-Trumbore against every triangle: the nearest t, or inf."""
    v0, v1, v2 = tri[:, 0], tri[:, 1], tri[:, 2]
    e1, e2 = v1 - v0, v2 - v0
    p = np.cross(d, e2)
    det = (e1 * p).sum(1)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = o - v0
    u = (s * p).sum(1) * inv
    q = np.cross(s, e1)
    w = (q * d).sum(1) * inv
    t = (e2 * q).sum(1) * inv
    good = ok & (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 1e-6)
    return t[good].min() if good.any() else math.inf


def box_t(o, d, lo, hi):
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - o) / d, (hi - o) / d
    tn, tf = np.nanmax(np.minimum(t1, t2)), np.nanmin(np.maximum(t1, t2))
    return tn if tf >= max(tn, 0) and tn > 0 else math.inf


def spot_design(v, f):
    tri = v[f]
    lo, hi = v.min(axis=0), v.max(axis=0)
    aim = (lo + hi) / 2
    axis = (aim - SPOT) / np.linalg.norm(aim - SPOT)
    a = np.cross(axis, [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(axis, a)
    fit = 0.0
    for k in range(1, 61):
        th = math.radians(0.5 * k)
        ring_ok = True
        for j in range(72):
            ph = 2 * math.pi * j / 72
            d = math.cos(th) * axis + math.sin(th) * (math.cos(ph) * a + math.sin(ph) * b)
            ts = hits(SPOT, d, tri)
            if not (ts < box_t(SPOT, d, *PEDESTAL) and ts < math.inf):
                ring_ok = False
                break
        if not ring_ok:
            break
        fit = 0.5 * k
    return aim, fit, np.linalg.norm(aim - SPOT)


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
    # The spot's design from the mesh as written (rounded coordinates).
    vr = np.round(vs, 4)
    aim, fit, dist = spot_design(vr, fs)
    print(f"spot aim (bounding-box centre) {aim.round(4)}, {dist:.3f} m from the spot")
    print(f"widest cone whose every ray hits the statue first: half-angle {fit} deg")


if __name__ == "__main__":
    main()
