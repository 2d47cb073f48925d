//! The resolved settings of a run, as the manifest records them for reports and people.
//!
//! On disk they are a JSON object of strings, sorted by key (`"spp": "16"`), the form every
//! manifest has had; in memory they are typed, and a manifest whose settings are missing,
//! unknown or malformed is refused when it is read, naming the setting.
use crate::job::Job;
use eyeadapt_color::{Cat, TemporalFilter};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Display;
use std::str::FromStr;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    try_from = "BTreeMap<String, String>",
    into = "BTreeMap<String, String>"
)]
pub struct RunSettings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: i32,
    pub rr_depth: u32,
    pub seed: u64,
    pub fps: f64,
    pub cat: Cat,
    /// Degree of adaptation D in [0, 1].
    pub degree: f64,
    pub eye_samples: u32,
    pub eye_min_samples: u32,
    pub eye_target_std_err_uv: f64,
    pub eye_common_random_numbers: bool,
    pub wcam_w: f64,
    /// The job's temporal filter presets, in the job's order.
    pub temporal_filters: Vec<TemporalFilter>,
    /// Preview exposure in stops.
    pub exposure: f32,
    /// The scene as the job named it (`builtin:NAME` or a path).
    pub scene: String,
}

impl RunSettings {
    pub fn of_job(job: &Job) -> RunSettings {
        let eye = &job.estimator_config.eye;
        RunSettings {
            width: job.width,
            height: job.height,
            spp: job.spp,
            max_depth: job.path_settings.max_depth,
            rr_depth: job.path_settings.rr_depth,
            seed: job.seed,
            fps: job.path.fps(),
            cat: job.adaptation.cat,
            degree: job.adaptation.degree,
            eye_samples: eye.samples,
            eye_min_samples: eye.min_samples(),
            eye_target_std_err_uv: eye.target_std_err_uv,
            eye_common_random_numbers: eye.common_random_numbers,
            wcam_w: job.estimator_config.wcam.w,
            // The job validated every name.
            temporal_filters: job
                .temporal
                .filters
                .iter()
                .filter_map(|f| f.parse().ok())
                .collect(),
            exposure: job.exposure,
            scene: job.scene.source.display().to_string(),
        }
    }

    /// Every setting as `(key, text)`, sorted by key: what the manifest holds.
    pub fn entries(&self) -> BTreeMap<String, String> {
        self.clone().into()
    }
}

impl From<RunSettings> for BTreeMap<String, String> {
    fn from(s: RunSettings) -> Self {
        let filters: Vec<String> = s.temporal_filters.iter().map(|f| f.to_string()).collect();
        [
            ("resolution", format!("{}x{}", s.width, s.height)),
            ("spp", s.spp.to_string()),
            ("max_depth", s.max_depth.to_string()),
            ("rr_depth", s.rr_depth.to_string()),
            ("seed", s.seed.to_string()),
            ("fps", s.fps.to_string()),
            ("cat", s.cat.to_string()),
            ("degree", s.degree.to_string()),
            ("eye_samples", s.eye_samples.to_string()),
            ("eye_min_samples", s.eye_min_samples.to_string()),
            ("eye_target_std_err_uv", s.eye_target_std_err_uv.to_string()),
            (
                "eye_common_random_numbers",
                s.eye_common_random_numbers.to_string(),
            ),
            ("wcam_w", s.wcam_w.to_string()),
            ("temporal_filters", filters.join(",")),
            ("exposure", s.exposure.to_string()),
            ("scene", s.scene),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}

impl TryFrom<BTreeMap<String, String>> for RunSettings {
    type Error = String;

    fn try_from(mut m: BTreeMap<String, String>) -> Result<Self, String> {
        let resolution = take::<String>(&mut m, "resolution")?;
        let (width, height) = resolution
            .split_once('x')
            .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
            .ok_or_else(|| format!("manifest setting resolution {resolution:?} is not WxH"))?;
        let degree: f64 = take(&mut m, "degree")?;
        if !(0.0..=1.0).contains(&degree) {
            return Err(format!(
                "manifest setting degree \"{degree}\" is not in [0, 1]"
            ));
        }
        let filters = take::<String>(&mut m, "temporal_filters")?;
        let temporal_filters = filters
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|f| {
                f.parse::<TemporalFilter>()
                    .map_err(|e| format!("manifest setting temporal_filters: {e}"))
            })
            .collect::<Result<_, _>>()?;
        let s = RunSettings {
            width,
            height,
            spp: take(&mut m, "spp")?,
            max_depth: take(&mut m, "max_depth")?,
            rr_depth: take(&mut m, "rr_depth")?,
            seed: take(&mut m, "seed")?,
            fps: take(&mut m, "fps")?,
            cat: take(&mut m, "cat")?,
            degree,
            eye_samples: take(&mut m, "eye_samples")?,
            eye_min_samples: take(&mut m, "eye_min_samples")?,
            eye_target_std_err_uv: take(&mut m, "eye_target_std_err_uv")?,
            eye_common_random_numbers: take(&mut m, "eye_common_random_numbers")?,
            wcam_w: take(&mut m, "wcam_w")?,
            temporal_filters,
            exposure: take(&mut m, "exposure")?,
            scene: take(&mut m, "scene")?,
        };
        match m.keys().next() {
            Some(k) => Err(format!("unknown manifest setting {k:?}")),
            None => Ok(s),
        }
    }
}

/// Removes and parses one setting.
fn take<T: FromStr>(m: &mut BTreeMap<String, String>, key: &str) -> Result<T, String>
where
    T::Err: Display,
{
    let v = m
        .remove(key)
        .ok_or_else(|| format!("manifest setting {key} is missing"))?;
    v.parse()
        .map_err(|e| format!("manifest setting {key} {v:?}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> RunSettings {
        RunSettings {
            width: 64,
            height: 36,
            spp: 4,
            max_depth: -1,
            rr_depth: 5,
            seed: 7,
            fps: 24.0,
            cat: Cat::Bradford,
            degree: 0.75,
            eye_samples: 512,
            eye_min_samples: 512,
            eye_target_std_err_uv: 3.4e-4,
            eye_common_random_numbers: true,
            wcam_w: 2.0,
            temporal_filters: vec![TemporalFilter::Fairchild, TemporalFilter::Artistic],
            exposure: -0.5,
            scene: "builtin:three-rooms".into(),
        }
    }

    #[test]
    fn json_is_a_sorted_map_of_strings_and_reads_back() {
        let s = sample();
        let json = serde_json::to_string(&s).unwrap();
        assert!(
            json.starts_with(r#"{"cat":"bradford","degree":"0.75","#),
            "{json}"
        );
        assert!(json.contains(r#""resolution":"64x36""#), "{json}");
        assert!(json.contains(r#""temporal_filters":"fairchild,artistic""#));
        assert_eq!(serde_json::from_str::<RunSettings>(&json).unwrap(), s);
    }

    #[test]
    fn bad_settings_are_named() {
        let mut m = sample().entries();
        m.insert("degree".into(), "2".into());
        let e = RunSettings::try_from(m).unwrap_err();
        assert_eq!(e, "manifest setting degree \"2\" is not in [0, 1]");
        let mut m = sample().entries();
        m.remove("spp");
        assert_eq!(
            RunSettings::try_from(m).unwrap_err(),
            "manifest setting spp is missing"
        );
        let mut m = sample().entries();
        m.insert("colour".into(), "red".into());
        assert!(RunSettings::try_from(m).unwrap_err().contains("\"colour\""));
        let mut m = sample().entries();
        m.insert("temporal_filters".into(), "fairchild,bogus".into());
        let e = RunSettings::try_from(m).unwrap_err();
        assert!(e.starts_with("manifest setting temporal_filters"), "{e}");
    }
}
