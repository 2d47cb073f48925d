"""Mitsuba 3's ray throughput (llvm_ad_rgb) on the mesh and ray sets of eyeadapt's
`bench --bvh-triangles N` (crates/cli/src/cmd_bench_bvh.rs): the same terrain of N triangles
(its `terrain` and `height`, vertex for vertex), and the same three ray sets, 2^20 rays each:
the 1024² pinhole camera's rays in row order, uniform rays from uniform points inside the
mesh's bounds, and 0.5-long shadow segments from 0.02 above uniform points of the terrain in
uniform directions (the camera set is the same rays; the two random sets are drawn from the
same distributions with numpy's generator). Closest hits are `ray_intersect_preliminary`
(distance and triangle, no surface interaction, as eyeadapt's query), shadow rays `ray_test`;
each set is traced once to compile its kernel, then timed five times (median).

Usage: python rays_mitsuba.py N   (run by scripts/bench/rays-vs-mitsuba.sh)
The last line, `mitsuba-rays: key=value ...`, is for the script."""
import statistics
import sys
import time

import numpy as np
import mitsuba as mi
import drjit as dr
mi.set_variant("llvm_ad_rgb")

if len(sys.argv) != 2 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 2:
    sys.exit("usage: rays_mitsuba.py TRIANGLES (an integer >= 2)")
n = int(sys.argv[1])

def height(x, z):
    return (0.15 * np.sin(3.1 * x + 0.7) * np.cos(2.3 * z) + 0.05 * np.sin(11.0 * x + 5.0 * z)
            + 0.02 * np.cos(37.0 * x - 23.0 * z)).astype(np.float32)

quads = max((n + 1) // 2, 1)
kx = max(int(round(quads ** 0.5)), 1)
kz = -(-quads // kx)
i, j = np.meshgrid(np.arange(kx + 1), np.arange(kz + 1), indexing="xy")
x = (-1.0 + 2.0 * i / kx).astype(np.float32); z = (-1.0 + 2.0 * j / kz).astype(np.float32)
verts = np.stack([x, height(x, z), z], -1).reshape(-1, 3).astype(np.float32)
idx = lambda a, b: b * (kx + 1) + a
faces = []
I, J = np.meshgrid(np.arange(kx), np.arange(kz), indexing="xy")
I = I.ravel(); J = J.ravel()
a, b, c, d = idx(I, J), idx(I + 1, J), idx(I + 1, J + 1), idx(I, J + 1)
f = np.empty((len(I) * 2, 3), np.uint32)
f[0::2] = np.stack([a, c, b], -1); f[1::2] = np.stack([a, d, c], -1)
f = f[:n]
mesh = mi.Mesh("terrain", len(verts), len(f))
params = mi.traverse(mesh)
params["vertex_positions"] = dr.ravel(mi.Point3f(verts[:, 0], verts[:, 1], verts[:, 2]))
params["faces"] = dr.ravel(mi.Vector3u(f[:, 0], f[:, 1], f[:, 2]))
params.update()
t0 = time.perf_counter()
scene = mi.load_dict({"type": "scene", "terrain": mesh})
print(f"mitsuba {mi.__version__}: {len(f)} triangles, scene build {time.perf_counter() - t0:.3f} s")
lo, hi = verts.min(0), verts.max(0)
R = 1 << 20
rng = np.random.default_rng(7)

def uniform_dirs(k):
    u, v = rng.random(k, np.float32), rng.random(k, np.float32)
    zz = 1 - 2 * u; s = np.sqrt(np.maximum(0, 1 - zz * zz)); phi = 2 * np.pi * v
    return np.stack([s * np.cos(phi), zz, s * np.sin(phi)], -1).astype(np.float32)

SIDE = 1024
eye = np.array([0.0, 1.4, 2.4], np.float32)
fwd = -eye / np.linalg.norm(eye); right = np.cross(fwd, [0, 1, 0]); right /= np.linalg.norm(right)
up = np.cross(right, fwd); half = np.tan(np.radians(15.0))
k = np.arange(R)
px = ((k % SIDE) + 0.5) / SIDE * 2 - 1; py = 1 - ((k // SIDE) + 0.5) / SIDE * 2
dprim = fwd + right * (px * half)[:, None] + up * (py * half)[:, None]
dprim = (dprim / np.linalg.norm(dprim, axis=1)[:, None]).astype(np.float32)
oprim = np.broadcast_to(eye, (R, 3)).astype(np.float32)
oin = (lo + (hi - lo) * rng.random((R, 3), np.float32)).astype(np.float32)
din = uniform_dirs(R)
xs, zs = rng.random(R, np.float32) * 2 - 1, rng.random(R, np.float32) * 2 - 1
osh = np.stack([xs, height(xs, zs) + 0.02, zs], -1).astype(np.float32)
dsh = uniform_dirs(R)

def ray(o, d, tmax=None):
    r = mi.Ray3f(mi.Point3f(o[:, 0], o[:, 1], o[:, 2]), mi.Vector3f(d[:, 0], d[:, 1], d[:, 2]))
    if tmax is not None:
        r.maxt = tmax
    return r

FIGURES = {}


def timed(name, fn, rays):
    out = fn(rays); dr.eval(out); dr.sync_thread()  # warm-up: kernel compilation
    ts = []
    for _ in range(5):
        t = time.perf_counter(); out = fn(rays); dr.eval(out); dr.sync_thread(); ts.append(time.perf_counter() - t)
    share = (np.array(out, dtype=bool).mean() if isinstance(out, mi.Bool) else np.isfinite(np.array(out)).mean())
    mrays = R / statistics.median(ts) / 1e6
    # eyeadapt reports the share of shadow rays that are unoccluded, and of the others that hit.
    pct = 100 * (1 - share if name == "shadow" else share)
    FIGURES[name] = (mrays, pct)
    print(f"{name}: {mrays:.2f} M rays/s (median of 5), {pct:.1f} % {'unoccluded' if name == 'shadow' else 'hit'}")

closest = lambda r: scene.ray_intersect_preliminary(r, coherent=False).t
timed("primary", closest, ray(oprim, dprim))
timed("inside", closest, ray(oin, din))
timed("shadow", lambda r: scene.ray_test(r), ray(osh, dsh, 0.5))
print("mitsuba-rays: triangles=%d version=%s " % (len(f), mi.__version__) + " ".join(
    f"{k}_mrays_per_s={v[0]:.3f} {k}_percent={v[1]:.2f}" for k, v in FIGURES.items()))
