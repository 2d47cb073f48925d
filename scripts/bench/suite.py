#!/usr/bin/env python3
"""The benchmark suite: eyeadapt against Mitsuba 3 llvm_ad_rgb on five scenes (suite_scenes.py).

Run through scripts/bench/suite.sh MITSUBA_DATA_DIR, which prepares the venv and a private copy
of the eyeadapt binary. Per scene, at --size pixels wide (the scene's aspect ratio), --spp
samples per pixel and the scene's max depth (given to both renderers explicitly, with
rr_depth 5):

Reference  Mitsuba llvm_ad_rgb, independent sampler, two halves of --ref-spp each in passes of
           --ref-pass-spp (vs_mitsuba.reference), cached under --cache; RMSE is against their
           mean with the reference's own noise subtracted (vs_mitsuba.mse). It counts any
           eyeadapt bias as error.
Render call  eyeadapt: the "seconds" of `eyeadapt render --stats-json` (rendering only: no
           scene loading, BVH build or image writing; it includes eyeadapt's AOVs). Mitsuba:
           mi.render(scene, spp, seed) plus the conversion to numpy, which waits for the
           kernels, in this process, the scene loaded beforehand and the kernels compiled by an
           untimed warm-up render (as vs_mitsuba.py). Every sampler of --samplers is timed;
           the best is the one with the highest render-call efficiency.
Whole process  eyeadapt: the wall time of that `eyeadapt render` (start, load, BVH, render,
           AOVs, raw.exr and preview.png). Mitsuba: the wall time of `mitsuba -m llvm_ad_rgb
           -o out.exr` with the best sampler (Python start, import, load, kernel tracing and
           compilation or Dr.Jit's on-disk kernel cache, render, EXR). One untimed process of
           each renderer first, so both start with warm file and kernel caches.
Runs       --runs rounds per phase; in each round the renderers run one after the other, so
           load on the shared machine hits them alike; every figure is a median over rounds.
           Phase 1: eyeadapt, then Mitsuba in-process with each sampler (render call).
           Phase 2: eyeadapt process, Mitsuba process with the best sampler (whole process).
CPU time   user + system seconds of each whole process (both renderers) and of Mitsuba's render
           calls (this process's, during the call): on a machine shared with other work a
           renderer's wall time depends on how much of the cores it gets, its CPU time much less.
           "samples per CPU-second" compares the whole processes by it.
Agreement  the mean of all eyeadapt images against the Mitsuba reference, per channel, in
           percent, with eyeadapt's standard error: "agree" when every channel is within 1 %.

samples/s = width × height × spp / seconds; efficiency = 1 / (RMSE² × seconds), with the
median MSE of the phase's images. Ratios are eyeadapt / Mitsuba (> 1: eyeadapt ahead).
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
from types import SimpleNamespace

import resource

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_xml  # noqa: E402
import suite_scenes  # noqa: E402
from vs_mitsuba import Tee, append_markdown, llvm_works, log, mse, read_exr_rgb, reference, sha256_file  # noqa: E402

VARIANT = "llvm_ad_rgb"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("data", help="a mitsuba-data checkout")
    p.add_argument("--eyeadapt", required=True, help="eyeadapt binary")
    p.add_argument("--size", type=int, default=128, help="image width; height by the scene's aspect")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--samplers", default="multijitter,ldsampler",
                   help="Mitsuba samplers to try (comma list: independent, stratified, multijitter, "
                        "orthogonal, ldsampler)")
    p.add_argument("--scenes", default=None, help="comma list of scene names (default: all)")
    p.add_argument("--ref-spp", type=int, default=2048, help="spp of each reference half")
    p.add_argument("--ref-pass-spp", type=int, default=256)
    p.add_argument("--cache", default=os.path.join(os.environ.get("XDG_CACHE_HOME") or
                                                   os.path.expanduser("~/.cache"), "eyeadapt-bench"),
                   help="references and generated scenes (outside git)")
    p.add_argument("--json", default=None, help="also write every measurement to this JSON file")
    p.add_argument("--markdown", default=None,
                   help="append the printed report as a dated section of this Markdown file")
    p.add_argument("--label", default="Benchmark suite", help="title of the --markdown section")
    a = p.parse_args()
    a.samplers = a.samplers.split(",")
    if a.ref_spp % a.ref_pass_spp or a.ref_spp // a.ref_pass_spp < 2:
        p.error("--ref-spp must be a multiple of --ref-pass-spp, with at least 2 passes")
    return a


# ----- renderers ---------------------------------------------------------------------------

def cpu_seconds(who):
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


def run_timed(cmd):
    """(completed process, wall seconds, CPU seconds of the child). Children run one at a time,
    so the growth of RUSAGE_CHILDREN is this child's."""
    c0, t0 = cpu_seconds(resource.RUSAGE_CHILDREN), time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r, time.perf_counter() - t0, cpu_seconds(resource.RUSAGE_CHILDREN) - c0


def eyeadapt_render(a, sc, wh, spp, seed, tmp):
    """(image, render-call seconds, whole-process seconds, whole-process CPU seconds, stats)."""
    out = os.path.join(tmp, f"ea-{seed}")
    stats = out + ".json"
    cmd = [a.eyeadapt, "render", sc.eyeadapt, "--spp", str(spp), "--seed", str(seed),
           "--width", str(wh[0]), "--height", str(wh[1]), "--max-depth", str(sc.max_depth),
           "--rr-depth", "5", "--out", out, "--stats-json", stats]
    r, wall, cpu = run_timed(cmd)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{r.stderr.strip()}")
    with open(stats) as f:
        st = json.load(f)
    img = read_exr_rgb(os.path.join(out, "raw.exr"))
    shutil.rmtree(out, ignore_errors=True)
    return img, float(st["seconds"]), wall, cpu, st


class MitsubaScene:
    """One loaded scene with one sampler, rendered in this process."""

    def __init__(self, xml, dirs, params):
        import mitsuba as mi
        self.mi = mi
        fr = mi.file_resolver()
        saved = [fr[i] for i in range(len(fr))]
        for d in reversed(dirs):
            fr.prepend(d)
        try:
            self.scene = mi.load_file(xml, **{k: str(v) for k, v in params.items()})
        finally:
            fr.clear()
            for e in saved:
                fr.append(e)
        got = self.scene.sensors()[0].sampler().sample_count()
        if got != int(params["bench_spp"]):
            raise SystemExit(f"Mitsuba's {params['bench_sampler']} sampler takes {got} spp, not "
                             f"{params['bench_spp']}: choose an spp it accepts")

    def render(self, spp, seed):
        """(image, seconds); self.cpu: the CPU seconds of this process during the call."""
        c0, t0 = cpu_seconds(resource.RUSAGE_SELF), time.perf_counter()
        img = self.mi.render(self.scene, spp=spp, seed=seed)
        arr = np.array(img, dtype=np.float32)  # waits for the (llvm) kernels
        dt = time.perf_counter() - t0
        self.cpu = cpu_seconds(resource.RUSAGE_SELF) - c0
        return arr[..., :3].astype(np.float64), dt

    def version(self):
        return f"{self.mi.__version__} {VARIANT}"


def mitsuba_process(xml, dirs, params, out):
    """(image, whole-process seconds, CPU seconds) of Mitsuba's command-line renderer."""
    cmd = [os.path.join(os.path.dirname(sys.executable), "mitsuba"), "-m", VARIANT,
           "-a", ";".join(dirs), "-o", out]
    for k, v in params.items():
        cmd += ["-D", f"{k}={v}"]
    cmd.append(xml)
    r, wall, cpu = run_timed(cmd)
    if r.returncode != 0 or not os.path.exists(out):
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{(r.stderr or r.stdout).strip()[-2000:]}")
    img = read_exr_rgb(out)
    os.remove(out)
    return img, wall, cpu


# ----- one scene ---------------------------------------------------------------------------

def median_mse(xs):
    return max(statistics.median(xs), 1e-30)


def run_scene(a, sc, tmp):
    text, dirs, file_wh = bench_xml.patch(sc.mitsuba)
    w = a.size
    h = max(1, round(a.size * file_wh[1] / file_wh[0]))
    xml = os.path.join(tmp, "scene.xml")
    with open(xml, "w") as f:
        f.write(text)
    params = dict(bench_spp=a.spp, bench_width=w, bench_height=h, bench_max_depth=sc.max_depth,
                  bench_rr_depth=5, bench_seed=0)
    key = hashlib.sha256(json.dumps([text, w, h, sc.max_depth, sha256_file(sc.mitsuba)] +
                                    [sha256_file(p) for p in sc.inputs]).encode()).hexdigest()
    ref_m = MitsubaScene(xml, dirs, dict(params, bench_sampler="independent",
                                         bench_spp=a.ref_pass_spp))
    label = "suite-" + sc.name.replace(" ", "_")
    ref_args = SimpleNamespace(ref_spp=a.ref_spp, ref_pass_spp=a.ref_pass_spp, cache=a.cache)
    ra, va = reference(ref_m, label + "-A", ref_args, key, 1_000_003)
    rb, vb = reference(ref_m, label + "-B", ref_args, key, 5_000_011)
    ref, ref_var = 0.5 * (ra + rb), 0.25 * (va + vb)
    del ref_m
    if ref.shape[:2] != (h, w):
        raise SystemExit(f"{sc.name}: Mitsuba rendered {ref.shape[1]}x{ref.shape[0]}, not {w}x{h}")

    mits = {s: MitsubaScene(xml, dirs, dict(params, bench_sampler=s)) for s in a.samplers}
    for m in mits.values():
        m.render(a.spp, seed=999_999)  # compiles the kernels
    ea_img, _, _, _, stats = eyeadapt_render(a, sc, (w, h), a.spp, 999_999, tmp)  # warms the caches
    if ea_img.shape != ref.shape:
        raise SystemExit(f"{sc.name}: eyeadapt rendered {ea_img.shape}, Mitsuba {ref.shape}")

    r = dict(name=sc.name, note=sc.note, width=w, height=h, spp=a.spp, max_depth=sc.max_depth,
             triangles=stats.get("triangles"), ea=dict(render=[], process=[], cpu=[], mse1=[], mse2=[]),
             mi={s: dict(render=[], cpu=[], mse=[]) for s in a.samplers},
             mi_proc=dict(process=[], cpu=[], mse=[]))
    ea_images = []
    for run in range(a.runs):  # phase 1: render call
        seed = 7919 * (run + 1)
        img, t, _, _, _ = eyeadapt_render(a, sc, (w, h), a.spp, seed, tmp)
        ea_images.append(img)
        r["ea"]["render"].append(t)
        r["ea"]["mse1"].append(mse(img, ref, ref_var))
        for s, m in mits.items():
            img, t = m.render(a.spp, seed)
            r["mi"][s]["render"].append(t)
            r["mi"][s]["cpu"].append(m.cpu)
            r["mi"][s]["mse"].append(mse(img, ref, ref_var))
        log(f"{sc.name}: render-call round {run + 1}/{a.runs}")
    del mits
    best = max(a.samplers, key=lambda s: 1 / (median_mse(r["mi"][s]["mse"]) *
                                              statistics.median(r["mi"][s]["render"])))
    r["best"] = best
    out = os.path.join(tmp, "mitsuba.exr")
    mparams = dict(params, bench_sampler=best)
    mitsuba_process(xml, dirs, dict(mparams, bench_seed=999_999), out)  # warms the caches
    for run in range(a.runs):  # phase 2: whole process
        seed = 104_729 * (run + 1)
        img, _, wall, cpu, _ = eyeadapt_render(a, sc, (w, h), a.spp, seed, tmp)
        ea_images.append(img)
        r["ea"]["process"].append(wall)
        r["ea"]["cpu"].append(cpu)
        r["ea"]["mse2"].append(mse(img, ref, ref_var))
        img, wall, cpu = mitsuba_process(xml, dirs, dict(mparams, bench_seed=seed), out)
        r["mi_proc"]["process"].append(wall)
        r["mi_proc"]["cpu"].append(cpu)
        r["mi_proc"]["mse"].append(mse(img, ref, ref_var))
        log(f"{sc.name}: whole-process round {run + 1}/{a.runs}")

    means = np.array([im.reshape(-1, 3).mean(0) for im in ea_images])
    ref_mean = ref.reshape(-1, 3).mean(0)
    r["mean_eyeadapt"] = means.mean(0).tolist()
    r["mean_mitsuba"] = ref_mean.tolist()
    r["diff_pct"] = (100 * (means.mean(0) - ref_mean) / ref_mean).tolist()
    r["se_pct"] = (100 * means.std(0, ddof=1) / np.sqrt(len(means)) / ref_mean).tolist()
    r["agree"] = bool(np.all(np.abs(r["diff_pct"]) <= 1.0))
    return r


# ----- report ------------------------------------------------------------------------------

def figures(r):
    """The derived figures of one scene: medians, samples/s, efficiencies and their ratios."""
    med = statistics.median
    n = r["width"] * r["height"] * r["spp"]
    ea, mb, mp = r["ea"], r["mi"][r["best"]], r["mi_proc"]
    f = dict(ea_render=med(ea["render"]), ea_process=med(ea["process"]),
             mi_render=med(mb["render"]), mi_process=med(mp["process"]),
             ea_cpu=med(ea["cpu"]), mi_cpu=med(mp["cpu"]), mi_render_cpu=med(mb["cpu"]),
             ea_rmse1=median_mse(ea["mse1"]) ** 0.5, ea_rmse2=median_mse(ea["mse2"]) ** 0.5,
             mi_rmse=median_mse(mb["mse"]) ** 0.5, mi_rmse_proc=median_mse(mp["mse"]) ** 0.5)
    for k in ("ea_render", "ea_process", "mi_render", "mi_process"):
        f[k.replace("_", "_msps_")] = n / f[k] / 1e6
    f["ea_eff_render"] = 1 / (f["ea_rmse1"] ** 2 * f["ea_render"])
    f["ea_eff_process"] = 1 / (f["ea_rmse2"] ** 2 * f["ea_process"])
    f["mi_eff_render"] = 1 / (f["mi_rmse"] ** 2 * f["mi_render"])
    f["mi_eff_process"] = 1 / (f["mi_rmse_proc"] ** 2 * f["mi_process"])
    return f


def g(x):
    return f"{x:.4g}"


def print_summary(a, results, mi_version):
    print(f"eyeadapt against Mitsuba {mi_version} {VARIANT} (samplers tried: {', '.join(a.samplers)}), "
          f"{a.spp} spp, {a.size} px wide, medians of {a.runs} rounds, {os.cpu_count()} cores, "
          f"every renderer on all of them. Reference: Mitsuba, independent sampler, 2 × "
          f"{a.ref_spp} spp. How each figure is timed: scripts/bench/suite.py.\n")
    print("| scene | size | max depth | triangles | Mitsuba sampler | samples/s render call | "
          "samples/s whole process | samples per CPU-second whole process | efficiency render "
          "call | efficiency whole process | means eyeadapt vs Mitsuba (R, G, B) | agree (1 %) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        f = figures(r)
        diff = ", ".join(f"{d:+.2f}" for d in r["diff_pct"])
        se = max(r["se_pct"])
        print(f"| {r['name']} | {r['width']}×{r['height']} | {r['max_depth']} | {r['triangles']} | "
              f"{r['best']} | {f['ea_msps_render'] / f['mi_msps_render']:.3f} | "
              f"{f['ea_msps_process'] / f['mi_msps_process']:.3f} | "
              f"{f['mi_cpu'] / f['ea_cpu']:.3f} | "
              f"{f['ea_eff_render'] / f['mi_eff_render']:.3f} | "
              f"{f['ea_eff_process'] / f['mi_eff_process']:.3f} | {diff} % (± {se:.2f}) | "
              f"{'yes' if r['agree'] else 'NO'} |")
    print("\nRatios are eyeadapt / Mitsuba (> 1: eyeadapt faster or more efficient); "
          "efficiency = 1/(RMSE² · seconds). Triangles: eyeadapt's count (it tessellates "
          "rectangles, cubes and spheres).\n")


def print_details(a, results):
    print("| scene | renderer | render call s | whole process s | CPU s render call / whole "
          "process | Msamples/s render call | Msamples/s whole process | RMSE | efficiency "
          "render call | efficiency whole process |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        f = figures(r)
        n = r["width"] * r["height"] * r["spp"]
        print(f"| {r['name']} | eyeadapt | {f['ea_render']:.3f} | {f['ea_process']:.3f} | "
              f"- / {f['ea_cpu']:.3f} | {f['ea_msps_render']:.3f} | {f['ea_msps_process']:.3f} | "
              f"{f['ea_rmse1']:.5f} / {f['ea_rmse2']:.5f} | {g(f['ea_eff_render'])} | "
              f"{g(f['ea_eff_process'])} |")
        for s in a.samplers:
            m = r["mi"][s]
            t, rm = statistics.median(m["render"]), median_mse(m["mse"]) ** 0.5
            proc = s == r["best"]
            pt = f"{f['mi_process']:.3f}" if proc else "-"
            pc = f"{f['mi_cpu']:.3f}" if proc else "-"
            pm = f"{f['mi_msps_process']:.3f}" if proc else "-"
            pr = f" / {f['mi_rmse_proc']:.5f}" if proc else ""
            pe = g(f["mi_eff_process"]) if proc else "-"
            print(f"| {r['name']} | Mitsuba {s} | {t:.3f} | {pt} | "
                  f"{statistics.median(m['cpu']):.3f} / {pc} | {n / t / 1e6:.3f} | {pm} | "
                  f"{rm:.5f}{pr} | {g(1 / (rm ** 2 * t))} | {pe} |")
    print("\nRMSE: of the render-call images / of the whole-process images (the Mitsuba "
          "process ran with the best sampler only). eyeadapt's render call has no CPU time "
          "of its own (its --stats-json has wall seconds only).")
    for r in results:
        print(f"\n- {r['name']}: {r['note']}")


def main():
    a = parse_args()
    started = time.strftime("%Y-%m-%d %H:%M", time.gmtime())
    if a.markdown:
        sys.stdout = Tee(sys.stdout)
    ok, err = llvm_works()
    if not ok:
        raise SystemExit(f"Mitsuba's {VARIANT} does not run (Debian: apt-get install libllvm19): {err}")
    import mitsuba as mi
    mi.set_variant(VARIANT)
    scenes = suite_scenes.prepare(os.path.abspath(a.data), os.path.join(a.cache, "scenes"), sys.executable)
    if a.scenes:
        want = a.scenes.split(",")
        scenes = [s for s in scenes if s.name in want]
    results = []
    tmp = tempfile.mkdtemp(prefix="bench-suite-")
    try:
        for sc in scenes:
            t0 = time.time()
            results.append(run_scene(a, sc, tmp))
            log(f"{sc.name}: done in {time.time() - t0:.0f} s")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print_summary(a, results, mi.__version__)
    print_details(a, results)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(results=results, args=vars(a), mitsuba=mi.__version__), f, indent=1)
    if a.markdown:
        append_markdown(a.markdown, a.label, "".join(sys.stdout.buf), started,
                        sha256_file(a.eyeadapt), script="scripts/bench/suite.sh", fenced=False)
        log(f"appended to {a.markdown}")


if __name__ == "__main__":
    main()
