//! The keyframe as TOML spells it, turned into a [`Keyframe`].
use super::{Keyframe, Orientation};
use glam::DVec3;
use serde::Deserialize;

/// The keyframe as written in TOML. `look_at` and yaw/pitch are alternatives; serde's
/// `flatten` cannot be combined with `deny_unknown_fields` (deps.md §7), so the choice is
/// checked here and turned into [`Orientation`] by `TryFrom`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct KeyframeToml {
    time: f64,
    position: DVec3,
    look_at: Option<DVec3>,
    up: Option<DVec3>,
    yaw_deg: Option<f64>,
    pitch_deg: Option<f64>,
    fov_deg: Option<f64>,
}

impl TryFrom<KeyframeToml> for Keyframe {
    type Error = String;

    fn try_from(k: KeyframeToml) -> Result<Keyframe, String> {
        let has_angles = k.yaw_deg.is_some() || k.pitch_deg.is_some();
        let orientation = match (k.look_at, k.yaw_deg) {
            (Some(_), _) if has_angles => {
                return Err("give either `look_at` or `yaw_deg`/`pitch_deg`, not both".into());
            }
            (Some(look_at), _) => Orientation::LookAt {
                look_at,
                up: k.up.unwrap_or(DVec3::Y),
            },
            (None, Some(yaw_deg)) => {
                if k.up.is_some() {
                    return Err("`up` only applies with `look_at` (yaw/pitch never roll)".into());
                }
                Orientation::YawPitch {
                    yaw_deg,
                    pitch_deg: k.pitch_deg.unwrap_or(0.0),
                }
            }
            (None, None) if k.pitch_deg.is_some() => {
                return Err("`pitch_deg` needs `yaw_deg`".into());
            }
            (None, None) => {
                return Err(
                    "a keyframe needs `look_at` or `yaw_deg` (and optionally `pitch_deg`)".into(),
                );
            }
        };
        Ok(Keyframe {
            time: k.time,
            position: k.position,
            orientation,
            fov_deg: k.fov_deg,
        })
    }
}
