//! Materials as the tracer evaluates them: at each hit, the scene material's parameters
//! (constants or texture lookups at the [`SurfaceInteraction`]) become a [`Bsdf`]. Only what
//! does not depend on the hit (the coating's internal reflectance) is computed once.
use crate::bsdf::Bsdf;
use crate::emitter::luminance;
use crate::interaction::SurfaceInteraction;
use crate::microfacet::internal_diffuse_reflectance;
use crate::texture;
use eyeadapt_scene::{Bsdf as SceneBsdf, Material, Param, Rgb, Scene, Texture};
use glam::Vec3A;

struct Entry {
    bsdf: SceneBsdf,
    emission: Vec3A,
    /// Internal diffuse reflectance of a plastic's coating (0 for other BSDFs).
    fdr: f32,
}

/// The scene's materials, then the error material, and the textures they read.
pub struct Materials {
    entries: Vec<Entry>,
    textures: Vec<Texture>,
}

impl Materials {
    pub fn new(scene: &Scene) -> Materials {
        let entry = |m: &Material| Entry {
            bsdf: m.bsdf.clone(),
            emission: m.emission.into(),
            fdr: match m.bsdf {
                SceneBsdf::Plastic { ior, .. } => internal_diffuse_reflectance(ior),
                _ => 0.0,
            },
        };
        let mut entries: Vec<Entry> = scene.materials.iter().map(entry).collect();
        entries.push(entry(&Material::error()));
        Materials {
            entries,
            textures: scene.textures.clone(),
        }
    }

    /// Index of the error material (for instances without one).
    pub fn error_index(&self) -> u32 {
        self.entries.len() as u32 - 1
    }

    #[inline]
    pub fn emission(&self, material: u32) -> Vec3A {
        self.entries[material as usize].emission
    }

    #[inline]
    fn rgb(&self, p: Param<Rgb>, si: &SurfaceInteraction) -> Vec3A {
        match p {
            Param::Const(c) => c.into(),
            Param::Texture(t) => texture::eval(&self.textures[t.0 as usize], si),
        }
    }

    /// A number parameter; a texture gives its luminance (Mitsuba's `eval_1`).
    #[inline]
    fn number(&self, p: Param<f32>, si: &SurfaceInteraction) -> f32 {
        match p {
            Param::Const(x) => x,
            Param::Texture(t) => luminance(texture::eval(&self.textures[t.0 as usize], si)),
        }
    }

    /// The BSDF of `si`'s material at `si`.
    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction) -> Bsdf {
        let e = &self.entries[si.material as usize];
        match e.bsdf {
            SceneBsdf::Diffuse { reflectance } => Bsdf::diffuse(self.rgb(reflectance, si)),
            SceneBsdf::Conductor {
                alpha,
                eta,
                k,
                specular_reflectance,
            } => Bsdf::conductor(
                self.number(alpha, si),
                eta.into(),
                k.into(),
                self.rgb(specular_reflectance, si),
            ),
            SceneBsdf::Plastic {
                reflectance,
                alpha,
                ior,
            } => Bsdf::plastic(
                self.rgb(reflectance, si),
                self.number(alpha, si).max(0.01),
                ior,
                e.fdr,
            ),
        }
    }

    /// The diffuse (base) reflectance at `si`: what the estimators take as the surface colour
    /// (zero for conductors, whose colour is specular).
    pub fn diffuse_reflectance(&self, si: &SurfaceInteraction) -> Vec3A {
        match self.entries[si.material as usize].bsdf {
            SceneBsdf::Diffuse { reflectance } | SceneBsdf::Plastic { reflectance, .. } => {
                self.rgb(reflectance, si)
            }
            SceneBsdf::Conductor { .. } => Vec3A::ZERO,
        }
    }
}
