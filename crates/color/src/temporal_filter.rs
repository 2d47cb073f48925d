//! A causal temporal adaptation filter: the eye does not re-adapt instantly when the scene's
//! white changes (estimators.md §8).
//!
//! The step response from an old white to a new one is modelled as two exponentials:
//! the fraction of adaptation still to do after t seconds is
//! `r(t) = a·e^{−t/τ_f} + (1−a)·e^{−t/τ_s}`.
//!
//! | preset | a | τ_f | τ_s | origin |
//! |---|---|---|---|---|
//! | `none` | – | – | – | the per-frame estimate is used as is (what \[GRC13\] does) |
//! | `fairchild` | 0.45 | 1.0 s | 41 s | fit to Fairchild & Reniff: 50 % at ≈4 s, 90 % at 70 s |
//! | `rinner` | 0.55 | 0.08 s | 28.9 s | Rinner & Gegenfurtner 2000 (slow half-life 20 s) |
//! | `artistic` | 0.5 | 0.25 s | 3 s | short walkthroughs |
//!
//! In a job file the filter is a preset name or a custom table (times in seconds):
//!
//! ```
//! # use eyeadapt_color::{FilterInit, TemporalFilter};
//! # #[derive(serde::Deserialize)] struct Job { temporal_filter: TemporalFilter, filter_init: FilterInit }
//! # let job: Job = toml::from_str(r#"
//! temporal_filter = "fairchild"          # none | fairchild | rinner | artistic
//! filter_init = "first_frame"            # or "d65"
//! # "#).unwrap();
//! # assert_eq!(job.temporal_filter, TemporalFilter::Fairchild);
//! # let job: Job = toml::from_str(r#"
//! temporal_filter = { a = 0.5, tau_f = 0.25, tau_s = 3.0 }
//! filter_init = "d65"
//! # "#).unwrap();
//! # assert_eq!(job.temporal_filter.to_string(), "custom(a=0.5 tau_f=0.25 tau_s=3)");
//! ```
//!
//! **Discretisation (§8.3).** Von Kries gains are multiplicative, so the filter runs on
//! `l_t = ln(M_CAT02 · W_t / Y_t)`: `F_t = F + α_f (l_t − F)`, `S_t = S + α_s (l_t − S)` with
//! `α = 1 − e^{−Δt/τ}`, and the output is `M⁻¹ exp(a F_t + (1−a) S_t)` renormalised to Y = 1.
//! Δt is the real time since the last update, so uneven frame times are exact: an input is
//! taken to have held since the previous update (the exact solution of the continuous filter
//! for an input that is constant over that interval), hence a white that changes at frame k
//! gives progress `1 − r(t − t_{k−1})` at every later frame, whatever the frame spacing.
//!
//! **Undefined frames** (no estimate, a non-finite value, or Y ≤ 0) leave the state untouched
//! and repeat the last output, flagged `undefined_input`; the time they span is charged to the
//! next defined input. Before any state exists (undefined first frames with `first_frame`
//! init), the output is D65, flagged `fallback_d65` too (§0). Cone responses below 1e-6
//! (including non-positive ones, which have no logarithm) are raised to 1e-6 and flagged
//! `clamped`.
//!
//! The filter is causal: the eye cannot see the future, so no forward–backward smoothing. On a
//! farm it must therefore run over the merged sequence, not per chunk.

use std::fmt;
use std::str::FromStr;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, Visitor};

/// CAT02 (XYZ → sharpened cone space) and its float64 inverse, estimators.md §6.2. These
/// duplicate the constants of the colour module's CAT code, written in parallel on another
/// branch; they are to be de-duplicated when the branches merge. (`0.182745179382773` is the
/// spec's `0.1827451793827730` without the trailing zero clippy objects to.)
const CAT02: [[f64; 3]; 3] = [
    [0.7328, 0.4296, -0.1624],
    [-0.7036, 1.6975, 0.0061],
    [0.0030, 0.0136, 0.9834],
];
const CAT02_INV: [[f64; 3]; 3] = [
    [1.0961238208355142, -0.2788690002182873, 0.182745179382773],
    [0.4543690419753592, 0.4735331543074118, 0.0720978037172291],
    [-0.0096276087384294, -0.0056980312161134, 1.0153256399545427],
];
/// D65 from xy (0.3127, 0.3290), Y = 1 (estimators.md §0).
const D65: [f64; 3] = [0.9504559270516716, 1.0, 1.0890577507598784];
/// Smallest cone response the log domain accepts.
const MIN_CONE: f64 = 1e-6;

/// Which adaptation time course to apply; deserialises from a preset name or a custom table.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum TemporalFilter {
    /// Identity: the per-frame estimate, normalised to Y = 1.
    #[default]
    None,
    Fairchild,
    Rinner,
    Artistic,
    Custom(FilterParams),
}

/// Parameters of `r(t) = a·e^{−t/τ_f} + (1−a)·e^{−t/τ_s}`; times in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterParams {
    /// Weight of the fast component, in [0, 1].
    pub a: f64,
    /// Fast time constant (s), ≥ 0; 0 is instantaneous.
    pub tau_f: f64,
    /// Slow time constant (s), ≥ 0.
    pub tau_s: f64,
}

impl FilterParams {
    fn check(&self) -> Result<(), FilterError> {
        let ok = (0.0..=1.0).contains(&self.a)
            && [self.tau_f, self.tau_s]
                .iter()
                .all(|t| t.is_finite() && *t >= 0.0);
        if ok {
            Ok(())
        } else {
            Err(FilterError::InvalidParams(*self))
        }
    }
}

impl TemporalFilter {
    /// The preset names, as accepted by `FromStr` and serde.
    pub const PRESETS: [&'static str; 4] = ["none", "fairchild", "rinner", "artistic"];

    /// The two-exponential parameters; `None` for the identity.
    pub fn params(&self) -> Option<FilterParams> {
        let p = |a, tau_f, tau_s| Some(FilterParams { a, tau_f, tau_s });
        match *self {
            TemporalFilter::None => None,
            TemporalFilter::Fairchild => p(0.45, 1.0, 41.0),
            TemporalFilter::Rinner => p(0.55, 0.08, 28.9),
            TemporalFilter::Artistic => p(0.5, 0.25, 3.0),
            TemporalFilter::Custom(params) => Some(params),
        }
    }
}

/// The name used in CSV estimator labels (`eye+filter:fairchild`). A custom filter prints its
/// parameters separated by spaces, not commas, so the label needs no CSV quoting.
impl fmt::Display for TemporalFilter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TemporalFilter::None => f.write_str("none"),
            TemporalFilter::Fairchild => f.write_str("fairchild"),
            TemporalFilter::Rinner => f.write_str("rinner"),
            TemporalFilter::Artistic => f.write_str("artistic"),
            TemporalFilter::Custom(p) => {
                write!(f, "custom(a={} tau_f={} tau_s={})", p.a, p.tau_f, p.tau_s)
            }
        }
    }
}

impl FromStr for TemporalFilter {
    type Err = FilterError;

    /// A preset name (custom parameters need the TOML table form).
    fn from_str(name: &str) -> Result<TemporalFilter, FilterError> {
        match name {
            "none" => Ok(TemporalFilter::None),
            "fairchild" => Ok(TemporalFilter::Fairchild),
            "rinner" => Ok(TemporalFilter::Rinner),
            "artistic" => Ok(TemporalFilter::Artistic),
            _ => Err(FilterError::UnknownPreset(name.to_string())),
        }
    }
}

/// Hand-written instead of `#[serde(untagged)]`, whose only error is "data did not match any
/// variant": this one names the unknown preset or the unknown field.
impl<'de> Deserialize<'de> for TemporalFilter {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<TemporalFilter, D::Error> {
        struct FilterVisitor;
        impl<'de> Visitor<'de> for FilterVisitor {
            type Value = TemporalFilter;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a preset name (none, fairchild, rinner, artistic) or a table { a, tau_f, tau_s }")
            }

            fn visit_str<E: de::Error>(self, name: &str) -> Result<TemporalFilter, E> {
                name.parse().map_err(E::custom)
            }

            fn visit_map<M: MapAccess<'de>>(self, map: M) -> Result<TemporalFilter, M::Error> {
                let params = FilterParams::deserialize(de::value::MapAccessDeserializer::new(map))?;
                params.check().map_err(de::Error::custom)?;
                Ok(TemporalFilter::Custom(params))
            }
        }
        deserializer.deserialize_any(FilterVisitor)
    }
}

/// What the observer is adapted to before the first frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterInit {
    /// Adapted to the first defined frame (§8.3 step 4): no transient at the start.
    #[default]
    FirstFrame,
    /// Adapted to D65 at the first frame's time, then adapting to the scene.
    D65,
}

/// Conditions met while producing one output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FilterFlags {
    /// The input was undefined; the output repeats the last one.
    pub undefined_input: bool,
    /// There was no last output either; the output is D65.
    pub fallback_d65: bool,
    /// A cone response was below 1e-6 and was raised to it.
    pub clamped: bool,
}

impl FilterFlags {
    pub fn is_empty(&self) -> bool {
        *self == FilterFlags::default()
    }
}

/// `|`-separated names of the raised flags (empty when none), for the CSV `flags` column.
impl fmt::Display for FilterFlags {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = [
            (self.undefined_input, "undefined_input"),
            (self.fallback_d65, "fallback_d65"),
            (self.clamped, "clamped"),
        ];
        let raised: Vec<&str> = names
            .iter()
            .filter(|(on, _)| *on)
            .map(|(_, n)| *n)
            .collect();
        f.write_str(&raised.join("|"))
    }
}

/// One filtered frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterOutput {
    /// The filtered adaptation white, XYZ with Y = 1.
    pub xyz: [f64; 3],
    pub flags: FilterFlags,
}

#[derive(Debug, Clone, PartialEq)]
pub enum FilterError {
    UnknownPreset(String),
    InvalidParams(FilterParams),
    /// Frame times must be finite and strictly increasing.
    TimeNotIncreasing {
        previous: f64,
        time: f64,
    },
    NonFiniteTime(f64),
}

impl fmt::Display for FilterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FilterError::UnknownPreset(name) => write!(
                f,
                "unknown temporal filter {name:?}: expected one of {} (or a table {{ a, tau_f, tau_s }} in a job file)",
                TemporalFilter::PRESETS.join(", ")
            ),
            FilterError::InvalidParams(p) => write!(
                f,
                "temporal filter parameters a = {}, tau_f = {}, tau_s = {}: need 0 <= a <= 1 and finite time constants >= 0 s",
                p.a, p.tau_f, p.tau_s
            ),
            FilterError::TimeNotIncreasing { previous, time } => {
                write!(
                    f,
                    "frame time {time} s does not follow the previous frame's {previous} s"
                )
            }
            FilterError::NonFiniteTime(t) => write!(f, "frame time {t} is not finite"),
        }
    }
}

impl std::error::Error for FilterError {}

/// `α = 1 − e^{−Δt/τ}`: the fraction of the way to the new input covered in Δt (1 for τ = 0).
pub fn smoothing_factor(dt: f64, tau: f64) -> f64 {
    // −expm1 keeps full precision for the tiny α of slow components (α_s ≈ 1e-3).
    -libm::expm1(-dt / tau)
}

/// The state of the filter; feed it frames in time order with [`AdaptationFilter::step`].
#[derive(Debug, Clone)]
pub struct AdaptationFilter {
    params: Option<FilterParams>,
    init: FilterInit,
    /// Fast and slow log-cone states and the time of their last update.
    state: Option<([f64; 3], [f64; 3], f64)>,
    last_time: Option<f64>,
    held: Option<[f64; 3]>,
}

impl AdaptationFilter {
    pub fn new(filter: TemporalFilter, init: FilterInit) -> Result<AdaptationFilter, FilterError> {
        let params = filter.params();
        if let Some(p) = params {
            p.check()?;
        }
        Ok(AdaptationFilter {
            params,
            init,
            state: None,
            last_time: None,
            held: None,
        })
    }

    /// Filters the adaptation white `xyz` (any luminance scale) estimated at `time` seconds;
    /// `None` marks an undefined estimate.
    pub fn step(&mut self, time: f64, xyz: Option<[f64; 3]>) -> Result<FilterOutput, FilterError> {
        if !time.is_finite() {
            return Err(FilterError::NonFiniteTime(time));
        }
        if let Some(previous) = self.last_time.filter(|&p| time <= p) {
            return Err(FilterError::TimeNotIncreasing { previous, time });
        }
        let first_frame = self.last_time.is_none();
        self.last_time = Some(time);
        if first_frame && self.init == FilterInit::D65 {
            self.held = Some(D65);
            let l = log_cones(D65).0;
            self.state = self.params.map(|_| (l, l, time));
        }

        let mut flags = FilterFlags::default();
        let Some(white) = xyz.filter(|w| w.iter().all(|c| c.is_finite()) && w[1] > 0.0) else {
            flags.undefined_input = true;
            flags.fallback_d65 = self.held.is_none();
            return Ok(FilterOutput {
                xyz: self.held.unwrap_or(D65),
                flags,
            });
        };
        let normalised = white.map(|c| c / white[1]);
        let out = match self.params {
            None => normalised,
            Some(p) => {
                let (l, clamped) = log_cones(normalised);
                flags.clamped = clamped;
                let (f, s, t) = self.state.get_or_insert((l, l, time));
                let (alpha_f, alpha_s) = (
                    smoothing_factor(time - *t, p.tau_f),
                    smoothing_factor(time - *t, p.tau_s),
                );
                // Δt = 0 on the initialising frame: α = 0 (or NaN for τ = 0, so skip it).
                if time > *t {
                    for c in 0..3 {
                        f[c] += alpha_f * (l[c] - f[c]);
                        s[c] += alpha_s * (l[c] - s[c]);
                    }
                    *t = time;
                }
                let mixed: [f64; 3] =
                    std::array::from_fn(|c| libm::exp(p.a * f[c] + (1.0 - p.a) * s[c]));
                let w = mul(&CAT02_INV, mixed);
                w.map(|c| c / w[1])
            }
        };
        self.held = Some(out);
        Ok(FilterOutput { xyz: out, flags })
    }
}

/// Filters a whole series of (time, white) frames from a fresh state.
pub fn filter_series(
    filter: TemporalFilter,
    init: FilterInit,
    frames: &[(f64, Option<[f64; 3]>)],
) -> Result<Vec<FilterOutput>, FilterError> {
    let mut state = AdaptationFilter::new(filter, init)?;
    frames.iter().map(|&(t, xyz)| state.step(t, xyz)).collect()
}

/// `ln(M_CAT02 · xyz)` with cones raised to [`MIN_CONE`]; the flag says whether any was.
fn log_cones(xyz: [f64; 3]) -> ([f64; 3], bool) {
    let cones = mul(&CAT02, xyz);
    let clamped = cones.iter().any(|&c| c < MIN_CONE);
    (cones.map(|c| libm::log(c.max(MIN_CONE))), clamped)
}

fn mul(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CIE illuminant A, xy (0.44758, 0.40745), Y = 1.
    const A: [f64; 3] = [0.44758 / 0.40745, 1.0, (1.0 - 0.44758 - 0.40745) / 0.40745];
    const PRESETS: [TemporalFilter; 4] = [
        TemporalFilter::None,
        TemporalFilter::Fairchild,
        TemporalFilter::Rinner,
        TemporalFilter::Artistic,
    ];

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        (0..3).all(|c| (a[c] - b[c]).abs() <= tol * b[c].abs().max(1.0))
    }

    /// Progress from A to D65 read from an output, in log-cone *ratios* so that the Y = 1
    /// renormalisation (a common shift of all three log cones) cancels.
    fn progress(w: [f64; 3]) -> f64 {
        let g = |w: [f64; 3]| {
            let c = mul(&CAT02, w);
            libm::log(c[0] / c[2])
        };
        (g(w) - g(A)) / (g(D65) - g(A))
    }

    /// Same, with the other cone pair: a linear filter moves all channels in step.
    fn progress_m(w: [f64; 3]) -> f64 {
        let g = |w: [f64; 3]| {
            let c = mul(&CAT02, w);
            libm::log(c[1] / c[2])
        };
        (g(w) - g(A)) / (g(D65) - g(A))
    }

    fn remaining(p: FilterParams, t: f64) -> f64 {
        p.a * libm::exp(-t / p.tau_f) + (1.0 - p.a) * libm::exp(-t / p.tau_s)
    }

    /// t with r(t) = 0.5, by bisection (r decreases monotonically).
    fn t50(p: FilterParams) -> f64 {
        let (mut lo, mut hi) = (0.0, 1000.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if remaining(p, mid) > 0.5 {
                lo = mid
            } else {
                hi = mid
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn cat02_inverse_matches_the_forward_matrix() {
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for (j, unit) in identity.into_iter().enumerate() {
            let product = mul(&CAT02, CAT02_INV.map(|row| row[j]));
            assert!(close(product, unit, 1e-15), "column {j}: {product:?}");
        }
    }

    #[test]
    fn alpha_slow_for_25_fps_and_41_s() {
        assert!((smoothing_factor(1.0 / 25.0, 41.0) - 9.751e-4).abs() < 5e-8);
        assert_eq!(smoothing_factor(0.04, 0.0), 1.0);
        assert!((smoothing_factor(1.0, 1.0) - (1.0 - libm::exp(-1.0f64))).abs() < 1e-16);
    }

    #[test]
    fn none_is_the_identity() {
        let inputs = [
            [0.9, 2.0, 1.3],
            [0.0, 1.0, 10.0],
            [5.0, 0.5, 0.1],
            [1e-9, 3e-9, 2e-9],
        ];
        let frames: Vec<_> = inputs
            .iter()
            .enumerate()
            .map(|(i, w)| (i as f64 / 24.0, Some(*w)))
            .collect();
        let out = filter_series(TemporalFilter::None, FilterInit::FirstFrame, &frames).unwrap();
        for (o, w) in out.iter().zip(inputs) {
            assert_eq!(o.xyz, w.map(|c| c / w[1]));
            assert!(o.flags.is_empty());
        }
    }

    #[test]
    fn constant_input_gives_itself() {
        for filter in PRESETS {
            for white in [A, D65, [95.0, 100.0, 60.0]] {
                let frames: Vec<_> = (0..500).map(|i| (i as f64 / 25.0, Some(white))).collect();
                for o in filter_series(filter, FilterInit::FirstFrame, &frames).unwrap() {
                    assert!(
                        close(o.xyz, white.map(|c| c / white[1]), 1e-12),
                        "{filter}: {:?}",
                        o.xyz
                    );
                    assert!(o.flags.is_empty());
                }
            }
        }
    }

    /// A → D65 at frame 10 of a 25 fps sequence. The D65 input of frame 10 stands for the
    /// interval since frame 9, so progress at frame n is 1 − r(t_n − t_9) exactly, and the
    /// 50 % point falls within one frame of the preset's t₅₀.
    #[test]
    fn step_response_reaches_half_at_t50() {
        let fps = 25.0;
        for filter in [
            TemporalFilter::Fairchild,
            TemporalFilter::Rinner,
            TemporalFilter::Artistic,
        ] {
            let p = filter.params().unwrap();
            let frames: Vec<_> = (0..2000)
                .map(|i| (i as f64 / fps, Some(if i < 10 { A } else { D65 })))
                .collect();
            let out = filter_series(filter, FilterInit::FirstFrame, &frames).unwrap();
            let step_time = 9.0 / fps;
            for (n, o) in out.iter().enumerate().skip(10) {
                let expected = 1.0 - remaining(p, frames[n].0 - step_time);
                assert!(
                    (progress(o.xyz) - expected).abs() < 1e-9,
                    "{filter} frame {n}"
                );
                assert!(
                    (progress_m(o.xyz) - expected).abs() < 1e-9,
                    "{filter} frame {n} (M/S)"
                );
            }
            let half = out.iter().position(|o| progress(o.xyz) >= 0.5).unwrap();
            let reached = frames[half].0 - step_time;
            let target = t50(p);
            assert!(
                (reached - target).abs() <= 1.0 / fps,
                "{filter}: 50 % at {reached} s, t50 = {target} s"
            );
            assert!(
                out[..10].iter().all(|o| progress(o.xyz).abs() < 1e-12),
                "{filter} before the step"
            );
        }
        // Fairchild's fit: about half-way after 4-5 s, 90 % by 70 s.
        let p = TemporalFilter::Fairchild.params().unwrap();
        assert!((4.0..5.0).contains(&t50(p)));
        assert!(1.0 - remaining(p, 70.0) > 0.9);
    }

    #[test]
    fn uneven_frame_times_are_exact() {
        let p = TemporalFilter::Artistic.params().unwrap();
        let mut t = 0.0;
        let mut frames = vec![(t, Some(A))];
        for i in 0..300 {
            t += 0.01 + 0.07 * ((i * 37 % 11) as f64 / 10.0);
            frames.push((t, Some(D65)));
        }
        let out = filter_series(TemporalFilter::Artistic, FilterInit::FirstFrame, &frames).unwrap();
        for n in 1..frames.len() {
            let expected = 1.0 - remaining(p, frames[n].0 - frames[0].0);
            assert!((progress(out[n].xyz) - expected).abs() < 1e-9, "frame {n}");
        }
    }

    #[test]
    fn undefined_frames_hold_and_their_time_is_not_lost() {
        let fps = 25.0;
        let mut frames: Vec<_> = (0..100)
            .map(|i| (i as f64 / fps, Some(if i < 10 { A } else { D65 })))
            .collect();
        let complete =
            filter_series(TemporalFilter::Fairchild, FilterInit::FirstFrame, &frames).unwrap();
        frames[20].1 = None;
        frames[21].1 = Some([f64::NAN, 1.0, 1.0]);
        frames[22].1 = Some([0.9, 0.0, 1.0]);
        frames[23].1 = Some([0.9, -1.0, 1.0]);
        let gappy =
            filter_series(TemporalFilter::Fairchild, FilterInit::FirstFrame, &frames).unwrap();
        for n in 20..24 {
            assert_eq!(gappy[n].xyz, gappy[19].xyz, "frame {n} holds");
            assert!(gappy[n].flags.undefined_input && !gappy[n].flags.fallback_d65);
        }
        // Under a constant input, dropping frames changes nothing afterwards.
        for n in 24..100 {
            assert!(close(gappy[n].xyz, complete[n].xyz, 1e-12), "frame {n}");
            assert!(gappy[n].flags.is_empty());
        }
    }

    #[test]
    fn undefined_first_frames_fall_back_to_d65() {
        let frames = [(0.0, None), (0.04, None), (0.08, Some(A)), (0.12, Some(A))];
        let out =
            filter_series(TemporalFilter::Fairchild, FilterInit::FirstFrame, &frames).unwrap();
        for o in &out[..2] {
            assert_eq!(o.xyz, D65);
            assert!(o.flags.undefined_input && o.flags.fallback_d65);
            assert_eq!(o.flags.to_string(), "undefined_input|fallback_d65");
        }
        assert!(
            close(out[2].xyz, A, 1e-12) && close(out[3].xyz, A, 1e-12),
            "adapted to the first defined frame"
        );
        let identity =
            filter_series(TemporalFilter::None, FilterInit::FirstFrame, &frames).unwrap();
        assert_eq!(identity[0].xyz, D65);
        assert!(identity[0].flags.fallback_d65);
    }

    #[test]
    fn d65_init_starts_adapted_to_d65() {
        let frames: Vec<_> = (0..300).map(|i| (i as f64 / 25.0, Some(A))).collect();
        let out = filter_series(TemporalFilter::Artistic, FilterInit::D65, &frames).unwrap();
        assert!(close(out[0].xyz, D65, 1e-12), "frame 0 is D65");
        assert!(out[0].flags.is_empty());
        let p = TemporalFilter::Artistic.params().unwrap();
        // Progress towards A after t seconds, measured as a fraction of the D65 → A distance.
        for n in [1, 10, 100, 299] {
            let towards_a = 1.0 - progress(out[n].xyz);
            assert!(
                (towards_a - (1.0 - remaining(p, frames[n].0))).abs() < 1e-9,
                "frame {n}"
            );
        }
    }

    #[test]
    fn non_positive_cones_are_clamped_and_flagged() {
        // X = 0, Z = 10: the L cone 0.4296 − 1.624 is negative.
        let bluish = [0.0, 1.0, 10.0];
        assert!(mul(&CAT02, bluish)[0] < 0.0);
        let frames = [(0.0, Some(D65)), (0.5, Some(bluish)), (1.0, Some(D65))];
        let out = filter_series(TemporalFilter::Artistic, FilterInit::FirstFrame, &frames).unwrap();
        assert!(out[1].flags.clamped && !out[0].flags.clamped && !out[2].flags.clamped);
        assert_eq!(out[1].flags.to_string(), "clamped");
        for o in &out {
            assert!(
                o.xyz.iter().all(|c| c.is_finite()) && o.xyz[1] == 1.0,
                "{:?}",
                o.xyz
            );
        }
    }

    #[test]
    fn times_must_increase() {
        let mut f =
            AdaptationFilter::new(TemporalFilter::Fairchild, FilterInit::FirstFrame).unwrap();
        f.step(1.0, Some(A)).unwrap();
        assert_eq!(
            f.step(1.0, Some(A)).unwrap_err().to_string(),
            "frame time 1 s does not follow the previous frame's 1 s"
        );
        assert_eq!(
            f.step(f64::NAN, None).unwrap_err().to_string(),
            "frame time NaN is not finite"
        );
        f.step(2.0, None).unwrap();
        assert!(
            f.step(1.5, Some(A)).is_err(),
            "undefined frames count as seen"
        );
    }

    #[test]
    fn preset_names_parse_and_print() {
        for name in TemporalFilter::PRESETS {
            assert_eq!(name.parse::<TemporalFilter>().unwrap().to_string(), name);
        }
        assert_eq!(
            "fairchil"
                .parse::<TemporalFilter>()
                .unwrap_err()
                .to_string(),
            "unknown temporal filter \"fairchil\": expected one of none, fairchild, rinner, artistic (or a table { a, tau_f, tau_s } in a job file)"
        );
        assert_eq!(
            TemporalFilter::Rinner.params(),
            Some(FilterParams {
                a: 0.55,
                tau_f: 0.08,
                tau_s: 28.9
            })
        );
        assert_eq!(TemporalFilter::default(), TemporalFilter::None);
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Job {
        temporal_filter: TemporalFilter,
        #[serde(default)]
        filter_init: FilterInit,
    }

    fn job(src: &str) -> Result<Job, String> {
        toml::from_str(src).map_err(|e| e.to_string())
    }

    #[test]
    fn deserialises_names_and_custom_tables() {
        let j = job("temporal_filter = \"rinner\"").unwrap();
        assert_eq!(
            (j.temporal_filter, j.filter_init),
            (TemporalFilter::Rinner, FilterInit::FirstFrame)
        );
        let j = job("temporal_filter = { a = 1, tau_f = 0, tau_s = 10 }\nfilter_init = \"d65\"")
            .unwrap();
        assert_eq!(
            j.temporal_filter,
            TemporalFilter::Custom(FilterParams {
                a: 1.0,
                tau_f: 0.0,
                tau_s: 10.0
            })
        );
        assert_eq!(j.filter_init, FilterInit::D65);
        let cases = [
            (
                "temporal_filter = \"fast\"",
                "unknown temporal filter \"fast\": expected one of none, fairchild",
            ),
            (
                "temporal_filter = { a = 0.5, tau_f = 1, tau_s = 2, tau_x = 3 }",
                "unknown field `tau_x`",
            ),
            (
                "temporal_filter = { a = 0.5, tau_f = 1 }",
                "missing field `tau_s`",
            ),
            (
                "temporal_filter = { a = 1.5, tau_f = 1, tau_s = 2 }",
                "need 0 <= a <= 1",
            ),
            (
                "temporal_filter = { a = 0.5, tau_f = -1, tau_s = 2 }",
                "tau_f = -1",
            ),
            (
                "temporal_filter = 3",
                "a preset name (none, fairchild, rinner, artistic) or a table",
            ),
            (
                "temporal_filter = \"none\"\nfilter_init = \"scene\"",
                "unknown variant `scene`",
            ),
        ];
        for (src, needle) in cases {
            let err = job(src).unwrap_err();
            assert!(err.contains(needle), "{src}:\n{err}");
        }
    }

    #[test]
    fn custom_params_are_checked_when_used_directly() {
        let bad = TemporalFilter::Custom(FilterParams {
            a: 0.5,
            tau_f: f64::NAN,
            tau_s: 1.0,
        });
        assert!(matches!(
            AdaptationFilter::new(bad, FilterInit::FirstFrame),
            Err(FilterError::InvalidParams(_))
        ));
        // a = 1, τ_f = 0 is the identity up to the log/exp round trip.
        let instant = TemporalFilter::Custom(FilterParams {
            a: 1.0,
            tau_f: 0.0,
            tau_s: 5.0,
        });
        let frames = [
            (0.0, Some(A)),
            (0.1, Some(D65)),
            (0.2, Some([95.0, 100.0, 60.0])),
        ];
        let out = filter_series(instant, FilterInit::FirstFrame, &frames).unwrap();
        for (o, (_, w)) in out.iter().zip(frames) {
            let w = w.unwrap();
            assert!(close(o.xyz, w.map(|c| c / w[1]), 1e-12));
        }
    }
}
