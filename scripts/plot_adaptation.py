#!/usr/bin/env python3
"""Plot u'(t) and v'(t) of every estimator from an eyeadapt adaptation.csv.

Usage:  python3 scripts/plot_adaptation.py out/demo/adaptation.csv [-o uv.png] [--raw-only]
Needs:  pip install pandas matplotlib

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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", help="adaptation.csv of a sequence directory")
    ap.add_argument("-o", "--out", default="adaptation_uv.png", help="output image")
    ap.add_argument("--raw-only", action="store_true", help="leave out filtered rows (+)")
    a = ap.parse_args()

    df = pd.read_csv(a.csv)
    df = df[df["valid"] == 1]
    if a.raw_only:
        df = df[~df["estimator"].str.contains("+", regex=False)]

    fig, (ax_u, ax_v) = plt.subplots(2, 1, sharex=True, figsize=(10, 7))
    for name, g in df.groupby("estimator", sort=False):
        style = "--" if "+" in name else "-"
        width = 2.5 if name.split("+")[0] == "eye" else 1.2
        ax_u.plot(g["time_s"], g["u_prime"], style, lw=width, label=name)
        ax_v.plot(g["time_s"], g["v_prime"], style, lw=width, label=name)
    ax_u.set_ylabel("u' of the adaptation white")
    ax_v.set_ylabel("v' of the adaptation white")
    ax_v.set_xlabel("time (s)")
    ax_u.legend(fontsize=8, ncol=2, loc="best")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
