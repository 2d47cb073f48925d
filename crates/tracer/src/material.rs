//! Materials as the tracer evaluates them: at each hit, the scene material's parameters
//! (constants or texture lookups at the [`SurfaceInteraction`]) become a [`Bsdf`]. Only what
//! does not depend on the hit (the coating's internal reflectance) is computed once.
//!
//! The scene's wrappers are flattened once per material: a one-sided BSDF becomes a flag (its
//! back side is black), and masks become the list of opacities the hit's opacity is the
//! product of (a mask in a mask passes light where either does).
use crate::bsdf::Bsdf;
use crate::dielectric::RoughDielectric;
use crate::emitter::luminance;
use crate::interaction::SurfaceInteraction;
use crate::microfacet::{Microfacet, internal_diffuse_reflectance};
use crate::texture;
use eyeadapt_scene::{Bsdf as SceneBsdf, Material, Param, Rgb, Scene, Texture, TextureId};
use glam::Vec3A;

struct Entry {
    /// The innermost BSDF (no `OneSided` or `Mask` left).
    bsdf: SceneBsdf,
    emission: Vec3A,
    /// Internal diffuse reflectance of a plastic's coating (0 for other BSDFs).
    fdr: f32,
    /// Black seen from the back of the geometric normal.
    one_sided: bool,
    /// Masks' opacities (empty: opaque).
    opacity: Vec<Param<f32>>,
    /// A tangent-space normal map replacing the shading normal (the innermost one counts).
    normal_map: Option<TextureId>,
}

impl Entry {
    fn new(m: &Material) -> Entry {
        let mut bsdf = &m.bsdf;
        let mut one_sided = false;
        let mut opacity = Vec::new();
        let mut normal_map = None;
        loop {
            match bsdf {
                SceneBsdf::OneSided(b) => {
                    one_sided = true;
                    bsdf = b;
                }
                SceneBsdf::Mask {
                    opacity: o,
                    bsdf: b,
                } => {
                    opacity.push(*o);
                    bsdf = b;
                }
                SceneBsdf::NormalMap { normals, bsdf: b } => {
                    normal_map = Some(*normals);
                    bsdf = b;
                }
                _ => break,
            }
        }
        Entry {
            bsdf: bsdf.clone(),
            emission: m.emission.into(),
            fdr: match bsdf {
                SceneBsdf::Plastic { ior, .. } => internal_diffuse_reflectance(*ior),
                _ => 0.0,
            },
            one_sided,
            opacity,
            normal_map,
        }
    }
}

/// The scene's materials, then the error material, and the textures they read.
pub struct Materials {
    entries: Vec<Entry>,
    textures: Vec<Texture>,
}

impl Materials {
    pub fn new(scene: &Scene) -> Materials {
        let mut entries: Vec<Entry> = scene.materials.iter().map(Entry::new).collect();
        entries.push(Entry::new(&Material::error()));
        Materials {
            entries,
            textures: scene.textures.clone(),
        }
    }

    /// True when some material is a thin pane (`panes.rs`).
    pub fn has_thin_panes(&self) -> bool {
        self.entries
            .iter()
            .any(|e| matches!(e.bsdf, SceneBsdf::ThinDielectric { .. }))
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

    /// The shading normal at `si`: the mesh's, or its material's normal map's, 2·rgb − 1 in
    /// the frame of the mesh's shading normal and ∂p/∂u (as Mitsuba's `normalmap`).
    #[inline]
    pub fn shading_normal(&self, si: &SurfaceInteraction) -> Vec3A {
        let Some(t) = self.entries[si.material as usize].normal_map else {
            return si.ns;
        };
        let local = texture::eval(&self.textures[t.0 as usize], si) * 2.0 - Vec3A::ONE;
        let n = si.ns;
        let s = (si.dpdu - n * n.dot(si.dpdu)).normalize_or_zero();
        if s == Vec3A::ZERO {
            return n;
        }
        let m = (s * local.x + n.cross(s) * local.y + n * local.z).normalize_or_zero();
        if m == Vec3A::ZERO { n } else { m }
    }

    /// The probability that a ray passes straight through `si` (its masks' opacity).
    #[inline]
    pub fn opacity(&self, si: &SurfaceInteraction) -> f32 {
        let e = &self.entries[si.material as usize];
        e.opacity
            .iter()
            .map(|&p| self.number(p, si).clamp(0.0, 1.0))
            .product()
    }

    /// The BSDF of `si`'s material at `si`, seen from the front of the geometric normal when
    /// `front` (a dielectric's exterior; the back of a one-sided BSDF is black).
    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction, front: bool) -> Bsdf {
        let e = &self.entries[si.material as usize];
        if e.one_sided && !front {
            return Bsdf::diffuse(Vec3A::ZERO);
        }
        match e.bsdf {
            SceneBsdf::Diffuse { reflectance } => Bsdf::diffuse(self.rgb(reflectance, si)),
            SceneBsdf::Conductor {
                alpha,
                distribution,
                eta,
                k,
                specular_reflectance,
            } => Bsdf::conductor(
                self.number(alpha, si),
                distribution,
                eta.into(),
                k.into(),
                self.rgb(specular_reflectance, si),
            ),
            SceneBsdf::Plastic {
                reflectance,
                alpha,
                distribution,
                ior,
            } => Bsdf::plastic(
                self.rgb(reflectance, si),
                self.number(alpha, si).max(0.01),
                distribution,
                ior,
                e.fdr,
            ),
            SceneBsdf::Dielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            } => Bsdf::Dielectric {
                eta: if front { eta } else { 1.0 / eta },
                r: specular_reflectance.into(),
                t: specular_transmittance.into(),
            },
            SceneBsdf::ThinDielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            } => Bsdf::ThinDielectric {
                eta,
                r: specular_reflectance.into(),
                t: specular_transmittance.into(),
            },
            SceneBsdf::RoughDielectric {
                alpha,
                distribution,
                eta,
                specular_reflectance,
                specular_transmittance,
            } => {
                // Mitsuba clamps a texture's roughness away from 0 the same way.
                let alpha = self.number(alpha, si).max(1e-4);
                Bsdf::RoughDielectric(RoughDielectric {
                    md: Microfacet::new(alpha, distribution),
                    eta: if front { eta } else { 1.0 / eta },
                    r: specular_reflectance.into(),
                    t: specular_transmittance.into(),
                })
            }
            // Flattened into the entry.
            SceneBsdf::OneSided(_) | SceneBsdf::Mask { .. } | SceneBsdf::NormalMap { .. } => {
                unreachable!()
            }
        }
    }
}
