//! Claims, the checks that decide them, and verdicts with their uncertainty.
//!
//! A claim is decided by one or more [`Check`]s, each "this measured value must be above (or
//! below) that bound". Measured over several seeds, a check's value has a mean and a standard
//! error; its margin (how far the mean is on the right side of the bound) is compared with
//! `t · se`, `t` the two-sided 95 % Student quantile for the number of seeds. A check then
//! holds, does not hold, or is within noise; a claim holds when all its checks hold, does not
//! hold when any does not, and is within noise otherwise.
//!
//! Verdict text prints the value, its standard error, the bound it needs to clear and the
//! signed margin — never an inequality between two measured numbers, which could be false
//! (issue 22: "eye 5.33 < WCAM 5.31").

/// What a claim needs of one measured value.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is measured, e.g. "eye − WCAM mean checker ΔE00".
    pub what: String,
    pub value: f64,
    pub bound: f64,
    /// The claim needs `value > bound` (true) or `value < bound` (false).
    pub above: bool,
}

/// `value` must exceed `bound`.
pub fn above(what: impl Into<String>, value: f64, bound: f64) -> Check {
    Check {
        what: what.into(),
        value,
        bound,
        above: true,
    }
}

/// `value` must stay below `bound`.
pub fn below(what: impl Into<String>, value: f64, bound: f64) -> Check {
    Check {
        what: what.into(),
        value,
        bound,
        above: false,
    }
}

/// One claim as measured by one run (one configuration, one seed).
#[derive(Clone, Debug, PartialEq)]
pub struct ClaimRun {
    pub claim: String,
    pub checks: Vec<Check>,
}

/// Holds, does not hold, or cannot be told apart from zero at the seeds' noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Outcome {
    Holds,
    WithinNoise,
    DoesNotHold,
}

impl Outcome {
    pub fn label(self) -> &'static str {
        match self {
            Outcome::Holds => "holds",
            Outcome::WithinNoise => "within noise",
            Outcome::DoesNotHold => "does not hold",
        }
    }
}

/// A check over seeds: mean, standard error of the mean, margin and outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckStat {
    pub what: String,
    pub mean: f64,
    pub se: f64,
    pub bound: f64,
    pub above: bool,
    pub seeds: usize,
    pub outcome: Outcome,
}

impl CheckStat {
    /// How far the mean is on the claim's side of the bound (negative: on the wrong side).
    pub fn margin(&self) -> f64 {
        if self.above {
            self.mean - self.bound
        } else {
            self.bound - self.mean
        }
    }

    /// E.g. "eye − WCAM = +0.021 ± 0.013 (needs < 0; margin −0.021 ± 0.013, 4 seeds)".
    pub fn describe(&self) -> String {
        format!(
            "{} = {} ± {} (needs {} {}; margin {} ± {})",
            self.what,
            num(self.mean),
            num(self.se),
            if self.above { ">" } else { "<" },
            num(self.bound),
            signed(self.margin()),
            num(self.se)
        )
    }
}

/// A claim decided over seeds.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    pub claim: String,
    pub checks: Vec<CheckStat>,
    pub outcome: Outcome,
    pub seeds: usize,
}

impl Verdict {
    pub fn holds(&self) -> bool {
        self.outcome == Outcome::Holds
    }

    /// The checks, described, joined by "; ".
    pub fn test(&self) -> String {
        self.checks
            .iter()
            .map(CheckStat::describe)
            .collect::<Vec<_>>()
            .join("; ")
    }
}

/// Two-sided 95 % quantile of Student's t with `dof` degrees of freedom (the normal's 1.96
/// beyond 30).
pub fn t95(dof: usize) -> f64 {
    const T: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match dof {
        0 => f64::INFINITY,
        d if d <= 30 => T[d - 1],
        _ => 1.96,
    }
}

/// Mean and standard error of the mean; NaN when any value is not finite.
pub fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len();
    if n == 0 || xs.iter().any(|x| !x.is_finite()) {
        return (f64::NAN, f64::NAN);
    }
    let m = xs.iter().sum::<f64>() / n as f64;
    if n == 1 {
        return (m, 0.0);
    }
    let var = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1) as f64;
    (m, (var / n as f64).sqrt())
}

/// Decides the claims of one configuration from its runs (one per seed, each with the same
/// claims and checks in the same order).
pub fn decide(runs: &[Vec<ClaimRun>]) -> Vec<Verdict> {
    let Some(first) = runs.first() else {
        return Vec::new();
    };
    let seeds = runs.len();
    let t = t95(seeds.saturating_sub(1));
    first
        .iter()
        .enumerate()
        .map(|(ci, claim)| {
            let checks: Vec<CheckStat> = claim
                .checks
                .iter()
                .enumerate()
                .map(|(ki, c)| {
                    let xs: Vec<f64> = runs.iter().map(|r| r[ci].checks[ki].value).collect();
                    let (mean, se) = mean_se(&xs);
                    let mut s = CheckStat {
                        what: c.what.clone(),
                        mean,
                        se,
                        bound: c.bound,
                        above: c.above,
                        seeds,
                        outcome: Outcome::DoesNotHold,
                    };
                    let m = s.margin();
                    s.outcome = if !m.is_finite() {
                        Outcome::DoesNotHold
                    } else if m > t * se {
                        Outcome::Holds
                    } else if m < -t * se {
                        Outcome::DoesNotHold
                    } else {
                        Outcome::WithinNoise
                    };
                    s
                })
                .collect();
            let outcome = checks
                .iter()
                .map(|c| c.outcome)
                .max()
                .unwrap_or(Outcome::Holds);
            Verdict {
                claim: claim.claim.clone(),
                checks,
                outcome,
                seeds,
            }
        })
        .collect()
}

/// Three significant digits, plain decimals between 1e-4 and 1e5, else scientific.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-4..1e5).contains(&a) {
        return format!("{v:.2e}");
    }
    let digits = (2 - libm::log10(a).floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

fn signed(v: f64) -> String {
    let s = num(v);
    if v > 0.0 { format!("+{s}") } else { s }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(value: f64) -> Vec<ClaimRun> {
        vec![ClaimRun {
            claim: "eye beats WCAM".into(),
            checks: vec![below("eye − WCAM", value, 0.0)],
        }]
    }

    #[test]
    fn a_margin_inside_the_noise_is_within_noise_not_a_verdict() {
        // Mean +0.01, se 0.0058 (3 seeds): the claim "below 0" is neither shown nor refuted.
        let v = decide(&[run(0.0), run(0.01), run(0.02)]);
        assert_eq!(v[0].outcome, Outcome::WithinNoise);
        // Far on the right side, or far on the wrong side.
        assert_eq!(
            decide(&[run(-1.0), run(-1.01), run(-0.99)])[0].outcome,
            Outcome::Holds
        );
        assert_eq!(
            decide(&[run(1.0), run(1.01), run(0.99)])[0].outcome,
            Outcome::DoesNotHold
        );
    }

    #[test]
    fn verdict_text_states_the_requirement_and_the_signed_margin_not_a_false_inequality() {
        // The audit's example: eye 5.33 and WCAM 5.31, claim "eye below WCAM".
        let v = decide(&[run(0.0199), run(0.02), run(0.0201)]);
        let text = v[0].test();
        assert_eq!(v[0].outcome, Outcome::DoesNotHold);
        assert!(text.contains("needs < 0"), "{text}");
        assert!(text.contains("margin -0.0200"), "{text}");
        assert!(!text.contains("5.33 <"), "{text}");
    }

    #[test]
    fn one_seed_cannot_decide_and_an_undefined_value_does_not_hold() {
        assert_eq!(decide(&[run(-1.0)])[0].outcome, Outcome::WithinNoise);
        assert_eq!(decide(&[run(f64::NAN)])[0].outcome, Outcome::DoesNotHold);
    }

    #[test]
    fn a_claim_is_as_good_as_its_worst_check() {
        let r = |a: f64, b: f64| {
            vec![ClaimRun {
                claim: "two".into(),
                checks: vec![above("a", a, 0.0), above("b", b, 0.0)],
            }]
        };
        let v = decide(&[r(1.0, 0.01), r(1.0, -0.01), r(1.0, 0.0)]);
        assert_eq!(v[0].checks[0].outcome, Outcome::Holds);
        assert_eq!(v[0].outcome, Outcome::WithinNoise);
    }

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(num(0.0123456), "0.0123");
        assert_eq!(num(5.3312), "5.33");
        assert_eq!(num(292.4), "292");
        assert_eq!(num(2.5e-6), "2.50e-6");
        assert_eq!(t95(2), 4.303);
    }
}
