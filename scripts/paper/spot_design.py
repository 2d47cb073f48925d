#!/usr/bin/env python3
"""Paper case 4's red spot, designed from the committed statue mesh (docs/paper.md, "Case 4").

  python spot_design.py [paper/scenes/meshes/guardian-lion.obj]      (needs numpy)

The spot stands in front of the statue, in the camera's vertical plane (x = 0), 45 degrees
above the horizontal through the statue's bounding-box centre and 2 m from it, aimed at that
centre: a key light on the side the camera sees. Printed: its position; the widest cone (in
0.5 degree steps) every ray of which (72 azimuths per ring) meets the statue before anything
else, the pedestal included; and, for the study's cones (1, 0.8 and 0.6 times that one), the
share of the statue's pixels the spot lights directly (centre rays at the study's 96 x 72;
`crates/paper/src/cases/design.rs` checks the same with the renderer's geometry).
"""
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
PEDESTAL = (np.array([-0.4, 0.0, -1.35]), np.array([0.4, 0.5, -0.65]))
CAMERA, LOOK_AT, FOV_DEG, SIZE = np.array([0.0, 1.3, 1.8]), np.array([0.0, 0.9, -1.0]), 40.0, (96, 72)
DISTANCE, ELEVATION_DEG = 2.0, 45.0


def read_obj(path):
    v, f = [], []
    for line in open(path):
        s = line.split()
        if s and s[0] == "v":
            v.append([float(x) for x in s[1:4]])
        elif s and s[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in s[1:4]])
    return np.array(v)[np.array(f)]


class Mesh:
    def __init__(self, tri):
        self.v0, self.e1, self.e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]

    def hit(self, o, d):
        """Möller-Trumbore against every triangle: the nearest t, or inf."""
        p = np.cross(d, self.e2)
        det = (self.e1 * p).sum(1)
        ok = np.abs(det) > 1e-12
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = o - self.v0
        u = (s * p).sum(1) * inv
        q = np.cross(s, self.e1)
        w = (q * d).sum(1) * inv
        t = (self.e2 * q).sum(1) * inv
        good = ok & (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 1e-6)
        return t[good].min() if good.any() else math.inf


def box_t(o, d, lo, hi):
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - o) / d, (hi - o) / d
    tn, tf = np.nanmax(np.minimum(t1, t2)), np.nanmin(np.maximum(t1, t2))
    return tn if tf >= max(tn, 0) and tn > 0 else math.inf


def widest_cone(mesh, spot, axis):
    a = np.cross(axis, [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(axis, a)
    fit = 0.0
    for k in range(1, 61):
        th = math.radians(0.5 * k)
        for j in range(72):
            ph = 2 * math.pi * j / 72
            d = math.cos(th) * axis + math.sin(th) * (math.cos(ph) * a + math.sin(ph) * b)
            ts = mesh.hit(spot, d)
            if not (ts < box_t(spot, d, *PEDESTAL) and ts < math.inf):
                return fit
        fit = 0.5 * k
    return fit


def lit_share(mesh, spot, axis, cone_deg):
    w, h = SIZE
    f = (LOOK_AT - CAMERA) / np.linalg.norm(LOOK_AT - CAMERA)
    r = np.cross(f, [0.0, 1.0, 0.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    th = math.tan(math.radians(FOV_DEG / 2))
    statue = lit = 0
    for y in range(h):
        for x in range(w):
            d = f + (2 * (x + 0.5) / w - 1) * th * w / h * r + (1 - 2 * (y + 0.5) / h) * th * u
            d /= np.linalg.norm(d)
            t = mesh.hit(CAMERA, d)
            if t == math.inf or t > box_t(CAMERA, d, *PEDESTAL):
                continue
            statue += 1
            to = CAMERA + t * d - spot
            dist = np.linalg.norm(to)
            dd = to / dist
            if dd @ axis < math.cos(math.radians(cone_deg)):
                continue
            if min(mesh.hit(spot, dd), box_t(spot, dd, *PEDESTAL)) >= dist - 0.01:
                lit += 1
    return statue, lit


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else ROOT / "paper/scenes/meshes/guardian-lion.obj"
    tri = read_obj(path)
    mesh = Mesh(tri)
    lo, hi = tri.reshape(-1, 3).min(0), tri.reshape(-1, 3).max(0)
    aim = (lo + hi) / 2
    e = math.radians(ELEVATION_DEG)
    spot = aim + DISTANCE * np.array([0.0, math.sin(e), math.cos(e)])
    axis = (aim - spot) / np.linalg.norm(aim - spot)
    print(f"statue box {lo.round(4)} .. {hi.round(4)}; aim (its centre) {aim.round(4)}")
    print(f"spot at {spot.round(4)}, {DISTANCE} m from the aim, {ELEVATION_DEG} deg above it")
    fit = widest_cone(mesh, spot, axis)
    print(f"widest cone whose every ray meets the statue first: half-angle {fit} deg")
    for c in (fit, 0.8 * fit, 0.6 * fit):
        n, k = lit_share(mesh, spot, axis, c)
        print(f"cone {c:.1f} deg: lights {k} of {n} statue pixels at {SIZE[0]} x {SIZE[1]} ({100 * k / n:.1f} %)")


if __name__ == "__main__":
    main()
