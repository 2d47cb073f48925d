#!/usr/bin/env python3
"""Checks the eye sensor's standard error against the spread over independent seeds.

    python3 scripts/paper/eye-se-calibration.py [--bin target/release/eyeadapt] [--seeds 24]
        [--samples 16384] [--scenes builtin:cornell-green-floor,...]

For each scene, renders a tiny still with `--estimators eye` under seeds 0..K-1 and compares
the reported `std_err_u`, `std_err_v` (RMS over seeds) with the standard deviation of u', v'
across the seeds (the true error of one reading). Ratio reported / empirical: 1 is honest, > 1
overstates. The ratio's own uncertainty is about 1/sqrt(2(K-1)) from the empirical side.
"""
import argparse, csv, math, subprocess, tempfile
from pathlib import Path

p = argparse.ArgumentParser()
p.add_argument("--bin", default="target/release/eyeadapt")
p.add_argument("--seeds", type=int, default=24)
p.add_argument("--samples", type=int, default=16384)
p.add_argument("--scenes", default="builtin:cornell-green-floor,builtin:statue-red-spot,builtin:two-rooms,builtin:three-rooms")
a = p.parse_args()


def sd(xs):
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


print(f"binary {a.bin}, {a.seeds} seeds, {a.samples} eye paths")
print("| scene | sd(u') over seeds | reported se_u (RMS) | ratio u | sd(v') | reported se_v | ratio v |")
print("|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as tmp:
    for scene in a.scenes.split(","):
        us, vs, su, sv = [], [], [], []
        for k in range(a.seeds):
            out = Path(tmp) / f"s{k}"
            subprocess.run([a.bin, "render", scene, "--width", "16", "--height", "16", "--spp", "1",
                            "--estimators", "eye", "--eye-samples", str(a.samples), "--seed", str(k),
                            "--out", str(out)], check=True, capture_output=True)
            with open(out / "adaptation.csv") as f:
                row = next(r for r in csv.DictReader(f) if r["estimator"] == "eye")
            us.append(float(row["u_prime"])); vs.append(float(row["v_prime"]))
            su.append(float(row["std_err_u"])); sv.append(float(row["std_err_v"]))
        rms = lambda xs: math.sqrt(sum(x * x for x in xs) / len(xs))
        eu, ev = sd(us), sd(vs)
        print(f"| {scene} | {eu:.3e} | {rms(su):.3e} | {rms(su)/eu:.2f} | {ev:.3e} | {rms(sv):.3e} | {rms(sv)/ev:.2f} |")
