//! The estimators by name: one closed enum, so every match over them is checked by the
//! compiler and the names in job files, CSV rows, manifests and directories are spelled once.
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// One adaptation estimator (estimators.md §1–§5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Estimator {
    /// The paper's eye-centred hemispherical sensor.
    Eye,
    /// The eye sensor restricted to the camera's field of view (ablation; not in `all`).
    EyeFov,
    Wcam,
    Ncns,
    Dominant,
    GreyWorld,
    WhitePatch,
    ShadesOfGrey,
    GreyEdge,
}

impl Estimator {
    /// Every estimator, in the order rows are written.
    pub const ALL: [Estimator; 9] = [
        Estimator::Eye,
        Estimator::EyeFov,
        Estimator::Wcam,
        Estimator::Ncns,
        Estimator::Dominant,
        Estimator::GreyWorld,
        Estimator::WhitePatch,
        Estimator::ShadesOfGrey,
        Estimator::GreyEdge,
    ];

    /// The name used in job files, CSV rows, manifests and output directories.
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Eye => "eye",
            Estimator::EyeFov => "eye_fov",
            Estimator::Wcam => "wcam",
            Estimator::Ncns => "ncns",
            Estimator::Dominant => "dominant",
            Estimator::GreyWorld => "grey_world",
            Estimator::WhitePatch => "white_patch",
            Estimator::ShadesOfGrey => "shades_of_grey",
            Estimator::GreyEdge => "grey_edge",
        }
    }
}

impl fmt::Display for Estimator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Estimator {
    type Err = String;

    fn from_str(s: &str) -> Result<Estimator, String> {
        Estimator::ALL
            .into_iter()
            .find(|e| e.name() == s)
            .ok_or_else(|| format!("unknown estimator \"{s}\" (known: all, {})", known()))
    }
}

fn known() -> String {
    Estimator::ALL.map(Estimator::name).join(", ")
}

/// Parses `all` or comma-separated lists into estimators, in canonical order.
pub fn parse_estimator_list(items: &[String]) -> Result<Vec<Estimator>, String> {
    let mut wanted = Vec::new();
    for item in items
        .iter()
        .flat_map(|s| s.split(','))
        .map(str::trim)
        .filter(|s| !s.is_empty())
    {
        if item == "all" {
            wanted.extend(
                Estimator::ALL
                    .into_iter()
                    .filter(|e| *e != Estimator::EyeFov),
            );
        } else {
            wanted.push(item.parse::<Estimator>()?);
        }
    }
    if wanted.is_empty() {
        return Err("no estimator selected".into());
    }
    Ok(Estimator::ALL
        .into_iter()
        .filter(|e| wanted.contains(e))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_text_and_serde() {
        for e in Estimator::ALL {
            assert_eq!(e.name().parse::<Estimator>(), Ok(e));
            let json = serde_json::to_string(&e).unwrap();
            assert_eq!(json, format!("\"{}\"", e.name()));
            assert_eq!(serde_json::from_str::<Estimator>(&json).unwrap(), e);
        }
    }

    #[test]
    fn lists_parse_in_canonical_order() {
        let l = parse_estimator_list(&["wcam,eye".into()]).unwrap();
        assert_eq!(l, [Estimator::Eye, Estimator::Wcam]);
        let all = parse_estimator_list(&["all".into()]).unwrap();
        assert_eq!(all.len(), Estimator::ALL.len() - 1);
        assert!(!all.contains(&Estimator::EyeFov));
        let e = parse_estimator_list(&["eye,bogus".into()]).unwrap_err();
        assert!(e.contains("unknown estimator \"bogus\""), "{e}");
        assert!(parse_estimator_list(&[" , ".into()]).is_err());
    }
}
