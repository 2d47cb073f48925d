#!/usr/bin/env python3
"""Path guiding's efficiency: `eyeadapt render --guiding on` against `--guiding off` (run via
guiding.sh).

Reference per scene: two unguided renders of --ref-spp/2 samples per pixel (seeds 1001, 1002);
their mean is the reference, and its own noise (the standard error of that mean, from the two
halves) is subtracted from every MSE. Guided renders converge to the same image (the bias check
prints the mean of each setting's renders against the reference's).

For each spp, --seeds renders per setting (seeds 1, 2, ...), alternating off and on so that load
on the shared machine hits both alike. Two times are reported: "wall", the `seconds` of
`--stats-json` (rendering only), and "cpu", the user+system time of the whole process
(getrusage of the child), which load from other processes disturbs far less on a shared machine.
MSE is over linear RGB, averaged over the seeds; relMSE divides each pixel's squared error by
(reference luminance² + 0.01). eff = 1/(MSE·t); the ratio on/off is the gain (> 1: guiding pays).
"""
import argparse
import json
import os
import resource
import subprocess

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def read_rgb(path):
    bmp = mi.Bitmap(path)
    arr = np.array(bmp, copy=False)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    return arr[..., [names.index(c) for c in ("R", "G", "B")]].astype(np.float64)


def render(binary, scene, size, spp, seed, guiding, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "render", scene, "--spp", str(spp), "--seed", str(seed), "--width", str(size[0]),
                    "--height", str(size[1]), "--guiding", guiding, "--out", out,
                    "--stats-json", out + ".json"], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return read_rgb(os.path.join(out, "raw.exr")), json.load(open(out + ".json"))["seconds"], cpu


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("binary")
    p.add_argument("--scene", required=True)
    p.add_argument("--size", default="160x90")
    p.add_argument("--spp", default="16,64,256")
    p.add_argument("--seeds", type=int, default=2)
    p.add_argument("--ref-spp", type=int, default=2048)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    size = tuple(int(v) for v in a.size.split("x"))
    halves = [render(a.binary, a.scene, size, a.ref_spp // 2, 1001 + k, "off", os.path.join(a.work, f"ref{k}"))[0]
              for k in range(2)]
    ref = (halves[0] + halves[1]) / 2
    ref_mse = float(np.mean((halves[0] - halves[1]) ** 2)) / 4
    lum = ref.mean(axis=2)
    ref_rel = float(np.mean(((halves[0] - halves[1]) ** 2).mean(axis=2) / (lum ** 2 + 0.01))) / 4
    print(f"Scene {a.scene} at {size[0]}x{size[1]}; reference: 2 x {a.ref_spp // 2} spp unguided, own noise "
          f"RMSE {ref_mse ** 0.5:.5f} (subtracted), mean {ref.mean():.5f}. {a.seeds} seeds per spp, alternating.")
    print(f"{'spp':>5} {'guiding':>7} {'RMSE':>9} {'relMSE':>9} {'wall s':>7} {'cpu s':>7} "
          f"{'eff(cpu)':>10} {'gain cpu':>8} {'gain wall':>9} {'gain spp':>8} {'mean':>8}")
    for spp in [int(s) for s in a.spp.split(",")]:
        acc = {g: {"mse": [], "rel": [], "wall": [], "cpu": [], "mean": []} for g in ("off", "on")}
        for seed in range(1, a.seeds + 1):
            for g in ("off", "on"):
                img, wall, cpu = render(a.binary, a.scene, size, spp, seed, g, os.path.join(a.work, f"{g}-{spp}-{seed}"))
                d2 = (img - ref) ** 2
                acc[g]["mse"].append(float(np.mean(d2)))
                acc[g]["rel"].append(float(np.mean(d2.mean(axis=2) / (lum ** 2 + 0.01))))
                acc[g]["wall"].append(wall)
                acc[g]["cpu"].append(cpu)
                acc[g]["mean"].append(float(img.mean()))
        res = {}
        for g in ("off", "on"):
            mse = max(np.mean(acc[g]["mse"]) - ref_mse, 1e-30)
            rel = max(np.mean(acc[g]["rel"]) - ref_rel, 1e-30)
            res[g] = (mse, rel, float(np.median(acc[g]["wall"])), float(np.median(acc[g]["cpu"])),
                      float(np.mean(acc[g]["mean"])))
        for g in ("off", "on"):
            mse, rel, wall, cpu, mean = res[g]
            gains = ""
            if g == "on":
                m0, r0, w0, c0, _ = res["off"]
                gains = f"{(m0 * c0) / (mse * cpu):>8.2f} {(m0 * w0) / (mse * wall):>9.2f} {m0 / mse:>8.2f}"
            print(f"{spp:>5} {g:>7} {mse ** 0.5:>9.5f} {rel:>9.5f} {wall:>7.2f} {cpu:>7.2f} "
                  f"{1 / (mse * cpu):>10.1f} {gains:>27} {mean:>8.5f}")


if __name__ == "__main__":
    main()
