//! Orientation of a keyframe as a quaternion, and the pose it gives.
use super::{CameraPose, Keyframe, Orientation};
use glam::{DMat3, DQuat, DVec3};

pub(super) fn pose(position: DVec3, q: DQuat, fov_deg: Option<f64>) -> CameraPose {
    // Renormalising keeps |forward| = |up| = 1 to the last bit after slerp's rounding.
    let q = q.normalize();
    CameraPose {
        position,
        forward: (q * DVec3::NEG_Z).normalize(),
        up: (q * DVec3::Y).normalize(),
        fov_deg,
    }
}

/// Rotation taking the camera's local frame (−z forward, +y up) to the keyframe's.
pub(super) fn orientation_quat(k: &Keyframe) -> DQuat {
    match k.orientation {
        Orientation::LookAt { look_at, up } => {
            let basis = look_at_basis(k.position, look_at, up).unwrap_or(DMat3::IDENTITY);
            DQuat::from_mat3(&basis).normalize()
        }
        // Pitch about the camera's own x axis first, then yaw about world +y: no roll.
        Orientation::YawPitch { yaw_deg, pitch_deg } => {
            DQuat::from_rotation_y(yaw_deg.to_radians())
                * DQuat::from_rotation_x(pitch_deg.to_radians())
        }
    }
}

/// Columns (right, up, −forward), or `None` when the direction is degenerate or `up` is
/// (nearly) parallel to it.
pub(crate) fn look_at_basis(position: DVec3, look_at: DVec3, up: DVec3) -> Option<DMat3> {
    let forward = (look_at - position).try_normalize()?;
    let right = forward.cross(up.try_normalize()?);
    // sin of the angle between up and forward; below 1e-6 the roll is numerically meaningless.
    if right.length() < 1e-6 {
        return None;
    }
    let right = right.normalize();
    Some(DMat3::from_cols(right, right.cross(forward), -forward))
}
