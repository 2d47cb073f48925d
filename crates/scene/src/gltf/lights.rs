//! `KHR_lights_punctual` lights as eyeadapt lights, with the unit conversion.
//!
//! glTF gives point and spot intensities in candela (lm/sr) and directional ones in lux
//! (lm/m²); eyeadapt's light `intensity` is radiant intensity (W/sr) and a sun's `irradiance`
//! is W/m². The conversion is by the
//! luminous efficacy 683 lm/W that defines the candela and that Blender's exporter uses
//! (`PBR_WATTS_TO_LUMENS`; with its default "Standard" lighting mode a Blender point light of
//! P watts is written as P/(4π)·683 cd), so `I [W/sr] = colour × intensity [cd] / 683`, and a
//! Blender light of P W comes back as P/(4π) W/sr — what Cycles emits. Likewise a directional
//! light of E lux has irradiance E/683 W/m² (Blender writes a sun's strength S W/m² as 683·S
//! lux, so it comes back as S).
//!
//! Spots: glTF's `outerConeAngle` is where the light reaches zero (eyeadapt's `cone_deg`),
//! `innerConeAngle` where it starts to fall (`falloff_deg`). glTF suggests a smooth falloff in
//! cos θ between them and eyeadapt's (Mitsuba's) falls linearly in θ; the two agree at both
//! ends and differ by a few percent inside the blend band.
use super::read::at;
use crate::{Diagnostic, Light, Rgb, Severity};
use glam::{DMat4, DVec3};
use gltf::khr_lights_punctual::Kind;
use std::path::Path;

/// Lumens per watt: the luminous efficacy at 540 THz that defines the candela.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// The light `l`, placed by its node's world transform `to_world`.
pub fn light(
    file: &Path,
    l: &gltf::khr_lights_punctual::Light,
    to_world: DMat4,
    warnings: &mut Vec<Diagnostic>,
) -> Option<Light> {
    let here = format!("/extensions/KHR_lights_punctual/lights/{}", l.index());
    let mut warn = |pointer: String, msg: String| {
        let mut d = at(file, &pointer, msg);
        d.severity = Severity::Warning;
        warnings.push(d);
    };
    if l.range().is_some() {
        warn(
            format!("{here}/range"),
            "a light's range cut-off is ignored: light falls off with distance squared only".into(),
        );
    }
    let intensity = Rgb::from_array(l.color()).max(Rgb::ZERO) * l.intensity().max(0.0);
    let position = to_world.transform_point3(DVec3::ZERO).as_vec3();
    let direction = to_world
        .transform_vector3(DVec3::NEG_Z)
        .normalize_or_zero()
        .as_vec3();
    match l.kind() {
        Kind::Point => Some(Light::Point {
            position,
            intensity: intensity / LUMENS_PER_WATT,
        }),
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let cone_deg = outer_cone_angle.to_degrees().clamp(0.01, 90.0);
            Some(Light::Spot {
                position,
                direction,
                intensity: intensity / LUMENS_PER_WATT,
                cone_deg,
                falloff_deg: inner_cone_angle.to_degrees().clamp(0.0, cone_deg),
            })
        }
        // Lux over 683 lm/W is irradiance in W/m² on a surface facing the light.
        Kind::Directional if direction.length() > 0.0 => Some(Light::Directional {
            direction,
            irradiance: intensity / LUMENS_PER_WATT,
        }),
        Kind::Directional => {
            warn(
                format!("{here}/type"),
                "a directional light whose node collapses its direction is left out".into(),
            );
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_directional_light_is_a_sun_in_watts_per_square_metre() {
        let json = br#"{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [
                {"type": "directional", "color": [1.0, 0.5, 0.25], "intensity": 1366.0}]}}}"#;
        let doc = gltf::Gltf::from_slice(json).unwrap();
        let l = doc.lights().unwrap().next().unwrap();
        let mut warnings = Vec::new();
        // A node turned 90° about +y: its −z (the light's direction) becomes −x.
        let to_world = DMat4::from_rotation_y(std::f64::consts::FRAC_PI_2);
        let got = light(Path::new("sun.gltf"), &l, to_world, &mut warnings).unwrap();
        assert!(warnings.is_empty());
        let Light::Directional {
            direction,
            irradiance,
        } = got
        else {
            panic!("{got:?}")
        };
        assert!(
            (direction - glam::Vec3::NEG_X).length() < 1e-6,
            "{direction}"
        );
        assert!(
            (irradiance - Rgb::new(2.0, 1.0, 0.5)).length() < 1e-5,
            "{irradiance}"
        );
    }
}
