#!/usr/bin/env python3
"""Render efficiency of two eyeadapt binaries on one scene (run via render-efficiency.sh).

Reference: each binary renders --ref-spp/2 samples per pixel (seeds 1001 and 1002); the
reference is their mean, and the two halves' channel means are printed as a bias check (an
unbiased change leaves them equal within noise). The reference's own noise (half the RMS
difference of the halves, the standard error of their mean) is printed beside the RMSEs and
subtracted from every MSE.

For each spp, --seeds renders per binary (seeds 1, 2, ...), alternating between the binaries so
that load on the machine hits both alike. Time is the "seconds" of `eyeadapt render
--stats-json` (rendering only); RMSE is over the linear RGB of raw.exr, averaged as MSE over
the seeds; eff = 1/(RMSE²·seconds) with the median seconds.
"""
import argparse
import json
import os
import statistics
import subprocess

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def read_rgb(path):
    bmp = mi.Bitmap(path)
    arr = np.array(bmp, copy=False)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    return arr[..., [names.index(c) for c in ("R", "G", "B")]].astype(np.float64)


def render(binary, scene, spp, seed, out):
    subprocess.run([binary, "render", scene, "--spp", str(spp), "--seed", str(seed), "--out", out,
                    "--stats-json", out + ".json"], check=True, capture_output=True)
    return read_rgb(os.path.join(out, "raw.exr")), json.load(open(out + ".json"))["seconds"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--scene", default=os.path.join(REPO, "scenes/three-rooms/scene.toml"))
    p.add_argument("--spp", default="16,64")
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--ref-spp", type=int, default=2048)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    bins = {"before": a.before, "after": a.after}
    halves = {}
    for k, (name, b) in enumerate(bins.items()):
        halves[name], _ = render(b, a.scene, a.ref_spp // 2, 1001 + k, os.path.join(a.work, f"ref-{name}"))
    ref = (halves["before"] + halves["after"]) / 2
    ref_mse = float(np.mean((halves["before"] - halves["after"]) ** 2)) / 4
    print(f"Scene {os.path.relpath(a.scene, REPO)}; reference: {a.ref_spp // 2} spp from each binary, "
          f"own noise RMSE {ref_mse ** 0.5:.5f} (subtracted). {a.seeds} seeds per spp, alternating.")
    for name in bins:
        m = halves[name].reshape(-1, 3).mean(0)
        print(f"  bias check, channel means of {name:6}'s half: R {m[0]:.5f} G {m[1]:.5f} B {m[2]:.5f}")
    print(f"\n{'binary':8} {'spp':>4} {'seconds':>8} {'RMSE':>9} {'eff':>9}")
    rows = {}
    for spp in [int(x) for x in a.spp.split(",")]:
        res = {name: ([], []) for name in bins}
        for seed in range(1, a.seeds + 1):
            for name, b in bins.items():
                img, t = render(b, a.scene, spp, seed, os.path.join(a.work, f"{name}-{spp}-{seed}"))
                res[name][0].append(float(np.mean((img - ref) ** 2)))
                res[name][1].append(t)
        for name in bins:
            mse = max(statistics.mean(res[name][0]) - ref_mse, 1e-30)
            t = statistics.median(res[name][1])
            rows[(name, spp)] = (t, mse ** 0.5, 1 / (mse * t))
            print(f"{name:8} {spp:>4} {t:>8.3f} {mse ** 0.5:>9.5f} {1 / (mse * t):>9.1f}")
    print("\nafter / before:")
    for spp in sorted({s for _, s in rows}):
        (tb, rb, eb), (ta, ra, ea) = rows[("before", spp)], rows[("after", spp)]
        print(f"  {spp:>4} spp: seconds {ta / tb:.3f}, RMSE {ra / rb:.3f}, efficiency {ea / eb:.2f}")


if __name__ == "__main__":
    main()
