//! The sensitivity study: every case over what the paper's text leaves open.
//!
//! A case's [`Param`]s each have levels; the first level of every parameter is the baseline
//! (the design fixed from the paper's words before any run, docs/paper.md). The grid is their
//! product, minus combinations that make no sense (a closed box with the camera outside it).
//! Every configuration runs with several seeds, and [`crate::verdict::decide`] turns the
//! seeds' checks into one verdict per claim. A claim is **robust** when it holds in at least
//! 80 % of the configurations.
use crate::verdict::{Outcome, Verdict};

/// Template placeholders that are not template values but estimator options of the job: the
/// WCAM weight reading (estimators.md §2.2 (d)) and WCAM's specular mode (§2.3).
pub const WCAM_WEIGHT: &str = "wcam_weight";
pub const WCAM_SPECULAR: &str = "wcam_specular";

/// One value of a parameter: its label and what it sets.
#[derive(Clone, Debug)]
pub struct Level {
    pub label: String,
    /// (placeholder, value) pairs for the scene and job templates, or `WCAM_WEIGHT` and
    /// `WCAM_SPECULAR`.
    pub fill: Vec<(&'static str, String)>,
}

pub(crate) fn level(label: impl Into<String>, fill: &[(&'static str, String)]) -> Level {
    Level {
        label: label.into(),
        fill: fill.to_vec(),
    }
}

/// Something the paper's text leaves open.
#[derive(Clone, Debug)]
pub struct Param {
    pub name: &'static str,
    pub levels: Vec<Level>,
}

/// One point of the grid: a level index per parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    pub levels: Vec<usize>,
    pub labels: Vec<String>,
    pub fill: Vec<(&'static str, String)>,
}

impl Config {
    pub fn get(&self, key: &str) -> Option<&str> {
        self.fill
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }

    /// "camera z −0.8 m, box open", or "baseline" for a grid with no parameter.
    pub fn describe(&self, params: &[Param]) -> String {
        if params.is_empty() {
            return "baseline".into();
        }
        params
            .iter()
            .zip(&self.labels)
            .map(|(p, l)| format!("{} {l}", p.name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// A directory name: the level indices, e.g. `c0-1-0`.
    pub fn slug(&self) -> String {
        let parts: Vec<String> = self.levels.iter().map(|l| l.to_string()).collect();
        format!("c{}", parts.join("-"))
    }
}

/// The grid's configurations, the baseline first, those `keep` rejects left out.
pub fn grid(params: &[Param], keep: fn(&Config) -> bool) -> Vec<Config> {
    let mut out = vec![Config {
        levels: Vec::new(),
        labels: Vec::new(),
        fill: Vec::new(),
    }];
    for p in params {
        out = out
            .into_iter()
            .flat_map(|c| {
                p.levels.iter().enumerate().map(move |(i, l)| {
                    let mut c = c.clone();
                    c.levels.push(i);
                    c.labels.push(l.label.clone());
                    c.fill.extend(l.fill.iter().cloned());
                    c
                })
            })
            .collect();
    }
    out.retain(keep);
    out
}

/// Seeds per configuration.
pub fn seeds(quick: bool, base: u64) -> Vec<u64> {
    let n = if quick { 3 } else { 4 };
    (0..n).map(|k| base + k).collect()
}

/// A case's study: its grid and one verdict per claim per configuration.
#[derive(Clone, Debug)]
pub struct Study {
    pub params: Vec<Param>,
    pub configs: Vec<(Config, Vec<Verdict>)>,
    pub seeds: Vec<u64>,
}

impl Study {
    pub fn baseline(&self) -> &[Verdict] {
        self.configs.first().map_or(&[], |(_, v)| v.as_slice())
    }

    /// How many configurations give `claim` the outcome `o`, out of how many.
    pub fn count(&self, claim: usize, o: Outcome) -> (usize, usize) {
        let n = self
            .configs
            .iter()
            .filter(|(_, v)| v.get(claim).is_some_and(|v| v.outcome == o))
            .count();
        (n, self.configs.len())
    }

    /// The fraction of configurations with level `level` of parameter `param` in which
    /// `claim` holds (NaN when there are none).
    pub fn level_fraction(&self, claim: usize, param: usize, level: usize) -> f64 {
        let at: Vec<&Vec<Verdict>> = self
            .configs
            .iter()
            .filter(|(c, _)| c.levels.get(param) == Some(&level))
            .map(|(_, v)| v)
            .collect();
        let holds = at
            .iter()
            .filter(|v| v.get(claim).is_some_and(Verdict::holds))
            .count();
        holds as f64 / at.len() as f64
    }

    /// "robust: holds in 12 of 12 configurations (100 %)", "fragile: …", "does not hold: …".
    pub fn robustness(&self, claim: usize) -> String {
        let (h, n) = self.count(claim, Outcome::Holds);
        let (w, _) = self.count(claim, Outcome::WithinNoise);
        let frac = h as f64 / n.max(1) as f64;
        let word = if frac >= 0.8 {
            "robust"
        } else if h > 0 {
            "fragile"
        } else {
            "does not hold"
        };
        let noise = if w > 0 {
            format!("; within noise in {w}")
        } else {
            String::new()
        };
        format!(
            "{word}: holds in {h} of {n} configuration{} ({:.0} %){noise}",
            if n == 1 { "" } else { "s" },
            100.0 * frac
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grids::case_grid;

    #[test]
    fn the_baseline_comes_first_and_a_closed_box_needs_the_camera_inside() {
        let (params, configs) = case_grid(3, false);
        assert_eq!(configs[0].levels, vec![0; params.len()]);
        assert_eq!(configs[0].get("camera_z"), Some("-0.8"));
        assert!(configs.iter().all(crate::grids::case3_keep));
        // 3 distances × 3 heights open, 3 heights closed (inside only), × 2 WCAM readings.
        assert_eq!(configs.len(), (9 + 3) * 2);
        let (_, quick) = case_grid(3, true);
        assert_eq!(quick.len(), 3);
    }

    #[test]
    fn every_configuration_fills_its_templates_into_a_scene_that_loads() {
        for case in crate::CASES {
            for quick in [true, false] {
                let (_, configs) = case_grid(case.number, quick);
                for c in &configs {
                    for (name, job, scene) in case.jobs {
                        let job = crate::shot::fill_template(job, c, name).unwrap();
                        assert!(job.contains("scene ="), "{name}");
                        if let Some(t) = scene {
                            let text = crate::shot::fill_template(t, c, name).unwrap();
                            // Beside the templates, where the files they read are.
                            let path = std::path::Path::new(concat!(
                                env!("CARGO_MANIFEST_DIR"),
                                "/../../paper/scenes/scene.toml"
                            ));
                            if let Err(e) = eyeadapt_scene::load_scene_str(&text, path) {
                                panic!("case {} {:?}: {e:?}", case.number, c.labels);
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn an_unfilled_placeholder_is_an_error_naming_it() {
        let c = Config {
            levels: vec![],
            labels: vec![],
            fill: vec![("a", "1".into())],
        };
        assert_eq!(
            crate::shot::fill_template("x = {{a}}", &c, "t").unwrap(),
            "x = 1"
        );
        let e = crate::shot::fill_template("x = {{b}}", &c, "t").unwrap_err();
        assert!(format!("{e}").contains("{{b}}"), "{e}");
    }

    #[test]
    fn every_case_has_a_grid() {
        for n in 1..=6 {
            for q in [true, false] {
                let (p, c) = case_grid(n, q);
                assert!(!c.is_empty() && !p.is_empty(), "case {n} quick {q}");
            }
        }
    }
}
