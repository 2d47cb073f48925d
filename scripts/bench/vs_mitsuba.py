#!/usr/bin/env python3
"""eyeadapt against Mitsuba 3 on one scene: speed, noise, efficiency and bias.

Run through scripts/bench/vs-mitsuba.sh, which prepares the venv and the eyeadapt binary.
For every spp in --spp, each run renders the scene once with eyeadapt and once with every
Mitsuba (variant, sampler); runs alternate between renderers so that load on the (shared)
machine hits all of them alike, and every figure is the median of --runs runs.

What is timed:
  eyeadapt  the "seconds" of `eyeadapt render --stats-json`: rendering only, without
            scene loading, BVH build or writing images (it does include eyeadapt's AOVs,
            which Mitsuba's path integrator does not compute).
  Mitsuba   mi.render(scene, spp, seed) plus the conversion of the result to numpy, which
            waits for the render to finish. The scene is loaded beforehand and not timed.
            For llvm_ad_rgb an untimed warm-up render at the same spp compiles the kernels
            first, so the timed renders reuse them from Dr.Jit's kernel cache; what remains
            included is Mitsuba's per-call Python tracing of the integrator and the kernel
            launch.

Reference: Mitsuba (llvm_ad_rgb when it works, else scalar_rgb) with the independent
sampler, rendered as two independent halves ("A" and "B") of --ref-spp samples per pixel
each, in passes of --ref-pass-spp with distinct seeds; the reference is their mean. Mitsuba
is the reference because it is the established, validated renderer this comparison is
about: RMSE against it counts eyeadapt's bias as error, as a user would. eyeadapt also
renders --ref-spp samples ("own reference") for the bias check and a noise-only RMSE. The
pass-to-pass spread gives each reference's own noise, which is subtracted from every MSE.

The bias check compares eyeadapt's reference with Mitsuba's, per pixel, against their
combined noise, and runs the same statistic on Mitsuba's half A against its half B as a
control: the statistic is dominated by a few hundred high-variance pixels (the light's
edge), so its own spread is large, and an eyeadapt-vs-Mitsuba ratio is only evidence of a
difference where it exceeds what two Mitsuba references show against each other.
References are cached (key: scene directory content, renderer version/binary, spp, seeds)
under --cache.
"""
import argparse
import hashlib
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--eyeadapt", required=True, help="eyeadapt binary")
    p.add_argument("--scene", default=os.path.join(REPO, "scenes/cornell-box/cornell.xml"),
                   help="Mitsuba XML scene; it must say <sampler type=\"$sampler\"> to allow --samplers")
    p.add_argument("--eyeadapt-scene", default=None,
                   help="scene file given to eyeadapt (default: --scene)")
    p.add_argument("--spp", default="16,64,256")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--samplers", default="independent",
                   help="Mitsuba samplers, comma list or 'all' (independent,multijitter,ldsampler)")
    p.add_argument("--variants", default="auto",
                   help="Mitsuba variants, comma list; auto = llvm_ad_rgb (if LLVM works) and scalar_rgb")
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--ref-pass-spp", type=int, default=256)
    p.add_argument("--cache", default=os.path.join(HERE, ".cache"))
    p.add_argument("--json", default=None, help="also write all results to this JSON file")
    p.add_argument("--markdown", default=None,
                   help="append the printed report, with date, commit and machine load, as a new "
                        "section of this Markdown file (e.g. docs/benchmarks/vs-mitsuba-cornell.md)")
    p.add_argument("--label", default="run", help="title of the --markdown section")
    a = p.parse_args()
    a.spp = [int(x) for x in a.spp.split(",")]
    a.samplers = (["independent", "multijitter", "ldsampler"] if a.samplers == "all"
                  else a.samplers.split(","))
    if a.ref_spp % a.ref_pass_spp or a.ref_spp // a.ref_pass_spp < 2:
        p.error("--ref-spp must be a multiple of --ref-pass-spp, with at least 2 passes")
    a.eyeadapt_scene = a.eyeadapt_scene or a.scene
    return a


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def scene_digest(path):
    """Hash of every file in the scene's directory (the scene and the meshes it uses)."""
    h = hashlib.sha256()
    root = os.path.dirname(os.path.abspath(path))
    h.update(os.path.basename(path).encode())
    for d, _, files in sorted(os.walk(root)):
        for f in sorted(files):
            full = os.path.join(d, f)
            h.update(os.path.relpath(full, root).encode())
            h.update(sha256_file(full).encode())
    return h.hexdigest()


# ----- renderers ---------------------------------------------------------------------------

class Eyeadapt:
    name = "eyeadapt"

    def __init__(self, binary, scene):
        self.binary, self.scene = binary, scene
        self.tmp = tempfile.mkdtemp(prefix="vs-mitsuba-")

    def render(self, spp, seed):
        out = os.path.join(self.tmp, f"r{spp}-{seed}")
        stats = out + ".json"
        cmd = [self.binary, "render", self.scene, "--spp", str(spp), "--seed", str(seed),
               "--out", out, "--stats-json", stats]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed:\n{r.stderr.strip()}")
        with open(stats) as f:
            st = json.load(f)
        img = read_exr_rgb(os.path.join(out, "raw.exr"))
        shutil.rmtree(out, ignore_errors=True)
        return img, float(st["seconds"])

    def version(self):
        return sha256_file(self.binary)


class Mitsuba:
    name = "mitsuba"

    def __init__(self, variant, sampler, scene_path):
        import mitsuba as mi
        self.mi, self.variant, self.sampler = mi, variant, sampler
        mi.set_variant(variant)
        try:
            self.scene = mi.load_file(scene_path, sampler=sampler)
        except Exception as e:
            if "unused parameters" in str(e):
                raise SystemExit(f"{scene_path}: the scene has no $sampler parameter: write "
                                 "<sampler type=\"$sampler\"> with <default name=\"sampler\" "
                                 "value=\"independent\"/> in it") from e
            raise
        got = str(self.scene.sensors()[0].sampler()).split("[")[0].lower()
        want = {"independent": "independent", "multijitter": "multijitter",
                "ldsampler": "lowdiscrepancy", "stratified": "stratified",
                "orthogonal": "orthogonal"}.get(sampler, sampler)
        if want not in got:
            raise SystemExit(f"{scene_path}: asked Mitsuba for the {sampler} sampler but the scene "
                             f"uses {got}: write <sampler type=\"$sampler\"> in the scene")
        self.warmed = set()

    def render(self, spp, seed):
        mi = self.mi
        mi.set_variant(self.variant)
        t0 = time.perf_counter()
        img = mi.render(self.scene, spp=spp, seed=seed)
        arr = np.array(img, dtype=np.float32)  # waits for the (llvm) kernels
        dt = time.perf_counter() - t0
        return arr[..., :3].astype(np.float64), dt

    def warm_up(self, spp):
        if self.variant.startswith("llvm") and spp not in self.warmed:
            self.render(spp, seed=999_999)
            self.warmed.add(spp)

    def version(self):
        return self.mi.__version__


def read_exr_rgb(path):
    """R, G and B of an EXR by channel name (eyeadapt's file also has AOV channels)."""
    import mitsuba as mi
    bmp = mi.Bitmap(path)
    parts = dict(bmp.split())
    root = parts.get("<root>", bmp)
    names = [root.struct_()[i].name for i in range(root.channel_count())]
    arr = np.array(root, dtype=np.float32)
    try:
        idx = [names.index(c) for c in "RGB"]
    except ValueError:
        raise RuntimeError(f"{path}: no R, G, B channels (has {names})")
    return arr[..., idx].astype(np.float64)


def llvm_works():
    """True when Dr.Jit finds an LLVM library (Debian: libllvm19) and can run a kernel."""
    code = ("import mitsuba as mi, drjit as dr; mi.set_variant('llvm_ad_rgb'); "
            "x = dr.llvm.Float([1, 2]) + 1; dr.eval(x); print(float(x[1]))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    return r.returncode == 0 and r.stdout.strip() == "3.0", r.stderr.strip()[-400:]


# ----- reference ---------------------------------------------------------------------------

def reference(renderer, label, args, digest, seed_base=1_000_003):
    """Mean and per-pixel variance of the mean, cached. Passes use seeds seed_base + 7919 k."""
    passes = args.ref_spp // args.ref_pass_spp
    key = hashlib.sha256(json.dumps([label, renderer.version(), digest, args.ref_spp,
                                     args.ref_pass_spp, seed_base]).encode()).hexdigest()[:20]
    path = os.path.join(args.cache, f"ref-{label}-{key}.npz")
    if os.path.exists(path):
        z = np.load(path)
        log(f"reference {label}: cached {path}")
        return z["mean"], z["var_mean"]
    log(f"reference {label}: {passes} passes x {args.ref_pass_spp} spp ...")
    s = s2 = None
    t0 = time.time()
    for k in range(passes):
        img, _ = renderer.render(args.ref_pass_spp, seed=seed_base + 7919 * k)
        s = img if s is None else s + img
        s2 = img * img if s2 is None else s2 + img * img
        log(f"  pass {k + 1}/{passes} ({time.time() - t0:.0f} s)")
    mean = s / passes
    var_mean = np.maximum(s2 / passes - mean * mean, 0.0) * passes / (passes - 1) / passes
    os.makedirs(args.cache, exist_ok=True)
    np.savez_compressed(path, mean=mean, var_mean=var_mean)
    return mean, var_mean


def mse(img, ref_mean, ref_var):
    """MSE against the reference, less the reference's own noise."""
    return float(np.mean((img - ref_mean) ** 2) - np.mean(ref_var))


# ----- main --------------------------------------------------------------------------------

class Tee:
    """Copies everything printed to stdout into a buffer for --markdown."""

    def __init__(self, out):
        self.out, self.buf = out, []

    def write(self, x):
        self.buf.append(x)
        return self.out.write(x)

    def flush(self):
        self.out.flush()


def append_markdown(path, label, text, started, binary_sha, script="scripts/bench/vs-mitsuba.sh",
                    fenced=True):
    """Appends `text` as a section: date, commit, binary, load and the command line (without
    private paths), then the text, in a ```text block unless it is Markdown (fenced=False)."""
    def git(*args):
        r = subprocess.run(["git", "-C", REPO, *args], capture_output=True, text=True)
        return r.stdout.strip() if r.returncode == 0 else "?"
    dirty = " (uncommitted changes)" if git("status", "--porcelain", "--untracked-files=no") else ""
    load = " ".join(open("/proc/loadavg").read().split()[:3]) if os.path.exists("/proc/loadavg") else "?"
    argv, shown = sys.argv[1:], []
    while argv:
        x = argv.pop(0)
        if x in ("--eyeadapt", "--markdown", "--json", "--cache"):
            argv = argv[1:]  # private paths, not part of the recipe
        elif os.path.isabs(x) and os.path.exists(x):
            shown.append(os.path.basename(x.rstrip("/")).upper())  # a local checkout: DIR
        else:
            shown.append(x)
    cmd = " ".join([script, *shown])
    body = f"```text\n{text.strip()}\n```" if fenced else text.strip()
    with open(path, "a") as f:
        f.write(f"\n## {label}\n\n{started} UTC, repository at {git('rev-parse', '--short', 'HEAD')}"
                f"{dirty}, eyeadapt binary sha256 {binary_sha[:12]}, load average at the end "
                f"{load}.\n\n`{cmd}`\n\n{body}\n")


def main():
    a = parse_args()
    started = time.strftime("%Y-%m-%d %H:%M", time.gmtime())
    if a.markdown:
        sys.stdout = Tee(sys.stdout)
    import mitsuba as mi
    notes = []
    if a.variants == "auto":
        ok, err = llvm_works()
        variants = ["llvm_ad_rgb", "scalar_rgb"] if ok else ["scalar_rgb"]
        if not ok:
            notes.append("llvm_ad_rgb unavailable (Dr.Jit found no working LLVM; on Debian "
                         "`apt-get install libllvm19`): Mitsuba ran as scalar_rgb only. " + err)
    else:
        variants = a.variants.split(",")

    ea = Eyeadapt(a.eyeadapt, a.eyeadapt_scene)
    try:
        ea.render(1, seed=0)
    except RuntimeError as e:
        toml = os.path.join(os.path.dirname(a.eyeadapt_scene), "scene.toml")
        if a.eyeadapt_scene.endswith(".xml") and os.path.exists(toml):
            notes.append(f"STAND-IN: this eyeadapt binary cannot load {a.eyeadapt_scene} "
                         f"({str(e).splitlines()[-1][:160]}); it rendered {toml}, the same "
                         "geometry, materials, light and camera as TOML")
            log(notes[-1])
            ea = Eyeadapt(a.eyeadapt, toml)
            ea.render(1, seed=0)
        else:
            raise

    mits = {}
    for v in variants:
        for s in a.samplers:
            mits[(v, s)] = Mitsuba(v, s, a.scene)
    threads = os.cpu_count()

    digest = scene_digest(a.scene)
    ref_variant = variants[0]
    ref_m = Mitsuba(ref_variant, "independent", a.scene)
    ma_ref, ma_var = reference(ref_m, f"mitsuba-{ref_variant}-A", a, digest, 1_000_003)
    mb_ref, mb_var = reference(ref_m, f"mitsuba-{ref_variant}-B", a, digest, 5_000_011)
    m_ref, m_var = 0.5 * (ma_ref + mb_ref), 0.25 * (ma_var + mb_var)
    e_ref, e_var = reference(ea, "eyeadapt", a, scene_digest(ea.scene))
    h, w = m_ref.shape[:2]
    if e_ref.shape != m_ref.shape:
        raise SystemExit(f"image sizes differ: eyeadapt {e_ref.shape}, Mitsuba {m_ref.shape}")

    # Timed runs, alternating renderers.
    results = {}  # (renderer, variant, sampler, spp) -> list of (seconds, mse_vs_mitsuba, mse_vs_own)
    for spp in a.spp:
        for m in mits.values():
            m.warm_up(spp)
    for run in range(a.runs):
        for spp in a.spp:
            seed = 7919 * (run + 1) + spp
            img, t = ea.render(spp, seed)
            results.setdefault(("eyeadapt", "-", "own", spp), []).append(
                (t, mse(img, m_ref, m_var), mse(img, e_ref, e_var)))
            for (v, s), m in mits.items():
                img, t = m.render(spp, seed)
                own = mse(img, m_ref, m_var)
                results.setdefault(("mitsuba", v, s, spp), []).append((t, own, own))
            log(f"run {run + 1}/{a.runs} spp {spp} done")

    rows = []
    for (r, v, s, spp), xs in results.items():
        t = statistics.median(x[0] for x in xs)
        e2 = statistics.median(x[1] for x in xs)
        o2 = statistics.median(x[2] for x in xs)
        rmse = max(e2, 0.0) ** 0.5
        rmse_own = max(o2, 0.0) ** 0.5
        rows.append(dict(renderer=r, variant=v, sampler=s, spp=spp, seconds=t,
                         msps=w * h * spp / t / 1e6, rmse=rmse, eff=1.0 / (max(e2, 1e-30) * t),
                         rmse_own=rmse_own, eff_own=1.0 / (max(o2, 1e-30) * t), runs=len(xs)))

    print(f"\nScene {os.path.relpath(a.scene, REPO)} ({w}x{h}); eyeadapt rendered "
          f"{os.path.relpath(ea.scene, REPO)}. Mitsuba {mi.__version__}. {threads} cores, "
          f"every renderer on all of them. Medians of {a.runs} runs.")
    print(f"Reference: Mitsuba {ref_variant} independent, 2 x {a.ref_spp} spp "
          f"(2 x {a.ref_spp // a.ref_pass_spp} passes); RMSE has the reference's own noise removed.")
    print("RMSE = vs the Mitsuba reference; own = vs the renderer's own reference "
          "(noise only, no bias). eff = 1/(RMSE^2 * seconds).\n")
    hdr = (f"{'renderer':<9} {'variant':<12} {'sampler':<12} {'spp':>5} {'seconds':>8} "
           f"{'Msamples/s':>10} {'RMSE':>9} {'eff':>9} {'RMSE own':>9} {'eff own':>9}")
    print(hdr)
    print("-" * len(hdr))
    for r in sorted(rows, key=lambda r: (r["spp"], r["renderer"] != "eyeadapt", r["variant"], r["sampler"])):
        print(f"{r['renderer']:<9} {r['variant']:<12} {r['sampler']:<12} {r['spp']:>5} "
              f"{r['seconds']:>8.3f} {r['msps']:>10.3f} {r['rmse']:>9.5f} {r['eff']:>9.1f} "
              f"{r['rmse_own']:>9.5f} {r['eff_own']:>9.1f}")

    print("\nRatios eyeadapt / Mitsuba (>1: eyeadapt faster / noisier / more efficient):\n")
    hdr = (f"{'vs variant':<12} {'sampler':<12} {'spp':>5} {'samples/s':>10} {'RMSE':>8} "
           f"{'eff':>8} {'eff own':>8}")
    print(hdr)
    print("-" * len(hdr))
    by = {(r["renderer"], r["variant"], r["sampler"], r["spp"]): r for r in rows}
    for spp in a.spp:
        e = by[("eyeadapt", "-", "own", spp)]
        for (v, s) in mits:
            m = by[("mitsuba", v, s, spp)]
            print(f"{v:<12} {s:<12} {spp:>5} {e['msps'] / m['msps']:>10.3f} "
                  f"{e['rmse'] / m['rmse']:>8.3f} {e['eff'] / m['eff']:>8.3f} "
                  f"{e['eff_own'] / m['eff_own']:>8.3f}")

    # Bias check between the two references.
    print(f"\nBias check: converged means (Mitsuba 2 x {a.ref_spp} spp, eyeadapt {a.ref_spp} spp), "
          "per channel:")
    npix = h * w
    for c, name in enumerate("RGB"):
        mm, em = m_ref[..., c].mean(), e_ref[..., c].mean()
        se = (m_var[..., c].sum() + e_var[..., c].sum()) ** 0.5 / npix
        print(f"  {name}: Mitsuba {mm:.5f}  eyeadapt {em:.5f}  eyeadapt/Mitsuba {em / mm:.4f}  "
              f"difference {em - mm:+.5f} = {(em - mm) / se:+.1f} standard errors")
    # Where an excess would live: silhouettes (a sub-pixel edge difference, or a reference
    # whose noise estimate is poor there) or everywhere (a shading difference).
    grey = m_ref.mean(-1)
    gy, gx = np.gradient(grey)
    g2 = gx * gx + gy * gy
    edge = g2 >= np.quantile(g2, 0.99)

    def agreement(x, xv, y, yv):
        """Per-pixel RMS difference / RMS combined noise: everywhere, off and on the 1 %
        steepest-gradient pixels."""
        d2, v = (x - y) ** 2, xv + yv
        return (float(np.sqrt(d2.mean())), float(np.sqrt(v.mean())),
                float(np.sqrt(d2[~edge].mean() / v[~edge].mean())),
                float(np.sqrt(d2[edge].mean() / v[edge].mean())))

    print("  per-pixel RMS difference / RMS combined noise (1.00 = the difference is noise):")
    print(f"  {'pair':<36} {'RMS diff':>9} {'noise':>9} {'ratio':>6} {'off edges':>9} "
          f"{'edges':>6}")
    pairs = [("eyeadapt vs Mitsuba (A+B)", e_ref, e_var, m_ref, m_var),
             ("eyeadapt vs Mitsuba A", e_ref, e_var, ma_ref, ma_var),
             ("eyeadapt vs Mitsuba B", e_ref, e_var, mb_ref, mb_var),
             ("control: Mitsuba A vs Mitsuba B", ma_ref, ma_var, mb_ref, mb_var)]
    stats = {}
    for name, x, xv, y, yv in pairs:
        diff, noise, off, on = agreement(x, xv, y, yv)
        stats[name] = dict(rmse=diff, noise=noise, ratio=diff / noise, off_edges=off, edges=on)
        print(f"  {name:<36} {diff:>9.5f} {noise:>9.5f} {diff / noise:>6.3f} {off:>9.3f} "
              f"{on:>6.3f}")
    ea_r = stats["eyeadapt vs Mitsuba (A+B)"]["ratio"]
    ctl = stats["control: Mitsuba A vs Mitsuba B"]["ratio"]
    verdict = ("consistent with noise" if ea_r <= max(ctl, 1.05)
               else "MORE than noise and more than Mitsuba's own control")
    print(f"  verdict: eyeadapt vs Mitsuba {ea_r:.3f}, Mitsuba vs itself {ctl:.3f}: {verdict}")
    for n in notes:
        print("\nNOTE: " + n)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(rows=rows, notes=notes, scene=a.scene, eyeadapt_scene=ea.scene,
                           mitsuba=mi.__version__, variants=variants, ref_spp=a.ref_spp,
                           bias=stats), f, indent=1)
    shutil.rmtree(ea.tmp, ignore_errors=True)
    if a.markdown:
        append_markdown(a.markdown, a.label, "".join(sys.stdout.buf), started, ea.version())
        log(f"appended to {a.markdown}")


if __name__ == "__main__":
    main()
