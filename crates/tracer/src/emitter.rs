//! What emits light, as the light set stores it: emissive triangles (and the parallelograms two
//! of them may form; a textured one carries its UVs), point, spot and directional lights, and
//! the beams of [`crate::beam`]. Shared by [`crate::lights`] (sampling) and
//! [`crate::light_pick`] (choosing which light a point samples).
use crate::beam::{Lookup, Projector, TexturedSpot};
use eyeadapt_scene::Texture;
use glam::{Vec2, Vec3A};

#[inline]
pub fn luminance(c: Vec3A) -> f32 {
    0.212_639 * c.x + 0.715_168_7 * c.y + 0.072_192_32 * c.z
}

#[derive(Clone, Copy, Debug)]
pub struct AreaTri {
    pub v0: Vec3A,
    pub e1: Vec3A,
    pub e2: Vec3A,
    pub n: Vec3A,
    pub area: f32,
    /// Emitted radiance; for a textured emitter, its mean (what the light choice weighs).
    pub emission: Vec3A,
    /// Index of the texture whose value times `scale` is the radiance (`u32::MAX`: none).
    pub texture: u32,
    pub scale: Vec3A,
    /// Texture coordinates of the three vertices (for a textured emitter).
    pub uv: [Vec2; 3],
}

/// Two emissive triangles that together form a parallelogram (a quad light split along a
/// diagonal): sampled as one, `o + u·e1 + v·e2` for (u, v) in the unit square, so that a
/// stratified 2-D sample stays stratified over the whole quad instead of being dealt out to
/// its halves by the light-picking number.
#[derive(Clone, Copy, Debug)]
pub struct Parallelogram {
    pub o: Vec3A,
    pub e1: Vec3A,
    pub e2: Vec3A,
}

#[derive(Clone, Copy, Debug)]
pub enum DeltaLight {
    Point {
        position: Vec3A,
        intensity: Vec3A,
    },
    Spot {
        position: Vec3A,
        direction: Vec3A,
        intensity: Vec3A,
        cos_cone: f32,
        cos_falloff: f32,
        cone: f32,
        inv_transition: f32,
    },
    /// Parallel light travelling along `direction` (unit), from infinitely far away.
    Directional {
        direction: Vec3A,
        irradiance: Vec3A,
    },
    TexturedSpot(TexturedSpot),
    Projector(Projector),
}

/// Light arriving at a point from a delta light.
#[derive(Clone, Copy, Debug)]
pub struct Arrival {
    /// Unit direction towards the light.
    pub wi: Vec3A,
    /// Distance to it (∞ for a directional light).
    pub dist: f32,
    /// Irradiance on a surface facing it: intensity / d², or a directional light's own.
    pub li: Vec3A,
}

impl DeltaLight {
    /// The light's colour: intensity, or a directional light's irradiance.
    pub fn colour(&self) -> Vec3A {
        match self {
            DeltaLight::Point { intensity, .. } | DeltaLight::Spot { intensity, .. } => *intensity,
            DeltaLight::Directional { irradiance, .. } => *irradiance,
            DeltaLight::TexturedSpot(s) => s.colour(),
            DeltaLight::Projector(p) => p.colour(),
        }
    }

    /// What arrives at `x`, the beams' images read through `lookup`; `None` at the light's
    /// own position.
    #[inline]
    pub fn arrival(&self, x: Vec3A, lookup: Lookup) -> Option<Arrival> {
        let position = match *self {
            DeltaLight::Point { position, .. } | DeltaLight::Spot { position, .. } => position,
            DeltaLight::TexturedSpot(s) => s.position,
            DeltaLight::Projector(p) => {
                let d = p.position - x;
                let dist = d.length();
                if dist <= 0.0 {
                    return None;
                }
                return Some(Arrival {
                    wi: d / dist,
                    dist,
                    li: p.irradiance_at(x, lookup),
                });
            }
            DeltaLight::Directional {
                direction,
                irradiance,
            } => {
                return Some(Arrival {
                    wi: -direction,
                    dist: f32::INFINITY,
                    li: irradiance,
                });
            }
        };
        let d = position - x;
        let d2 = d.length_squared();
        let dist = d2.sqrt();
        if dist <= 0.0 {
            return None;
        }
        let wi = d / dist;
        // A point light's intensity is the same in every direction: no call for it (the
        // spatial light choice asks for every vertex).
        let intensity = match *self {
            DeltaLight::Point { intensity, .. } => intensity,
            _ => self.intensity(-wi, lookup),
        };
        Some(Arrival {
            wi,
            dist,
            li: intensity / d2,
        })
    }

    /// Radiant intensity towards direction `w` (unit, leaving the light); a directional
    /// light's irradiance.
    fn intensity(&self, w: Vec3A, lookup: Lookup) -> Vec3A {
        match *self {
            DeltaLight::Point { intensity, .. } => intensity,
            DeltaLight::Directional { irradiance, .. } => irradiance,
            DeltaLight::TexturedSpot(s) => s.intensity(w, lookup),
            // Handled in `arrival` (its value depends on the point, not only the direction).
            DeltaLight::Projector(_) => Vec3A::ZERO,
            DeltaLight::Spot {
                direction,
                intensity,
                cos_cone,
                cos_falloff,
                cone,
                inv_transition,
                ..
            } => {
                let c = direction.dot(w);
                if c <= cos_cone {
                    Vec3A::ZERO
                } else if c >= cos_falloff {
                    intensity
                } else {
                    // Linear in angle between the beam width and the cutoff (Mitsuba's `spot`).
                    intensity * ((cone - libm::acosf(c.clamp(-1.0, 1.0))) * inv_transition)
                }
            }
        }
    }
}

impl AreaTri {
    /// The emitting triangle `v` (front side = (v1 − v0) × (v2 − v0)); `None` without area.
    pub fn new(v: [Vec3A; 3], emission: Vec3A) -> Option<AreaTri> {
        let e1 = v[1] - v[0];
        let e2 = v[2] - v[0];
        let c = e1.cross(e2);
        let area = 0.5 * c.length();
        let (n, area) = if area.is_finite() {
            (c / (2.0 * area), area)
        } else {
            // |c|² overflows for edges of 1e10 and more: scaled edges give both.
            crate::triangle::normal_and_area(e1, e2)?
        };
        (area > 0.0 && area.is_finite()).then_some(AreaTri {
            v0: v[0],
            e1,
            e2,
            n,
            area,
            emission,
            texture: u32::MAX,
            scale: emission,
            uv: [Vec2::ZERO, Vec2::X, Vec2::Y],
        })
    }

    /// This triangle with its radiance `scale` × texture `texture` (whose mean is `mean`) at
    /// vertex UVs `uv`.
    pub fn textured(self, texture: u32, mean: Vec3A, uv: [Vec2; 3]) -> AreaTri {
        AreaTri {
            emission: self.scale * mean,
            texture,
            uv,
            ..self
        }
    }

    /// The radiance at barycentrics (`b1`, `b2`) (weights of vertices 1 and 2).
    #[inline]
    pub fn radiance(&self, b1: f32, b2: f32, textures: &[Texture]) -> Vec3A {
        if self.texture == u32::MAX {
            return self.emission;
        }
        let uv = self.uv[0] * (1.0 - b1 - b2) + self.uv[1] * b1 + self.uv[2] * b2;
        self.scale * crate::texture::eval_uv(&textures[self.texture as usize], uv)
    }
}
