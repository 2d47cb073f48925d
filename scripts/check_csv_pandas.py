#!/usr/bin/env python3
"""Checks that adaptation.csv loads in pandas with the documented columns and dtypes.

Usage: check_csv_pandas.py PATH/adaptation.csv
"""
import sys

import pandas as pd

COLUMNS = {
    "frame": "int64", "time_s": "float64", "estimator": "object",
    "X": "float64", "Y": "float64", "Z": "float64", "x": "float64", "y": "float64",
    "u_prime": "float64", "v_prime": "float64", "cct_mccamy": "float64",
    "r_lin": "float64", "g_lin": "float64", "b_lin": "float64",
    "std_err_u": "float64", "std_err_v": "float64", "n_samples": "int64", "valid": "int64",
    "flags": "object", "abs_Y": "float64", "cam_x": "float64", "cam_y": "float64", "cam_z": "float64",
}


def main(path):
    df = pd.read_csv(path)
    assert list(df.columns) == list(COLUMNS), f"columns {list(df.columns)}"
    for col, dtype in COLUMNS.items():
        got = str(df[col].dtype)
        # Text columns are `object` before pandas 3 and `str` from 3 on; an all-empty
        # column (e.g. flags with no flag set) reads as float64 NaN.
        text = got in ("object", "str", "string")
        ok = got == dtype or (dtype == "object" and (text or df[col].isna().all()))
        assert ok, f"{col}: dtype {got}, expected {dtype}"
    valid = df[df.valid == 1]
    assert (abs(valid.Y - 1.0) < 1e-9).all(), "XYZ must be normalised to Y = 1"
    assert valid.u_prime.between(0, 0.7).all() and valid.v_prime.between(0, 0.7).all()
    per_frame = df.groupby("frame").estimator.nunique()
    assert per_frame.nunique() == 1, "every frame has the same estimators"
    eye = df[df.estimator == "eye"]
    assert eye.std_err_u.notna().all(), "the eye sensor reports its standard error"
    print(f"adaptation.csv OK in pandas {pd.__version__}: {len(df)} rows, "
          f"{df.frame.nunique()} frames, estimators {sorted(df.estimator.unique())}")


if __name__ == "__main__":
    main(sys.argv[1])
