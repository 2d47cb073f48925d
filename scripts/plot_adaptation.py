#!/usr/bin/env python3
"""Plot u'(t) and v'(t) of the adaptation white per estimator from an eyeadapt adaptation.csv.

Usage:  python3 scripts/plot_adaptation.py out/demo/adaptation.csv [-o uv.png]
                [--filtered [PRESET ...]] [--estimators eye,wcam,...]
Needs:  pip install pandas matplotlib

By default only the per-frame estimates are drawn (eye, wcam, ...). `--filtered` adds the
temporal-filtered copies that `eyeadapt report` appends (eye+fairchild, ...): all presets, or
only the ones named. A filtered series has its estimator's colour and the preset's line style.
The colours are the report's (report.html, plots/*.svg), so a figure made here matches it.

adaptation.csv has one row per (frame, estimator); the columns (estimators.md §0.2,
docs/report.md) are:

  frame, time_s          frame number and its time in seconds
  estimator              eye, eye_fov, wcam, ncns, dominant, grey_world, white_patch,
                         shades_of_grey, grey_edge; "<estimator>+<preset>" rows
                         (e.g. eye+fairchild) are temporal-filtered copies added by
                         `eyeadapt report`
  X, Y, Z                the adaptation white in CIE XYZ, normalised to Y = 1
  x, y                   CIE 1931 chromaticity
  u_prime, v_prime       CIE 1976 UCS chromaticity (what the coherence metrics use)
  cct_mccamy             McCamy CCT in K (empty when outside 1000-25000 K)
  r_lin, g_lin, b_lin    the white in linear sRGB (may be negative)
  std_err_u, std_err_v   Monte-Carlo standard error of u', v' (empty if unknown)
  n_samples              samples or pixels behind the estimate
  valid                  1 if the white is defined; 0 rows have NaN chromaticity
  flags                  ';'-separated notes (held_d65, reconstruction, undefined_input...)
  abs_Y                  the estimate's absolute luminance before normalising (NaN when
                         it has none, e.g. filtered rows)
  cam_x, cam_y, cam_z    camera position

Undefined values are written as NaN, which pandas reads as missing.
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import pandas as pd

# One colour per estimator, the same as the report's (a test in the report crate checks that
# this table matches it). The eye sensor is always black and drawn thickest.
PALETTE = {
    "eye": "#000000",
    "eye_fov": "#7f7f7f",
    "wcam": "#e15759",
    "ncns": "#4e79a7",
    "dominant": "#b07aa1",
    "grey_world": "#59a14f",
    "white_patch": "#f28e2b",
    "shades_of_grey": "#76b7b2",
    "grey_edge": "#9c755f",
}

# Line style of each temporal-filter preset, as in the report: fairchild dashed, artistic
# dotted, rinner long dashes; per-frame estimates are solid.
FILTER_STYLE = {"fairchild": "--", "artistic": ":", "rinner": (0, (6, 2))}


def colour_of(base):
    """The estimator's colour; any other name gets a stable colour from its bytes, as in the
    report."""
    if base in PALETTE:
        return PALETTE[base]
    h = 7
    for b in base.encode():
        h = (h * 31 + b) & 0xFFFFFFFF
    return "#%02x%02x%02x" % (h % 200, (h // 200) % 200, (h // 40000) % 200)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", help="adaptation.csv of a sequence directory")
    ap.add_argument("-o", "--out", default="adaptation_uv.png", help="output image")
    ap.add_argument(
        "--filtered",
        nargs="*",
        metavar="PRESET",
        help="also draw the temporal-filtered series (all presets, or the ones named)",
    )
    ap.add_argument(
        "--estimators",
        help="comma-separated estimators to draw (default: every one in the file)",
    )
    a = ap.parse_args()

    df = pd.read_csv(a.csv)
    df = df[df["valid"] == 1]
    parts = df["estimator"].str.split("+", n=1, expand=True).reindex(columns=[0, 1])
    df = df.assign(base=parts[0], preset=parts[1])
    if a.filtered is None:
        df = df[df["preset"].isna()]
    elif a.filtered:
        df = df[df["preset"].isna() | df["preset"].isin(a.filtered)]
    if a.estimators:
        df = df[df["base"].isin(a.estimators.split(","))]
    if df.empty:
        ap.error("no defined rows to plot with these options")

    fig, (ax_u, ax_v) = plt.subplots(
        2, 1, sharex=True, figsize=(11, 7), layout="constrained"
    )
    for name, g in df.groupby("estimator", sort=False):
        base, preset = g["base"].iloc[0], g["preset"].iloc[0]
        style = "-" if pd.isna(preset) else FILTER_STYLE.get(preset, "--")
        width = 2.6 if base == "eye" else 1.3
        # Break the line at undefined frames and gaps instead of joining across them.
        g = g.set_index("frame").reindex(range(g["frame"].min(), g["frame"].max() + 1))
        for ax, col in ((ax_u, "u_prime"), (ax_v, "v_prime")):
            ax.plot(
                g["time_s"].interpolate(),
                g[col],
                style,
                color=colour_of(base),
                lw=width,
                label=name,
                zorder=3 if base == "eye" else 2,
            )
    ax_u.set_ylabel("u′ of the adaptation white")
    ax_v.set_ylabel("v′ of the adaptation white")
    ax_v.set_xlabel("time (s)")
    for ax in (ax_u, ax_v):
        ax.grid(color="#e6e6e6", lw=0.8)
    ax_u.set_title("Adaptation white per estimator (CIE 1976 u′v′)")
    # The legend sits outside the axes, to the right, so it never covers a line.
    handles, labels = ax_u.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside right upper", fontsize=9, title="estimator")
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
