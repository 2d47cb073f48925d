//! The delta lights whose intensity varies across their beam: a spot carrying a texture and a
//! slide projector (Mitsuba's `spot` with `texture`, and `projector`). Both are points; the
//! value of a direction is looked up in the light's own frame, where the beam runs along +z.
use crate::texture;
use eyeadapt_scene::{Param, Rgb, Texture};
use glam::{Mat3, Mat3A, Vec2, Vec3A};
use std::f32::consts::PI;

/// What a beam's image reads: the texture itself, or its mean (the light choice's estimate
/// of what a point receives, which must be positive wherever the light can contribute).
#[derive(Clone, Copy)]
pub enum Lookup<'a> {
    Texture(&'a [Texture]),
    Mean,
}

/// A beam's image: a constant, or a texture (an index into the light set's textures) with
/// its mean.
#[derive(Clone, Copy, Debug)]
pub struct Image {
    constant: Vec3A,
    texture: u32,
    mean: Vec3A,
}

impl Image {
    /// `p` with the light set's `textures` (whose means it keeps).
    pub fn new(p: Param<Rgb>, textures: &[Texture]) -> Image {
        match p {
            Param::Const(c) => Image {
                constant: c.into(),
                texture: u32::MAX,
                mean: c.into(),
            },
            Param::Texture(t) => Image {
                constant: Vec3A::ONE,
                texture: t.0,
                mean: textures
                    .get(t.0 as usize)
                    .map_or(Vec3A::ZERO, texture::mean),
            },
        }
    }

    #[inline]
    fn at(&self, uv: Vec2, lookup: Lookup) -> Vec3A {
        match lookup {
            _ if self.texture == u32::MAX => self.constant,
            Lookup::Mean => self.mean,
            Lookup::Texture(t) => texture::eval_uv(&t[self.texture as usize], uv),
        }
    }

    pub fn mean(&self) -> Vec3A {
        self.mean
    }
}

/// The world-to-light map of a frame whose columns are the light's axes in the world.
pub fn to_local(frame: Mat3) -> Mat3A {
    Mat3A::from(frame.inverse())
}

/// A spot with an image across its cone.
#[derive(Clone, Copy, Debug)]
pub struct TexturedSpot {
    pub position: Vec3A,
    pub to_local: Mat3A,
    pub intensity: Vec3A,
    pub cos_cone: f32,
    pub cos_falloff: f32,
    pub cone: f32,
    pub inv_transition: f32,
    /// tan of the cutoff angle: the image spans the cone's base.
    pub tan_cone: f32,
    pub image: Image,
}

impl TexturedSpot {
    /// Radiant intensity towards world direction `w` (unit, leaving the light).
    #[inline]
    pub fn intensity(&self, w: Vec3A, lookup: Lookup) -> Vec3A {
        let l = self.to_local * w;
        let len = l.length();
        if len <= 0.0 {
            return Vec3A::ZERO;
        }
        let c = l.z / len;
        let profile = if c <= self.cos_cone {
            return Vec3A::ZERO;
        } else if c >= self.cos_falloff {
            1.0
        } else {
            // Linear in angle between the beam width and the cutoff (Mitsuba's `spot`).
            (self.cone - libm::acosf(c.clamp(-1.0, 1.0))) * self.inv_transition
        };
        let k = 0.5 / (l.z * self.tan_cone);
        let uv = Vec2::new(0.5 + l.x * k, 0.5 + l.y * k);
        self.intensity * self.image.at(uv, lookup) * profile
    }

    /// Total emitted power in luminance-weighted units, for the choice of light: the
    /// untextured spot's times the image's mean.
    pub fn colour(&self) -> Vec3A {
        self.intensity * self.image.mean()
    }
}

/// A slide projector: its image (or a constant) thrown through a frustum.
#[derive(Clone, Copy, Debug)]
pub struct Projector {
    pub position: Vec3A,
    pub to_local: Mat3A,
    /// The frame's z axis in the world (not normalised, as Mitsuba takes it).
    pub axis: Vec3A,
    pub image: Image,
    /// π · scale.
    pub pi_scale: f32,
    pub tan_half_fov_x: f32,
    pub aspect: f32,
}

impl Projector {
    /// What arrives at `x` from the projector, per unit area facing it: π·scale·E(uv) /
    /// (z² · cos θ) with z the depth of `x` in the light's frame (Mitsuba's
    /// `Projector::sample_direction`); zero outside the frustum.
    #[inline]
    pub fn irradiance_at(&self, x: Vec3A, lookup: Lookup) -> Vec3A {
        let d = x - self.position;
        let l = self.to_local * d;
        if l.z <= 0.0 {
            return Vec3A::ZERO;
        }
        let k = 1.0 / (l.z * self.tan_half_fov_x);
        let uv = Vec2::new(0.5 * (1.0 - l.x * k), 0.5 * (1.0 - self.aspect * l.y * k));
        if !(uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()) {
            return Vec3A::ZERO;
        }
        let cos = self.axis.dot(d) / d.length();
        if cos <= 0.0 {
            return Vec3A::ZERO;
        }
        self.image.at(uv, lookup) * (self.pi_scale / (l.z * l.z * cos))
    }

    /// Total emitted power in colour units: π·scale·mean(E) times the image's area one unit
    /// in front of the light, (2t) × (2t / aspect).
    pub fn power(&self) -> Vec3A {
        let t = self.tan_half_fov_x;
        self.image.mean() * (self.pi_scale * 4.0 * t * t / self.aspect)
    }

    /// The light's colour (for the `dominant` estimator).
    pub fn colour(&self) -> Vec3A {
        self.image.mean() * (self.pi_scale / PI)
    }
}
