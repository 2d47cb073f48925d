//! What is measured in each case, how it is judged, and how it is written up.
//!
//! Every table lists every estimator the job ran (estimators.md §0.1) plus, where a colour is
//! read off an image, `raw` (no adaptation). Adapted colours are `CAT02(white → D65, D = 1)`
//! applied to raw region means (the CAT is linear). HSV read-outs use
//! [`equal_luminance_hsv`](crate::measure::equal_luminance_hsv).
mod case1;
mod case2;
mod case3;
mod case4;
mod case5;
mod case6;
#[cfg(test)]
mod design;
mod spot;

use super::measure::{
    Region, equal_luminance_hsv, hue_diff, pixels_in_box, reflectance, region_mean,
};
use super::sheet::Tiles;
use super::{CaseInfo, CaseReport, JobRun, Named, Shot};
use crate::verdict::{Check, ClaimRun, above, below};
use eyeadapt_color::{
    D65_XYZ, Estimate, FrameAovs, SeriesParams, SeriesPoint, delta_e_2000, delta_uv, hsv_of_linear,
    luminance, rgb_to_xyz, series_metrics, wcam, whiteness, xyz_to_lab, xyz_to_rgb, xyz_to_uv,
};
use eyeadapt_scene::Scene;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::{cat_matrix, white_for_cat};
use eyeadapt_sequencer::job::Job;
use eyeadapt_tracer::{Frame, View};
use glam::{DMat3, DVec2, DVec3};
use std::collections::BTreeMap;
use std::fmt::Write;

/// Δu′v′ of a just-noticeable display difference (estimators.md §7.1).
pub const THETA_JND: f64 = 0.004;
/// The tolerance the paper's single-illuminant cases are held to (issue 6).
pub const CASE1_TOLERANCE: f64 = 2e-3;

/// One estimator's reading on one shot, with the CAT it implies.
struct Est<'a> {
    name: &'static str,
    estimate: &'a Estimate,
    /// The CAT on linear sRGB (D65 when the estimate is undefined).
    m: DMat3,
}

impl Est<'_> {
    fn uv(&self) -> Option<DVec2> {
        self.estimate.uv()
    }
}

fn ests<'a>(run: &JobRun, shot: &'a Shot) -> Vec<Est<'a>> {
    shot.readings
        .iter()
        .map(|r| Est {
            name: r.name,
            estimate: &r.estimate,
            m: cat_matrix(white_for_cat(&r.estimate, D65_XYZ).0, &run.job.adaptation),
        })
        .collect()
}

fn find<'a, 'b>(es: &'b [Est<'a>], name: &str) -> &'b Est<'a> {
    es.iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("estimator {name} did not run"))
}

fn f(v: f64, digits: usize) -> String {
    if v.is_finite() {
        format!("{v:.digits$}")
    } else {
        "n/a".into()
    }
}

fn uv_cell(uv: Option<DVec2>) -> String {
    uv.map_or("undefined".into(), |p| format!("({:.4}, {:.4})", p.x, p.y))
}

fn hue_cell(h: f64, s: f64) -> String {
    if s < 0.0005 {
        "–".into()
    } else {
        format!("{h:.0}°")
    }
}

fn pct(s: f64) -> String {
    format!("{:.1} %", 100.0 * s)
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// A markdown table.
struct Table {
    head: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn new(head: &[&str]) -> Table {
        Table {
            head: head.iter().map(|s| s.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    fn render(&self) -> String {
        let mut s = format!("| {} |\n|", self.head.join(" | "));
        for _ in &self.head {
            s.push_str("---|");
        }
        s.push('\n');
        for r in &self.rows {
            let _ = writeln!(s, "| {} |", r.join(" | "));
        }
        s
    }
}

fn setup_line(run: &JobRun) -> String {
    let j = &run.job;
    let source = j.scene.source.display().to_string();
    let files = match source.strip_prefix("builtin:") {
        // The job is a template of paper/scenes/ whose baseline is the configs/ job.
        Some(b) => format!(
            "`configs/{}.toml` (its camera a parameter of the study) over `builtin:{b}`",
            run.name
        ),
        // A template of paper/scenes/, filled (the work directory holds the filled files).
        None => "the job and scene templates of `paper/scenes/`, baseline configuration".into(),
    };
    format!(
        "{files}: {}×{}, {} spp, max_depth {}, {} eye-sensor paths per frame, {} frame(s), CAT02 with D = {}.",
        j.width,
        j.height,
        j.spp,
        j.path_settings.max_depth,
        eye_budget(&j.estimator_config.eye),
        run.shots.len(),
        j.adaptation.degree
    )
}

/// The eye sensor's budget as RESULTS.md states it.
fn eye_budget(e: &eyeadapt_sequencer::adapt::EyeOptions) -> String {
    if e.target_std_err_uv > 0.0 && e.min_samples() < e.samples {
        format!(
            "{}–{} (until σ(u′v′) ≤ {:e})",
            e.min_samples(),
            e.samples,
            e.target_std_err_uv
        )
    } else {
        e.samples.to_string()
    }
}

/// The emissive materials' common emission colour (the scene's light colour).
fn light_colour(scene: &Scene) -> DVec3 {
    scene
        .materials
        .iter()
        .find(|m| m.is_emissive())
        .map(|m| m.emission.as_dvec3())
        .unwrap_or(DVec3::ONE)
}

fn uv_of_rgb(rgb: DVec3) -> DVec2 {
    xyz_to_uv(rgb_to_xyz(rgb)).unwrap_or(DVec2::NAN)
}

fn d65_uv() -> DVec2 {
    xyz_to_uv(D65_XYZ).expect("D65 has a chromaticity")
}

struct Out {
    md: String,
    metrics: BTreeMap<String, f64>,
    claims: Vec<ClaimRun>,
}

impl Out {
    fn new() -> Out {
        Out {
            md: String::new(),
            metrics: BTreeMap::new(),
            claims: Vec::new(),
        }
    }

    fn metric(&mut self, k: impl Into<String>, v: f64) {
        self.metrics.insert(k.into(), v);
    }

    /// A claim of the paper and the checks that decide it (on this run's numbers).
    fn claim(&mut self, claim: &str, checks: Vec<Check>) {
        self.claims.push(ClaimRun {
            claim: claim.into(),
            checks,
        });
    }
}

/// Name of case 6's diagnostic estimator: `wcam` with the bench's pixels left out.
pub const WCAM_NO_BENCH: &str = "wcam_without_bench";

/// Extra per-frame readings and numbers a case needs besides the estimators. Case 6: `wcam`
/// recomputed without the pixels whose first hit lies on the glossy bench, and the bench's
/// share of WCAM's weighted luminance sum (`bench_share`), and its brightest pixel over the
/// image's 99th-percentile luminance (`bench_peak`), to test the paper's explanation of WCAM's
/// jump (a specular highlight on the bench).
pub(crate) fn diagnostics(
    case: &CaseInfo,
    job: &Job,
    view: &View,
    image: &Frame,
) -> (Vec<Named>, BTreeMap<String, f64>) {
    let mut diag = BTreeMap::new();
    if case.number != 6 {
        return (Vec::new(), diag);
    }
    let bench = Region::from_material(&job.scene, "bench", "bench", 0.0);
    let pad = glam::Vec3::splat(0.01);
    let px = pixels_in_box(image, view, bench.min - pad, bench.max + pad);
    let mut hit = image.hit.clone();
    for &i in &px {
        hit[i] = 0.0;
    }
    let aovs = FrameAovs {
        width: image.width,
        height: image.height,
        rgb: &image.rgb,
        albedo: &image.albedo,
        achromatic: &image.achromatic,
        irradiance: &image.irradiance,
        emitter: &image.emitter,
        hit: &hit,
        fov_y_deg: view.fov_deg as f64,
    };
    let opts = &job.estimator_config.wcam;
    let est = wcam(&aovs, opts);
    // The bench's share of Σ ω·Y(A) (the same weights as `wcam`, linear reading).
    let weight_y = |i: usize| {
        let cover = (image.hit[i] - image.emitter[i]).max(0.0) as f64;
        let rho = glam::Vec3::from(image.albedo[i]).as_dvec3();
        let a = glam::Vec3::from(image.achromatic[i]).as_dvec3();
        cover * (1.0 + opts.w * whiteness(rho)) * luminance(a)
    };
    let total: f64 = (0..image.width * image.height).map(weight_y).sum();
    let on_bench: f64 = px.iter().map(|&i| weight_y(i)).sum();
    diag.insert(
        "bench_share".into(),
        if total > 0.0 { on_bench / total } else { 0.0 },
    );
    diag.insert("bench_pixels".into(), px.len() as f64);
    // Does a highlight stand out on the bench: its brightest pixel against the 99th
    // percentile of the image's surface pixels (emitters left out).
    let lum = |i: usize| luminance(glam::Vec3::from(image.rgb[i]).as_dvec3());
    let mut surf: Vec<f64> = (0..image.width * image.height)
        .filter(|&i| image.hit[i] > 0.0 && image.emitter[i] == 0.0)
        .map(lum)
        .collect();
    surf.sort_by(f64::total_cmp);
    let p99 = surf
        .get((surf.len() as f64 * 0.99) as usize)
        .copied()
        .unwrap_or(f64::NAN);
    let peak = px.iter().map(|&i| lum(i)).fold(0.0, f64::max);
    diag.insert("bench_peak".into(), peak / p99);
    (
        vec![Named {
            name: WCAM_NO_BENCH,
            estimate: est,
        }],
        diag,
    )
}

/// Measures and judges one case.
pub(crate) fn evaluate(case: &'static CaseInfo, runs: &[JobRun]) -> Result<CaseReport, Failure> {
    let (claim, out) = match case.number {
        1 => case1::case1(runs),
        2 => case2::case2(runs),
        3 => case3::case3(runs),
        4 => case4::case4(runs),
        5 => case5::case5(runs),
        6 => case6::case6(runs)?,
        n => return Err(Failure::Input(format!("there is no paper case {n}"))),
    };
    Ok(CaseReport {
        info: case,
        paper_claim: claim.into(),
        markdown: out.md,
        metrics: out.metrics,
        claims: out.claims,
        verdicts: Vec::new(),
        study: None,
        sheet: None,
        plot: None,
    })
}

/// The rows of a case's contact sheet.
pub(crate) fn sheet_rows<'a>(
    case: &CaseInfo,
    runs: &'a [JobRun],
    report: &CaseReport,
) -> Vec<&'a Tiles> {
    let all: Vec<&Shot> = runs.iter().flat_map(|r| &r.shots).collect();
    if case.number != 6 {
        return all.iter().map(|s| &s.tiles).collect();
    }
    // The walkthrough: the paper's frames 5 and 10 (Fig. 15), the two frames around WCAM's
    // largest step overall, and the last frame.
    let pick = |frame: f64| -> Option<&'a Tiles> {
        runs[0]
            .shots
            .iter()
            .find(|s| s.frame as f64 == frame)
            .map(|s| &s.tiles)
    };
    let j = report
        .metrics
        .get("wcam.max_jump_frame")
        .copied()
        .unwrap_or(f64::NAN);
    let last = runs[0].shots.last().map_or(0.0, |s| s.frame as f64);
    let mut frames = vec![5.0, 10.0];
    if j.is_finite() && j != 5.0 && j != 10.0 {
        frames.extend([j - 1.0, j]);
    }
    frames.push(last);
    frames.into_iter().filter_map(pick).collect()
}

fn fmt3(v: DVec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
}
