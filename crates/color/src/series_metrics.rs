//! Temporal-coherence metrics of one estimator's adaptation-colour series (estimators.md §7.2).
//!
//! The input is one [`SeriesPoint`] per frame: the frame number, its time, the chromaticity
//! `p = (u′, v′)` of the estimated adaptation white (or `None` when the estimate was undefined)
//! and optionally its Monte-Carlo standard error. Every distance is Euclidean in u′v′ ("duv"
//! in units below, i.e. Δu′v′).
//!
//! **Segments.** An undefined point, or a frame number that is not the previous one plus one,
//! ends a segment: no step, acceleration or jerk is ever taken across a hole, and the low-pass
//! filter of `hf_rms` never reads across one. Per-segment results are combined so that a series
//! cut in two by a gap reads like the same series without the missing stretch:
//! - steps `d_t`, accelerations and jerks are *pooled* over all segments before taking means,
//!   percentiles, maxima, RMS and threshold counts (so `n_jumps(θ)` fractions are over all
//!   steps, the §7.2 "fraction of N−1" with N−1 summed over segments);
//! - `total_variation` and `net_displacement` are *sums* of the per-segment values, and
//!   `tortuosity = Σ TV / max(Σ net, 1e-6)` — a net-displacement-weighted mean of the
//!   per-segment tortuosities;
//! - `hf_rms` pools squared residuals over all defined points (a one-point segment has residual
//!   0 and still counts as a point);
//! - `noise_floor` is the median over all defined points that carry a standard error.
//!
//! A metric with nothing to measure (no steps, a segment too short for a jerk, no standard
//! errors) is NaN, as §0 asks for undefined values; counts are then 0.
//!
//! **Smoothing for `hf_rms`.** A normalised Gaussian of σ = σ_s·fps frames, truncated at
//! R = ⌈3σ⌉, with mirror padding `p₋ₖ = pₖ`, `p_{N−1+k} = p_{N−1−k}` (the edge sample is not
//! repeated). When a segment is shorter than the kernel the mirroring is simply repeated (the
//! index reflects back and forth between the segment's ends, i.e. the segment is extended as an
//! even periodic signal of period 2(N−1)), so every segment of two or more points is filtered
//! with the full kernel; a one-point segment is its own mean.

use std::fmt;

/// Δu′v′ thresholds of §7.1: one MacAdam step, a display JND, the 7-step LED binning limit.
pub const DEFAULT_THRESHOLDS: [f64; 3] = [0.001, 0.004, 0.007];
/// Gaussian σ in seconds for `hf_rms` (its −3 dB point is at about 0.27 Hz).
pub const DEFAULT_SIGMA_S: f64 = 0.5;
/// Widest smoothing Gaussian, σ in frames (σ_s·fps): its kernel has 2⌈3σ⌉+1 weights, so the
/// bound keeps a huge σ_s or fps an error instead of an allocation that cannot succeed.
pub const MAX_SIGMA_FRAMES: f64 = 100_000.0;

/// One frame of an adaptation-colour series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesPoint {
    pub frame: u32,
    /// Seconds; only used to report when the largest jump happened.
    pub time: f64,
    /// (u′, v′) of the estimate; `None` (or a non-finite value) when it was undefined.
    pub uv: Option<[f64; 2]>,
    /// Standard error of u′ and v′, when the estimator provides one.
    pub std_err: Option<[f64; 2]>,
}

/// Parameters of [`series_metrics`]; [`SeriesParams::new`] gives the §10 defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesParams {
    pub fps: f64,
    /// Gaussian σ in seconds for `hf_rms`; 0 disables smoothing (hf_rms = 0).
    pub sigma_s: f64,
    /// Step thresholds for `n_jumps`, in Δu′v′.
    pub thresholds: Vec<f64>,
}

impl SeriesParams {
    pub fn new(fps: f64) -> SeriesParams {
        SeriesParams {
            fps,
            sigma_s: DEFAULT_SIGMA_S,
            thresholds: DEFAULT_THRESHOLDS.to_vec(),
        }
    }
}

/// How many steps exceed one threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpCount {
    pub threshold: f64,
    /// `#{t : d_t > threshold}`.
    pub count: usize,
    /// `count / n_steps` (NaN without steps).
    pub fraction: f64,
}

/// Every §7.2 metric of one series. See the module docs for how segments are combined.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesMetrics {
    /// Defined points.
    pub n_points: usize,
    pub n_segments: usize,
    /// Frame-to-frame steps inside segments.
    pub n_steps: usize,
    /// duv/frame.
    pub mean_step: f64,
    /// 95th percentile of the steps, linear interpolation between order statistics (NumPy's
    /// default): rank 0.95·(n−1). duv/frame.
    pub p95_step: f64,
    /// Largest step, duv/frame.
    pub max_jump: f64,
    /// Frame (and time) *reached* by the largest step; the first one on ties.
    pub max_jump_frame: Option<u32>,
    pub max_jump_time: Option<f64>,
    /// fps · max_jump, duv/s.
    pub speed_max: f64,
    /// Path length, duv.
    pub total_variation: f64,
    /// duv.
    pub net_displacement: f64,
    /// total_variation / max(net_displacement, 1e-6); 1 for a straight monotone path.
    pub tortuosity: f64,
    /// ‖p_{t+1} − 2p_t + p_{t−1}‖, duv/frame².
    pub accel_rms: f64,
    pub accel_max: f64,
    /// ‖p_{t+2} − 3p_{t+1} + 3p_t − p_{t−1}‖, duv/frame³.
    pub jerk_rms: f64,
    /// One entry per threshold, in the order given.
    pub jumps: Vec<JumpCount>,
    /// RMS of p − Gaussian-smoothed p, duv.
    pub hf_rms: f64,
    /// Median of √2·‖std_err‖: the RMS step noise alone would give a static scene, duv.
    pub noise_floor: f64,
}

/// One line of a metrics CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct MetricRow {
    pub name: String,
    pub value: f64,
    pub unit: &'static str,
}

impl SeriesMetrics {
    /// Every metric as (name, value, unit), in a fixed order, for `coherence.csv`. Units are
    /// ASCII: `duv` is Δu′v′, `1` is dimensionless; a frame number is given as a value with
    /// unit `frame` (NaN when there was no step).
    pub fn rows(&self) -> Vec<MetricRow> {
        let row = |name: &str, value: f64, unit| MetricRow {
            name: name.to_string(),
            value,
            unit,
        };
        let mut rows = vec![
            row("n_points", self.n_points as f64, "count"),
            row("n_segments", self.n_segments as f64, "count"),
            row("n_steps", self.n_steps as f64, "count"),
            row("mean_step", self.mean_step, "duv/frame"),
            row("p95_step", self.p95_step, "duv/frame"),
            row("max_jump", self.max_jump, "duv/frame"),
            row(
                "max_jump_frame",
                self.max_jump_frame.map_or(f64::NAN, f64::from),
                "frame",
            ),
            row("max_jump_time", self.max_jump_time.unwrap_or(f64::NAN), "s"),
            row("speed_max", self.speed_max, "duv/s"),
            row("total_variation", self.total_variation, "duv"),
            row("net_displacement", self.net_displacement, "duv"),
            row("tortuosity", self.tortuosity, "1"),
            row("accel_rms", self.accel_rms, "duv/frame^2"),
            row("accel_max", self.accel_max, "duv/frame^2"),
            row("jerk_rms", self.jerk_rms, "duv/frame^3"),
        ];
        for jump in &self.jumps {
            rows.push(row(
                &format!("n_jumps_{}", jump.threshold),
                jump.count as f64,
                "count",
            ));
            rows.push(row(
                &format!("frac_jumps_{}", jump.threshold),
                jump.fraction,
                "1",
            ));
        }
        rows.push(row("hf_rms", self.hf_rms, "duv"));
        rows.push(row("noise_floor", self.noise_floor, "duv"));
        rows
    }
}

/// Why [`series_metrics`] refused its input.
#[derive(Debug, Clone, PartialEq)]
pub enum SeriesError {
    InvalidFps(f64),
    InvalidSigma(f64),
    /// σ_s·fps is more than [`MAX_SIGMA_FRAMES`] frames.
    SigmaTooWide {
        sigma_s: f64,
        fps: f64,
    },
    InvalidThreshold(f64),
    /// Frame numbers must strictly increase; `index` is the offending point.
    FramesNotIncreasing {
        index: usize,
        previous: u32,
        frame: u32,
    },
}

impl fmt::Display for SeriesError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SeriesError::InvalidFps(v) => write!(f, "fps must be a positive number, got {v}"),
            SeriesError::InvalidSigma(v) => {
                write!(
                    f,
                    "sigma_s must be a non-negative number of seconds, got {v}"
                )
            }
            SeriesError::SigmaTooWide { sigma_s, fps } => write!(
                f,
                "sigma_s {sigma_s:e} s at {fps} fps is a Gaussian of σ = {:e} frames, more than the \
                 {MAX_SIGMA_FRAMES} frames a series is smoothed with",
                sigma_s * fps
            ),
            SeriesError::InvalidThreshold(v) => {
                write!(f, "jump threshold must be a non-negative number, got {v}")
            }
            SeriesError::FramesNotIncreasing {
                index,
                previous,
                frame,
            } => write!(
                f,
                "series point {index}: frame {frame} does not follow frame {previous} (frames must increase)"
            ),
        }
    }
}

impl std::error::Error for SeriesError {}

/// Computes every §7.2 metric of `points` (in frame order).
pub fn series_metrics(
    points: &[SeriesPoint],
    params: &SeriesParams,
) -> Result<SeriesMetrics, SeriesError> {
    if !(params.fps.is_finite() && params.fps > 0.0) {
        return Err(SeriesError::InvalidFps(params.fps));
    }
    if !(params.sigma_s.is_finite() && params.sigma_s >= 0.0) {
        return Err(SeriesError::InvalidSigma(params.sigma_s));
    }
    if params.sigma_s * params.fps > MAX_SIGMA_FRAMES {
        return Err(SeriesError::SigmaTooWide {
            sigma_s: params.sigma_s,
            fps: params.fps,
        });
    }
    if let Some(&bad) = params
        .thresholds
        .iter()
        .find(|t| !(t.is_finite() && **t >= 0.0))
    {
        return Err(SeriesError::InvalidThreshold(bad));
    }
    for (index, pair) in points.windows(2).enumerate() {
        if pair[1].frame <= pair[0].frame {
            let (previous, frame) = (pair[0].frame, pair[1].frame);
            return Err(SeriesError::FramesNotIncreasing {
                index: index + 1,
                previous,
                frame,
            });
        }
    }

    let kernel = gaussian_kernel(params.sigma_s * params.fps);
    let mut steps = Vec::new();
    let mut max_jump: Option<(f64, &SeriesPoint)> = None;
    let (mut accel, mut jerk) = (Vec::new(), Vec::new());
    let (mut total_variation, mut net_displacement) = (0.0, 0.0);
    let (mut hf_sum_sq, mut n_points, mut n_segments) = (0.0, 0, 0);

    for segment in segments(points) {
        let p: Vec<[f64; 2]> = segment
            .iter()
            .map(|s| s.uv.expect("segments are defined"))
            .collect();
        n_points += p.len();
        n_segments += 1;
        for (k, w) in p.windows(2).enumerate() {
            let d = norm(sub(w[1], w[0]));
            steps.push(d);
            total_variation += d;
            if max_jump.is_none_or(|(best, _)| d > best) {
                max_jump = Some((d, &segment[k + 1]));
            }
        }
        net_displacement += norm(sub(p[p.len() - 1], p[0]));
        accel.extend(
            p.windows(3)
                .map(|w| norm(sub(add(w[2], w[0]), scale(w[1], 2.0)))),
        );
        jerk.extend(p.windows(4).map(|w| {
            // p_{t+2} − 3p_{t+1} + 3p_t − p_{t−1}
            norm(sub(add(w[3], scale(sub(w[1], w[2]), 3.0)), w[0]))
        }));
        hf_sum_sq += high_pass_residuals(&p, &kernel)
            .map(|r| r[0] * r[0] + r[1] * r[1])
            .sum::<f64>();
    }

    let n_steps = steps.len();
    let jumps = params
        .thresholds
        .iter()
        .map(|&threshold| {
            let count = steps.iter().filter(|&&d| d > threshold).count();
            JumpCount {
                threshold,
                count,
                fraction: count as f64 / n_steps as f64,
            }
        })
        .collect();
    let noise: Vec<f64> = points
        .iter()
        .filter(|p| defined(p))
        .filter_map(|p| p.std_err)
        .filter(|se| se.iter().all(|v| v.is_finite()))
        .map(|se| std::f64::consts::SQRT_2 * norm(se))
        .collect();
    let max_jump_value = max_jump.map_or(f64::NAN, |(d, _)| d);
    Ok(SeriesMetrics {
        n_points,
        n_segments,
        n_steps,
        mean_step: mean(&steps),
        p95_step: percentile(steps.clone(), 0.95),
        max_jump: max_jump_value,
        max_jump_frame: max_jump.map(|(_, p)| p.frame),
        max_jump_time: max_jump.map(|(_, p)| p.time),
        speed_max: params.fps * max_jump_value,
        total_variation,
        net_displacement,
        tortuosity: total_variation / net_displacement.max(1e-6),
        accel_rms: rms(&accel),
        accel_max: accel.iter().copied().reduce(f64::max).unwrap_or(f64::NAN),
        jerk_rms: rms(&jerk),
        jumps,
        hf_rms: (hf_sum_sq / n_points as f64).sqrt(),
        noise_floor: percentile(noise, 0.5),
    })
}

fn defined(p: &SeriesPoint) -> bool {
    p.uv.is_some_and(|uv| uv.iter().all(|v| v.is_finite()))
}

/// Maximal runs of defined points with consecutive frame numbers.
fn segments(points: &[SeriesPoint]) -> Vec<&[SeriesPoint]> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, p) in points.iter().enumerate() {
        let continues =
            i > 0 && defined(&points[i - 1]) && points[i - 1].frame.checked_add(1) == Some(p.frame);
        if let Some(s) = start.filter(|_| !(continues && defined(p))) {
            out.push(&points[s..i]);
            start = None;
        }
        if defined(p) && start.is_none() {
            start = Some(i);
        }
    }
    if let Some(s) = start {
        out.push(&points[s..]);
    }
    out
}

/// Normalised Gaussian weights w_{−R..=R}, R = ⌈3σ⌉ (σ in frames); σ = 0 gives the identity.
fn gaussian_kernel(sigma: f64) -> Vec<f64> {
    if sigma == 0.0 {
        return vec![1.0];
    }
    let radius = (3.0 * sigma).ceil() as i64;
    let weights: Vec<f64> = (-radius..=radius)
        .map(|k| libm::exp(-(k * k) as f64 / (2.0 * sigma * sigma)))
        .collect();
    let total: f64 = weights.iter().sum();
    weights.into_iter().map(|w| w / total).collect()
}

/// Index of sample `k` of a length-`n` segment under repeated mirror padding (`p₋ₖ = pₖ`).
fn mirror(k: i64, n: usize) -> usize {
    if n == 1 {
        return 0;
    }
    let period = 2 * (n as i64 - 1);
    let k = k.rem_euclid(period);
    (if k < n as i64 { k } else { period - k }) as usize
}

/// `p_t − (G_σ * p)_t` for every t. Written as `−Σ_k w_k (p_{t+k} − p_t)` (equal because the
/// weights sum to 1): a constant segment then gives exactly 0, and nothing is lost to
/// cancellation between two values near 0.2–0.5 that differ in the fifth digit.
fn high_pass_residuals<'a>(
    p: &'a [[f64; 2]],
    kernel: &'a [f64],
) -> impl Iterator<Item = [f64; 2]> + 'a {
    let radius = (kernel.len() / 2) as i64;
    (0..p.len()).map(move |t| {
        let mut r = [0.0; 2];
        for (j, w) in kernel.iter().enumerate() {
            let q = p[mirror(t as i64 + j as i64 - radius, p.len())];
            r[0] -= w * (q[0] - p[t][0]);
            r[1] -= w * (q[1] - p[t][1]);
        }
        r
    })
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

/// Linear-interpolation percentile (`q` in [0, 1]); NaN for an empty list.
fn percentile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let rank = q * (v.len() - 1) as f64;
    let (lo, frac) = (rank.floor() as usize, rank.fract());
    match v.get(lo + 1) {
        Some(hi) => v[lo] + (hi - v[lo]) * frac,
        None => v[lo],
    }
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn scale(a: [f64; 2], s: f64) -> [f64; 2] {
    [a[0] * s, a[1] * s]
}

fn norm(a: [f64; 2]) -> f64 {
    libm::hypot(a[0], a[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const FPS: f64 = 24.0;

    /// Frames 0..n at FPS, u′v′ from `f(frame)`, no standard errors.
    fn series(n: u32, f: impl Fn(u32) -> [f64; 2]) -> Vec<SeriesPoint> {
        (0..n)
            .map(|i| SeriesPoint {
                frame: i,
                time: i as f64 / FPS,
                uv: Some(f(i)),
                std_err: None,
            })
            .collect()
    }

    fn metrics(points: &[SeriesPoint]) -> SeriesMetrics {
        series_metrics(points, &SeriesParams::new(FPS)).unwrap()
    }

    #[test]
    fn constant_series_gives_zero_everywhere() {
        let mut points = series(100, |_| [0.1978300066, 0.4683199949]);
        for p in &mut points {
            p.std_err = Some([0.0, 0.0]);
        }
        let m = metrics(&points);
        for row in m.rows() {
            if ![
                "n_points",
                "n_segments",
                "n_steps",
                "max_jump_frame",
                "max_jump_time",
            ]
            .contains(&row.name.as_str())
            {
                assert_eq!(row.value, 0.0, "{}", row.name);
            }
        }
        assert_eq!((m.n_points, m.n_segments, m.n_steps), (100, 1, 99));
    }

    #[test]
    fn linear_ramp_is_a_straight_path() {
        // Binary fractions keep every difference exact, so acceleration is exactly zero.
        let v = [2f64.powi(-12), -(2f64.powi(-13))];
        let m = metrics(&series(200, |i| {
            [0.25 + v[0] * i as f64, 0.5 + v[1] * i as f64]
        }));
        let step = norm(v);
        assert!((m.total_variation - m.net_displacement).abs() <= 1e-15);
        assert!((m.net_displacement - 199.0 * step).abs() <= 1e-15);
        assert!((m.tortuosity - 1.0).abs() <= 1e-12);
        assert_eq!((m.accel_rms, m.accel_max, m.jerk_rms), (0.0, 0.0, 0.0));
        assert!((m.mean_step - step).abs() <= 1e-16 && (m.p95_step - step).abs() <= 1e-16);
        assert!((m.speed_max - FPS * step).abs() <= 1e-15);
    }

    #[test]
    fn single_step_is_found_at_its_frame_and_counted_once() {
        let s = 0.005;
        let m = metrics(&series(48, |i| {
            if i < 30 {
                [0.2, 0.47]
            } else {
                [0.2 + s * 0.6, 0.47 - s * 0.8]
            }
        }));
        assert!((m.max_jump - s).abs() < 1e-15);
        assert_eq!(m.max_jump_frame, Some(30));
        assert_eq!(m.max_jump_time, Some(30.0 / FPS));
        let counts: Vec<usize> = m.jumps.iter().map(|j| j.count).collect();
        assert_eq!(counts, [1, 1, 0], "thresholds {DEFAULT_THRESHOLDS:?}");
        assert!((m.jumps[0].fraction - 1.0 / 47.0).abs() < 1e-15);
        assert!((m.total_variation - s).abs() < 1e-15 && (m.tortuosity - 1.0).abs() < 1e-9);
        // The step shows as two accelerations of size s and three jerks (s, 2s, s).
        assert!((m.accel_max - s).abs() < 1e-15);
        assert!((m.accel_rms - (2.0 * s * s / 46.0).sqrt()).abs() < 1e-15);
        assert!((m.jerk_rms - (6.0 * s * s / 45.0).sqrt()).abs() < 1e-15);
        assert_eq!(
            m.p95_step, 0.0,
            "one step in 47 is below the 95th percentile"
        );
    }

    /// hf_rms of u′ = A sin(2π f₀ t): the Gaussian passes exp(−2π² f₀² σ_s²) of the amplitude,
    /// the residual keeps the rest, and a sinusoid's RMS is its amplitude / √2. Measured: 0.27 %
    /// off at 1 Hz, 0.98 % at 0.3 Hz (the edges of the mirrored 100 s series and the kernel's
    /// 3σ truncation account for it).
    #[test]
    fn sinusoid_residual_matches_gaussian_attenuation() {
        let amplitude = 0.01;
        for f0 in [1.0, 0.3] {
            let m = metrics(&series(2400, |i| {
                [
                    0.2 + amplitude * libm::sin(2.0 * PI * f0 * i as f64 / FPS),
                    0.47,
                ]
            }));
            let gain = libm::exp(-2.0 * PI * PI * f0 * f0 * DEFAULT_SIGMA_S * DEFAULT_SIGMA_S);
            let expected = amplitude * (1.0 - gain) / 2f64.sqrt();
            let error = (m.hf_rms - expected).abs() / expected;
            assert!(
                error < 0.05,
                "f0 = {f0} Hz: hf_rms {} vs {expected} ({:.2} %)",
                m.hf_rms,
                100.0 * error
            );
        }
    }

    #[test]
    fn gaps_and_undefined_frames_split_segments() {
        // Frames 0-9 at one colour, 10-14 missing, 15-24 far away, frame 20 undefined.
        let mut points: Vec<SeriesPoint> =
            series(25, |i| if i < 10 { [0.2, 0.47] } else { [0.25, 0.5] })
                .into_iter()
                .filter(|p| !(10..15).contains(&p.frame))
                .collect();
        points.iter_mut().find(|p| p.frame == 20).unwrap().uv = None;
        let m = metrics(&points);
        assert_eq!((m.n_points, m.n_segments, m.n_steps), (19, 3, 9 + 4 + 3));
        assert_eq!(m.max_jump, 0.0, "no step across the gap");
        assert_eq!(m.total_variation, 0.0);
        assert_eq!(
            m.hf_rms, 0.0,
            "the smoother does not read across the gap either"
        );
        // A non-finite value counts as undefined too.
        points[3].uv = Some([f64::NAN, 0.47]);
        assert_eq!(metrics(&points).n_segments, 4);
    }

    #[test]
    fn segments_combine_by_pooling_and_summing() {
        // Two ramps of different lengths separated by a hole: TV and net add up, tortuosity 1.
        // Binary step sizes (2⁻¹⁰ ≈ 0.00098, 2⁻⁹ ≈ 0.00195) keep every step exact.
        let (small, large) = (2f64.powi(-10), 2f64.powi(-9));
        let mut points = series(10, |i| [0.25 + small * i as f64, 0.375]);
        points.extend((20..25).map(|i| SeriesPoint {
            frame: i,
            time: i as f64 / FPS,
            uv: Some([0.125, 0.5 + large * (i - 20) as f64]),
            std_err: None,
        }));
        let m = metrics(&points);
        let tv = 9.0 * small + 4.0 * large;
        assert_eq!(
            (m.total_variation, m.net_displacement, m.tortuosity),
            (tv, tv, 1.0)
        );
        assert_eq!(m.mean_step, tv / 13.0);
        assert_eq!(
            m.max_jump_frame,
            Some(21),
            "first of the equal largest steps"
        );
        assert_eq!(m.jumps[0].count, 4, "only the 2⁻⁹ steps exceed 0.001");
    }

    #[test]
    fn short_segments_mirror_repeatedly() {
        assert_eq!(
            (-5..=8).map(|k| mirror(k, 3)).collect::<Vec<_>>(),
            [1, 0, 1, 2, 1, 0, 1, 2, 1, 0, 1, 2, 1, 0]
        );
        assert_eq!(mirror(-40, 1), 0);
        // Three points and a kernel of 73 taps: [a, b, a] mirrors into a, b, a, b, … whose
        // low-pass is the mean, so every residual is ±(b − a)/2.
        let m = metrics(&series(3, |i| {
            [0.2 + if i == 1 { 0.01 } else { 0.0 }, 0.47]
        }));
        // (Up to the 3σ truncation: the cut tails pass 3e-4 of the alternation.)
        assert!((m.hf_rms - 0.005).abs() < 0.005 * 1e-3, "{}", m.hf_rms);
        let single = metrics(&series(1, |_| [0.2, 0.47]));
        assert_eq!((single.hf_rms, single.n_steps), (0.0, 0));
        assert!(single.mean_step.is_nan() && single.max_jump.is_nan() && single.accel_rms.is_nan());
        assert_eq!(single.max_jump_frame, None);
    }

    #[test]
    fn kernel_is_normalised_and_truncated_at_three_sigma() {
        let k = gaussian_kernel(12.0);
        assert_eq!(k.len(), 2 * 36 + 1);
        assert!((k.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(
            (k[36] / k[0] - libm::exp(4.5f64)).abs() < 1e-9,
            "tail weight exp(-9/2)"
        );
        assert_eq!(gaussian_kernel(0.1).len(), 3);
        assert_eq!(gaussian_kernel(0.0), [1.0]);
    }

    #[test]
    fn noise_floor_is_the_median_scaled_by_root_two() {
        let mut points = series(4, |_| [0.2, 0.47]);
        let errs = [[0.0003, 0.0004], [0.0, 0.001], [0.006, 0.008], [0.0, 0.0]];
        for (p, e) in points.iter_mut().zip(errs) {
            p.std_err = Some(e);
        }
        points[3].std_err = None;
        // Norms 0.0005, 0.001, 0.01 → median 0.001.
        let m = metrics(&points);
        assert!((m.noise_floor - 2f64.sqrt() * 0.001).abs() < 1e-15);
        assert!(metrics(&series(4, |_| [0.2, 0.47])).noise_floor.is_nan());
    }

    #[test]
    fn percentile_interpolates_linearly() {
        let v: Vec<f64> = (0..=20).map(f64::from).collect();
        assert_eq!(percentile(v.clone(), 0.95), 19.0);
        assert_eq!(percentile(vec![1.0, 2.0], 0.95), 1.95);
        assert_eq!(percentile(vec![3.0, 1.0, 2.0], 0.5), 2.0);
        assert!(percentile(vec![], 0.5).is_nan());
    }

    #[test]
    fn rows_list_every_metric_with_units() {
        let m = metrics(&series(10, |i| [0.2 + 0.002 * i as f64, 0.47]));
        let rows = m.rows();
        let names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "n_points",
                "n_segments",
                "n_steps",
                "mean_step",
                "p95_step",
                "max_jump",
                "max_jump_frame",
                "max_jump_time",
                "speed_max",
                "total_variation",
                "net_displacement",
                "tortuosity",
                "accel_rms",
                "accel_max",
                "jerk_rms",
                "n_jumps_0.001",
                "frac_jumps_0.001",
                "n_jumps_0.004",
                "frac_jumps_0.004",
                "n_jumps_0.007",
                "frac_jumps_0.007",
                "hf_rms",
                "noise_floor",
            ]
        );
        let speed = rows.iter().find(|r| r.name == "speed_max").unwrap();
        assert_eq!(speed.unit, "duv/s");
        assert!((speed.value - 0.048).abs() < 1e-12);
    }

    #[test]
    fn invalid_input_is_refused() {
        let points = series(3, |_| [0.2, 0.47]);
        let with = |f: fn(&mut SeriesParams)| {
            let mut p = SeriesParams::new(FPS);
            f(&mut p);
            series_metrics(&points, &p).unwrap_err().to_string()
        };
        assert_eq!(
            with(|p| p.fps = 0.0),
            "fps must be a positive number, got 0"
        );
        assert_eq!(
            with(|p| p.sigma_s = -1.0),
            "sigma_s must be a non-negative number of seconds, got -1"
        );
        // A window too wide to allocate is refused before the kernel is built.
        assert!(
            with(|p| p.sigma_s = 1e18).contains("σ = 2.4e19 frames, more than the 100000"),
            "{}",
            with(|p| p.sigma_s = 1e18)
        );
        assert_eq!(
            with(|p| p.thresholds = vec![f64::NAN]),
            "jump threshold must be a non-negative number, got NaN"
        );
        let mut swapped = points.clone();
        swapped.swap(1, 2);
        assert_eq!(
            series_metrics(&swapped, &SeriesParams::new(FPS))
                .unwrap_err()
                .to_string(),
            "series point 2: frame 1 does not follow frame 2 (frames must increase)"
        );
        let mut custom = SeriesParams::new(FPS);
        custom.sigma_s = 0.0;
        custom.thresholds = vec![0.0];
        let m = series_metrics(
            &series(5, |i| [0.2 + 0.001 * f64::from(i % 2), 0.47]),
            &custom,
        )
        .unwrap();
        assert_eq!(m.hf_rms, 0.0);
        assert_eq!(m.jumps[0].count, 4);
    }
}
