#!/usr/bin/env python3
"""Does the built-in three-rooms scene's bench show a highlight? (issue 22's audit; docs/paper.md,
"The audit's numbers"). Per frame: the brightest bench pixel's luminance against the image's
99th-percentile luminance (pixels that see no emitter), as `eyeadapt paper` measures case 6.

  python bench-highlight.py NORMAL_DIR MASK_DIR

NORMAL_DIR: `eyeadapt sequence` output of the scene; MASK_DIR: the same job over a copy of the
scene whose bench is diffuse with reflectance (0.123, 0.456, 0.789), which marks its pixels in
the albedo AOV (`bench-highlight.sh` makes both). Needs numpy and Mitsuba 3's Python package
(VENV=/work/venv/mitsuba) to read the EXRs.
"""
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
MARK = np.array([0.123, 0.456, 0.789])
Y = np.array([0.2126390058715103, 0.7151686787677559, 0.0721923153607337])


def channels(path):
    """Every channel group of the EXR, its channels in the order R, G, B (or emitter, hit)."""
    out = {}
    for name, c in mi.Bitmap(str(path)).split():
        names = [c.struct_()[i].name for i in range(c.channel_count())]
        a = np.array(c)
        order = [n for n in ("R", "G", "B", "emitter", "hit") if n in names]
        if order:
            out[name] = np.stack([a[..., names.index(n)] for n in order], axis=-1)
    return out


def main():
    normal, mask = Path(sys.argv[1]), Path(sys.argv[2])
    ratios = []
    for f in sorted((normal / "frames" / "raw").glob("*.exr")):
        n, m = channels(f), channels(mask / "frames" / "raw" / f.name)
        lum = n["<root>"][..., :3] @ Y
        no_emitter = n["mask"][..., 0] == 0
        bench = (np.abs(m["albedo"] - MARK) <= 0.03 * MARK).all(axis=-1) & no_emitter
        p99 = np.percentile(lum[no_emitter], 99)
        peak = lum[bench].max() if bench.any() else float("nan")
        ratios.append(peak / p99)
        print(f"{f.stem}: bench pixels {bench.sum():5d}, peak {peak:.4f}, p99 {p99:.4f}, ratio {peak / p99:.3f}")
    r = np.array(ratios)
    print(f"frames {len(r)}: peak / p99 from {np.nanmin(r):.3f} to {np.nanmax(r):.3f}")


if __name__ == "__main__":
    main()
