#!/usr/bin/env python3
"""eyeadapt against Mitsuba 3 (llvm_ad_rgb) on scenes of a mitsuba-data checkout: do they agree?

Run through vs-mitsuba-data.sh. Each scene is rendered at a small size (--size wide, the
scene's aspect ratio) by
  Mitsuba   as two independent halves A and B of --ref-spp each (the reference is their mean);
  eyeadapt  as two independent renders of --spp each (seeds 1 and 2; their mean is compared).
Both use the scene's own integrator settings. Per scene it prints the channel means of both,
their relative difference in percent, and the per-pixel RMS difference of the two means
divided by the RMS of their combined noise (estimated from each renderer's two halves): 1.0
means the difference is noise alone.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from vs_mitsuba import read_exr_rgb  # noqa: E402
from mitsuba_data import define_args, scene_params  # noqa: E402


def mitsuba_halves(path, size, spp, params):
    import mitsuba as mi

    scene = mi.load_file(path, **params)
    params = mi.traverse(scene)
    key = next(k for k in params.keys() if k.endswith("film.size"))
    w0, h0 = params[key]
    h = max(1, round(size * h0 / w0))
    params[key] = [size, h]
    params[key.replace("film.size", "film.crop_size")] = [size, h]
    params.update()
    halves = [np.array(mi.render(scene, spp=spp, seed=s), dtype=np.float64)[..., :3] for s in (11, 12)]
    return halves, (size, h)


def eyeadapt_halves(binary, path, wh, spp, tmp, params):
    out = []
    for seed in (1, 2):
        d = os.path.join(tmp, f"ea{seed}")
        subprocess.run(
            [binary, "render", path, "--spp", str(spp), "--seed", str(seed), "--width", str(wh[0]),
             "--height", str(wh[1]), "--out", d] + define_args(params),
            check=True, capture_output=True)
        out.append(read_exr_rgb(os.path.join(d, "raw.exr")).astype(np.float64))
    return out


def compare(e, m):
    """(means e, means m, relative difference %, noise ratio)."""
    em, mm = (e[0] + e[1]) / 2, (m[0] + m[1]) / 2
    var = ((e[0] - e[1]) ** 2).mean() / 4 + ((m[0] - m[1]) ** 2).mean() / 4
    ratio = float(np.sqrt(((em - mm) ** 2).mean() / var)) if var > 0 else float("nan")
    me, mmi = em.reshape(-1, 3).mean(0), mm.reshape(-1, 3).mean(0)
    rel = 100 * (me - mmi) / np.where(mmi != 0, mmi, 1)
    return me, mmi, rel, ratio


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--eyeadapt", required=True)
    ap.add_argument("--scenes", required=True, help="comma-separated paths relative to DIR")
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--ref-spp", type=int, default=1024)
    args = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    print(f"Mitsuba {mi.__version__} llvm_ad_rgb, 2 × {args.ref_spp} spp; eyeadapt 2 × {args.spp} spp; "
          f"{args.size} px wide")
    print()
    print("| scene | size | eyeadapt mean RGB | Mitsuba mean RGB | difference % (R, G, B) | pixel diff / noise |")
    print("|---|---|---|---|---|---|")
    for rel_path in args.scenes.split(","):
        path = os.path.join(args.dir, rel_path)
        try:
            # The parameters Mitsuba's harnesses give the scene (both renderers get the same;
            # `spp` only matters where the file's sampler reads it: the spp given here rule).
            m, wh = mitsuba_halves(path, args.size, args.ref_spp,
                                   scene_params(args.dir, path, args.ref_spp))
            with tempfile.TemporaryDirectory() as tmp:
                e = eyeadapt_halves(args.eyeadapt, path, wh, args.spp, tmp,
                                    scene_params(args.dir, path, args.spp))
        except Exception as ex:  # one scene's failure is a row, not the end of the table
            print(f"| {rel_path} | | failed: {str(ex).splitlines()[0][:120]} | | | |", flush=True)
            continue
        me, mm, rel, ratio = compare(e, m)
        f3 = lambda v, fmt: ", ".join(fmt.format(x) for x in v)  # noqa: E731
        print(f"| {rel_path} | {wh[0]}×{wh[1]} | {f3(me, '{:.4f}')} | {f3(mm, '{:.4f}')} | "
              f"{f3(rel, '{:+.2f}')} | {ratio:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
