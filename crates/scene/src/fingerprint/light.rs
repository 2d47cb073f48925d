//! How lights feed a fingerprint, variant by variant.
use super::{Feed, tag};
use crate::Light;
use sha2::Sha256;

impl Feed for Light {
    fn feed(&self, h: &mut Sha256) {
        match self {
            Light::Point {
                position,
                intensity,
            } => {
                tag(h, 0);
                position.feed(h);
                intensity.feed(h);
            }
            Light::Spot {
                position,
                direction,
                intensity,
                cone_deg,
                falloff_deg,
            } => {
                tag(h, 1);
                position.feed(h);
                direction.feed(h);
                intensity.feed(h);
                cone_deg.feed(h);
                falloff_deg.feed(h);
            }
            Light::Directional {
                direction,
                irradiance,
            } => {
                tag(h, 2);
                direction.feed(h);
                irradiance.feed(h);
            }
            Light::TexturedSpot {
                position,
                frame,
                intensity,
                cone_deg,
                falloff_deg,
                texture,
            } => {
                tag(h, 3);
                position.feed(h);
                frame.feed(h);
                intensity.feed(h);
                cone_deg.feed(h);
                falloff_deg.feed(h);
                texture.0.feed(h);
            }
            Light::Projector {
                position,
                frame,
                irradiance,
                scale,
                tan_half_fov_x,
                aspect,
            } => {
                tag(h, 4);
                position.feed(h);
                frame.feed(h);
                irradiance.feed(h);
                scale.feed(h);
                tan_half_fov_x.feed(h);
                aspect.feed(h);
            }
        }
    }
}
