//! The answer at the top of the report: `eye` against each field-of-view estimator, as ratios
//! eye ÷ other of three §7 magnitudes (largest step, mean step, mean dE_cat) with a 95 %
//! bootstrap interval over frames, and a one-line reading of each.
//!
//! The ratios use the frames where both series are defined. The interval is a moving-block
//! bootstrap (blocks of ⌈n^⅓⌉ consecutive frames, so the frame-to-frame correlation of the
//! steps is kept; 1000 resamples, the same frames for both estimators; percentiles 2.5 and
//! 97.5). The resampling is seeded, so a report is the same every time it is run.
use crate::coherence::EstimatorReport;

/// A ratio eye ÷ other with its interval; NaN where undefined (e.g. the other never moves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ratio {
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
}

impl Ratio {
    const UNDEFINED: Ratio = Ratio {
        value: f64::NAN,
        lo: f64::NAN,
        hi: f64::NAN,
    };
}

/// eye against one estimator.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub name: String,
    pub base: String,
    pub max_step: Ratio,
    pub mean_step: Ratio,
    /// `None` without image metrics.
    pub de_cat_mean: Option<Ratio>,
    /// The other estimator's white never moved (every defined step is 0).
    pub never_moves: bool,
}

const RESAMPLES: usize = 1000;

/// splitmix64: a small, seeded generator, enough for resampling.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn mean(v: &mut dyn Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

fn max(v: &mut dyn Iterator<Item = f64>) -> f64 {
    v.fold(f64::NAN, f64::max)
}

fn quotient(a: f64, b: f64) -> f64 {
    if a.is_finite() && b.is_finite() && b > 0.0 {
        a / b
    } else {
        f64::NAN
    }
}

/// `stat(eye) / stat(other)` over the paired values, with its moving-block bootstrap interval.
pub fn ratio(
    pairs: &[(f64, f64)],
    stat: fn(&mut dyn Iterator<Item = f64>) -> f64,
    seed: u64,
) -> Ratio {
    let n = pairs.len();
    if n == 0 {
        return Ratio::UNDEFINED;
    }
    let of = |idx: &mut dyn Iterator<Item = usize>| {
        let (a, b): (Vec<f64>, Vec<f64>) = idx.map(|i| pairs[i]).unzip();
        quotient(stat(&mut a.into_iter()), stat(&mut b.into_iter()))
    };
    let value = of(&mut (0..n));
    if !value.is_finite() {
        return Ratio::UNDEFINED;
    }
    let block = libm::cbrt(n as f64).ceil() as usize;
    let starts = n - block + 1;
    let mut rng = Rng(seed);
    let mut samples: Vec<f64> = (0..RESAMPLES)
        .map(|_| {
            let mut idx = Vec::with_capacity(n + block);
            while idx.len() < n {
                let s = rng.below(starts);
                idx.extend(s..s + block);
            }
            idx.truncate(n);
            of(&mut idx.into_iter())
        })
        .filter(|v| v.is_finite())
        .collect();
    if samples.is_empty() {
        return Ratio {
            value,
            lo: f64::NAN,
            hi: f64::NAN,
        };
    }
    samples.sort_by(f64::total_cmp);
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q).round() as usize];
    Ratio {
        value,
        lo: at(0.025),
        hi: at(0.975),
    }
}

fn pairs(
    eye: &EstimatorReport,
    other: &EstimatorReport,
    value: &dyn Fn(&EstimatorReport, usize) -> f64,
) -> Vec<(f64, f64)> {
    (0..eye.steps.len().min(other.steps.len()))
        .map(|k| (value(eye, k), value(other, k)))
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .collect()
}

/// eye against every other per-frame estimator (filtered series are left out).
pub fn compare(reports: &[EstimatorReport]) -> Vec<Comparison> {
    let Some(eye) = reports.iter().find(|r| r.name == "eye") else {
        return Vec::new();
    };
    let de_cat = |r: &EstimatorReport, k: usize| {
        r.image.as_ref().map_or(f64::NAN, |m| m.per_frame[k].de_cat)
    };
    let step = |r: &EstimatorReport, k: usize| r.steps[k];
    reports
        .iter()
        .filter(|r| r.filter.is_none() && r.name != "eye")
        .enumerate()
        .map(|(i, r)| {
            let seed = 0x5EED_0000 + i as u64;
            let steps = pairs(eye, r, &step);
            let image = eye.image.is_some() && r.image.is_some();
            Comparison {
                name: r.name.clone(),
                base: r.base.clone(),
                max_step: ratio(&steps, max, seed),
                mean_step: ratio(&steps, mean, seed),
                de_cat_mean: image.then(|| ratio(&pairs(eye, r, &de_cat), mean, seed)),
                never_moves: !steps.is_empty() && steps.iter().all(|p| p.1 == 0.0),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratio_of_a_scaled_copy_is_the_scale_with_a_tight_interval() {
        let pairs: Vec<(f64, f64)> = (0..60)
            .map(|k| {
                let b = 1.0 + libm::sin(k as f64 * 0.7).abs();
                (0.5 * b, b)
            })
            .collect();
        let r = ratio(&pairs, mean, 1);
        assert!(
            (r.value - 0.5).abs() < 1e-12 && (r.lo - 0.5).abs() < 1e-12,
            "{r:?}"
        );
        assert!((r.hi - 0.5).abs() < 1e-12, "{r:?}");
    }

    #[test]
    fn the_interval_brackets_the_value_and_is_reproducible() {
        // eye's steps are noisy halves of the other's: the interval has width, holds the value.
        let pairs: Vec<(f64, f64)> = (0..120)
            .map(|k| {
                let b = 1.0 + libm::sin(k as f64).abs();
                (b * (0.5 + 0.3 * libm::cos(k as f64 * 2.3)), b)
            })
            .collect();
        let a = ratio(&pairs, mean, 7);
        assert!(
            a.lo < a.value && a.value < a.hi && a.hi - a.lo > 0.01,
            "{a:?}"
        );
        assert!(a.lo > 0.3 && a.hi < 0.7, "{a:?}");
        assert_eq!(a, ratio(&pairs, mean, 7));
        let m = ratio(&pairs, max, 7);
        assert!(m.lo <= m.value && m.value <= m.hi, "{m:?}");
    }

    #[test]
    fn an_estimator_that_never_moves_has_no_ratio() {
        let pairs = vec![(0.1, 0.0); 10];
        assert!(ratio(&pairs, mean, 1).value.is_nan());
        assert!(ratio(&[], mean, 1).value.is_nan());
    }
}
