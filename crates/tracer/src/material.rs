//! Materials as the tracer evaluates them: at each hit, the scene material's parameters
//! (constants or texture lookups at the [`SurfaceInteraction`]) become a [`Bsdf`]. Only what
//! does not depend on the hit (the coating's internal reflectance) is computed once.
//!
//! The scene's wrappers are flattened once per material: a one-sided BSDF becomes a flag (its
//! back side is black), and masks become the list of opacities the hit's opacity is the
//! product of (a mask in a mask passes light where either does); normal and bump maps become
//! the hit's shading-normal rule. A blend becomes a node whose two children (each flattened,
//! with the wrappers around the blend pushed down into them) are chosen per hit with
//! probabilities 1 − weight and weight ([`Materials::select`]): the vertex then scatters with
//! that child alone, an unbiased estimate of the blend (Mitsuba evaluates both children for
//! light samples instead; the images converge to the same, with different noise).
use crate::bsdf::Bsdf;
use crate::bump::{Terminator, bumped_normal, height_gradient};
use crate::dielectric::RoughDielectric;
use crate::interaction::SurfaceInteraction;
use crate::microfacet::Microfacet;
use crate::plastic_table::PlasticTable;
use crate::pplastic::PPlastic;
use crate::principled::Principled;
use crate::principled_thin::PrincipledThin;
use crate::texture;
use eyeadapt_scene::{
    Bsdf as SceneBsdf, Distribution, Material, Param, Rgb, Scene, Texture, TextureId,
};
use glam::Vec3A;

#[derive(Clone)]
struct Entry {
    /// The innermost BSDF (no wrapper left); unused for a blend.
    bsdf: SceneBsdf,
    emission: Vec3A,
    /// A plastic's coating terms (at its roughness, or its mean roughness if textured) and
    /// the mean of its base reflectance; `None` for other BSDFs.
    plastic: Option<(&'static PlasticTable, f32)>,
    /// A `pplastic`'s probability of sampling its specular lobe.
    spec_prob: f32,
    /// Black seen from the back of the geometric normal.
    one_sided: bool,
    /// Masks' opacities (empty: opaque).
    opacity: Vec<Param<f32>>,
    /// A tangent-space normal map replacing the shading normal (the innermost one counts).
    normal_map: Option<TextureId>,
    /// A height field and its scale tilting the shading normal (applied after a normal map).
    bump: Option<(TextureId, f32)>,
    /// A blend: its weight and its two children in [`Materials::nodes`].
    blend: Option<(Param<f32>, [u32; 2])>,
    /// A texture that multiplies `emission` (a textured area emitter's radiance).
    emission_texture: Option<TextureId>,
    /// The BSDF seen from the back and from the front, built once, when it is the same at
    /// every hit: no texture, blend, mask, normal or bump map, no anisotropy
    /// ([`Materials::fixed`]).
    fixed: Option<[Bsdf; 2]>,
}

/// True when `e`'s BSDF is the same at every hit: a leaf without wrappers whose parameters
/// are constants, isotropic. Only the common BSDFs are recognised; any other is built per
/// hit, which is always right.
fn is_constant(e: &Entry) -> bool {
    let plain = e.blend.is_none() && e.normal_map.is_none() && e.bump.is_none();
    let c = |p: &Param<f32>| p.constant().is_some();
    let rgb = |p: &Param<Rgb>| p.constant().is_some();
    plain
        && e.opacity.is_empty()
        && match &e.bsdf {
            SceneBsdf::Diffuse { reflectance } => rgb(reflectance),
            SceneBsdf::Conductor {
                alpha,
                alpha_v: None,
                specular_reflectance,
                ..
            } => c(alpha) && rgb(specular_reflectance),
            SceneBsdf::Plastic {
                reflectance, alpha, ..
            } => rgb(reflectance) && c(alpha),
            SceneBsdf::Dielectric { .. } | SceneBsdf::ThinDielectric { .. } => true,
            SceneBsdf::RoughDielectric {
                alpha,
                alpha_v: None,
                ..
            } => c(alpha),
            _ => false,
        }
}

/// The flattened material a hit scatters with (a blend's chosen child).
#[derive(Clone, Copy)]
pub struct Leaf<'m>(&'m Entry);

impl Leaf<'_> {
    /// Whether a shadow ray may pass this material somewhere: it is a thin pane, or it has
    /// masks (a null surface is a mask of opacity 0) and `cutouts` pass shadow rays. (Not a
    /// blend: only its leaves scatter.)
    #[inline]
    pub fn may_pass(self, cutouts: bool) -> bool {
        self.0.blend.is_none()
            && (matches!(self.0.bsdf, SceneBsdf::ThinDielectric { .. })
                || (cutouts && !self.0.opacity.is_empty()))
    }
}

impl Entry {
    fn new(m: &Material, textures: &[Texture], nodes: &mut Vec<Entry>) -> Entry {
        let root = Entry {
            bsdf: SceneBsdf::Null,
            emission: m.emission.into(),
            plastic: None,
            spec_prob: 0.0,
            one_sided: false,
            opacity: Vec::new(),
            normal_map: None,
            bump: None,
            blend: None,
            emission_texture: None,
            fixed: None,
        };
        root.flatten(&m.bsdf, textures, nodes)
    }

    /// `self` (the wrappers seen so far) with `bsdf`'s wrappers added, down to its leaf or
    /// blend.
    fn flatten(mut self, bsdf: &SceneBsdf, textures: &[Texture], nodes: &mut Vec<Entry>) -> Entry {
        let mut bsdf = bsdf;
        loop {
            match bsdf {
                SceneBsdf::OneSided(b) => {
                    self.one_sided = true;
                    bsdf = b;
                }
                SceneBsdf::Mask { opacity, bsdf: b } => {
                    self.opacity.push(*opacity);
                    bsdf = b;
                }
                SceneBsdf::NormalMap { normals, bsdf: b } => {
                    self.normal_map = Some(*normals);
                    bsdf = b;
                }
                SceneBsdf::BumpMap {
                    height,
                    scale,
                    bsdf: b,
                } => {
                    self.bump = Some((*height, *scale));
                    bsdf = b;
                }
                SceneBsdf::Blend { weight, bsdfs } => {
                    let mut children = [0u32; 2];
                    for (c, b) in children.iter_mut().zip(bsdfs.iter()) {
                        let e = self.clone().flatten(b, textures, nodes);
                        nodes.push(e);
                        *c = nodes.len() as u32 - 1;
                    }
                    self.blend = Some((*weight, children));
                    return self;
                }
                SceneBsdf::Null => {
                    // No surface: light always passes (the BSDF is never used).
                    self.opacity.push(Param::Const(0.0));
                    self.bsdf = SceneBsdf::Diffuse {
                        reflectance: Param::Const(Rgb::ZERO),
                    };
                    return self;
                }
                _ => break,
            }
        }
        self.plastic = match bsdf {
            SceneBsdf::Plastic {
                reflectance,
                alpha,
                distribution,
                ior,
            } => {
                // A constant 0 is a smooth coating: the smooth interface's terms, though its
                // specular lobe is evaluated at alpha 0.01.
                let a = match *alpha {
                    Param::Const(a) if a <= 0.0 => 0.0,
                    Param::Const(a) => a.max(0.01),
                    Param::Texture(t) => texture::param_mean(Param::Texture(t), textures).max(0.01),
                };
                Some((
                    PlasticTable::get(a, *distribution, *ior),
                    texture::param_mean(*reflectance, textures),
                ))
            }
            _ => None,
        };
        if let SceneBsdf::PPlastic {
            diffuse_reflectance,
            specular_reflectance,
            ..
        } = bsdf
        {
            let d = texture::param_mean(*diffuse_reflectance, textures);
            let s = texture::param_mean(*specular_reflectance, textures);
            self.spec_prob = PPlastic::spec_prob(d, s);
        }
        self.bsdf = bsdf.clone();
        self
    }
}

/// The scene's materials, then the error material, and the textures they read.
pub struct Materials {
    entries: Vec<Entry>,
    /// Blends' children.
    nodes: Vec<Entry>,
    textures: Vec<Texture>,
}

impl Materials {
    pub fn new(scene: &Scene) -> Materials {
        let mut nodes = Vec::new();
        let mut entries: Vec<Entry> = scene
            .materials
            .iter()
            .map(|m| Entry::new(m, &scene.textures, &mut nodes))
            .collect();
        entries.push(Entry::new(&Material::error(), &scene.textures, &mut nodes));
        for &(m, t) in &scene.emission_textures {
            entries[m.0 as usize].emission_texture = Some(t);
        }
        let mut materials = Materials {
            entries,
            nodes,
            textures: scene.textures.clone(),
        };
        materials.fix_constant_bsdfs();
        materials
    }

    /// Builds once the BSDFs that do not depend on the hit, so that shading them is a copy.
    fn fix_constant_bsdfs(&mut self) {
        let probe = SurfaceInteraction::default();
        let fixed: Vec<Option<[Bsdf; 2]>> = self
            .entries
            .iter()
            .chain(&self.nodes)
            .map(|e| {
                let leaf = Leaf(e);
                is_constant(e).then(|| {
                    [
                        self.bsdf(leaf, &probe, false),
                        self.bsdf(leaf, &probe, true),
                    ]
                })
            })
            .collect();
        let (a, b) = fixed.split_at(self.entries.len());
        for (e, f) in self.entries.iter_mut().zip(a) {
            e.fixed = *f;
        }
        for (e, f) in self.nodes.iter_mut().zip(b) {
            e.fixed = *f;
        }
    }

    /// The BSDF of material `material` seen from the front (`front`) or the back of the
    /// geometric normal, when it is the same at every hit; `None` when it must be built per
    /// hit ([`Materials::select`], [`Materials::shading_normal`], [`Materials::bsdf`]). A
    /// fixed material's hit also has the mesh's shading normal, opacity 1, an unchanged lobe
    /// number and an isotropic BSDF.
    #[inline]
    pub fn fixed(&self, material: u32, front: bool) -> Option<&Bsdf> {
        self.entries[material as usize]
            .fixed
            .as_ref()
            .map(|b| &b[front as usize])
    }

    /// True when some hit's BSDF reads the surface's parameterisation (UV, ∂p/∂u, ∂p/∂v,
    /// vertex or face colours): a texture anywhere, or a material that is not fixed.
    pub fn read_parameterisation(&self) -> bool {
        !self.textures.is_empty() || self.entries.iter().any(|e| e.fixed.is_none())
    }

    /// The flattened material `si` scatters with, and the lobe-choice number `u_lobe`
    /// still uniform for it: through each blend, child 1 with probability `weight` (clamped
    /// to [0, 1]), `u_lobe` rescaled to the chosen interval. Without blends, the material
    /// itself and `u_lobe` unchanged.
    #[inline]
    pub fn select(&self, si: &SurfaceInteraction, mut u_lobe: f32) -> (Leaf<'_>, f32) {
        let mut e = &self.entries[si.material as usize];
        while let Some((weight, [a, b])) = e.blend {
            let w = self.number(weight, si).clamp(0.0, 1.0);
            let child = if u_lobe < w {
                u_lobe /= w;
                b
            } else {
                u_lobe = ((u_lobe - w) / (1.0 - w)).min(1.0 - f32::EPSILON / 2.0);
                a
            };
            e = &self.nodes[child as usize];
        }
        (Leaf(e), u_lobe)
    }

    /// Calls `f` with every flattened material `si` may scatter with and the probability
    /// [`Materials::select`] chooses it with (through each blend, 1 − weight and weight).
    /// Children chosen with probability 0 are left out.
    #[inline]
    pub fn leaves(&self, si: &SurfaceInteraction, mut f: impl FnMut(Leaf<'_>, f32)) {
        self.leaves_below(&self.entries[si.material as usize], si, 1.0, &mut f);
    }

    fn leaves_below<'m>(
        &'m self,
        e: &'m Entry,
        si: &SurfaceInteraction,
        p: f32,
        f: &mut impl FnMut(Leaf<'m>, f32),
    ) {
        match e.blend {
            None => f(Leaf(e), p),
            Some((weight, [a, b])) => {
                let w = self.number(weight, si).clamp(0.0, 1.0);
                for (child, q) in [(a, 1.0 - w), (b, w)] {
                    if q > 0.0 {
                        self.leaves_below(&self.nodes[child as usize], si, p * q, f);
                    }
                }
            }
        }
    }

    /// False when no leaf of `material` may pass shadow rays ([`Leaf::may_pass`]): its
    /// straight-through transmittance is then 0 at every hit, whatever its blend weights.
    #[inline]
    pub fn may_pass(&self, material: u32, cutouts: bool) -> bool {
        self.subtree_may_pass(&self.entries[material as usize], cutouts)
    }

    fn subtree_may_pass(&self, e: &Entry, cutouts: bool) -> bool {
        match e.blend {
            None => Leaf(e).may_pass(cutouts),
            Some((_, children)) => children
                .iter()
                .any(|&c| self.subtree_may_pass(&self.nodes[c as usize], cutouts)),
        }
    }

    /// Index of the error material (for instances without one).
    pub fn error_index(&self) -> u32 {
        self.entries.len() as u32 - 1
    }

    /// The emitted radiance of a material, or of a textured one its scale.
    #[inline]
    pub fn emission(&self, material: u32) -> Vec3A {
        self.entries[material as usize].emission
    }

    /// The texture multiplying material `material`'s emission, as (texture index, its mean).
    pub fn emission_texture(&self, material: u32) -> Option<(u32, Vec3A)> {
        let t = self.entries[material as usize].emission_texture?;
        Some((t.0, texture::mean(&self.textures[t.0 as usize])))
    }

    /// The radiance emitted at `si` (front side; the caller checks the side).
    #[inline]
    pub fn emission_at(&self, si: &SurfaceInteraction) -> Vec3A {
        let e = &self.entries[si.material as usize];
        match e.emission_texture {
            None => e.emission,
            Some(t) => e.emission * texture::eval(&self.textures[t.0 as usize], si),
        }
    }

    #[inline]
    fn rgb(&self, p: Param<Rgb>, si: &SurfaceInteraction) -> Vec3A {
        match p {
            Param::Const(c) => c.into(),
            Param::Texture(t) => texture::eval(&self.textures[t.0 as usize], si),
        }
    }

    /// A number parameter; a texture gives its luminance (Mitsuba's `eval_1`, see
    /// [`texture::eval_1`]).
    #[inline]
    fn number(&self, p: Param<f32>, si: &SurfaceInteraction) -> f32 {
        match p {
            Param::Const(x) => x,
            Param::Texture(t) => texture::eval_1(&self.textures[t.0 as usize], si),
        }
    }

    /// The shading normal of `leaf` at `si` seen from `wo`: the mesh's, its normal map's or
    /// its bump map's (`bump.rs`, with the bump's shadowing term).
    ///
    /// Mitsuba 3.9.1 mirrors a normal-mapped normal the viewer is below and applies the same
    /// shadowing term to normal maps too; eyeadapt's normal maps (also glTF's, which have
    /// neither) do not, yet: that would need a flag on `Bsdf::NormalMap`.
    #[inline]
    pub fn shading_normal(
        &self,
        leaf: Leaf<'_>,
        si: &SurfaceInteraction,
        wo: Vec3A,
    ) -> (Vec3A, Option<Terminator>) {
        let n = self.normal_mapped(leaf, si);
        let Some((t, scale)) = leaf.0.bump else {
            return (n, None);
        };
        let g = height_gradient(&self.textures[t.0 as usize], si) * scale;
        let si_n = SurfaceInteraction { ns: n, ..*si };
        let m = bumped_normal(&si_n, g, wo);
        (m, Some(Terminator::new(n, m)))
    }

    /// The mesh's shading normal, or the normal map's, 2·rgb − 1 in the frame of the mesh's
    /// shading normal and ∂p/∂u (as Mitsuba's `normalmap`).
    #[inline]
    fn normal_mapped(&self, leaf: Leaf<'_>, si: &SurfaceInteraction) -> Vec3A {
        let Some(t) = leaf.0.normal_map else {
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

    /// The probability that a ray passes straight through `leaf` at `si` (its masks'
    /// opacity).
    #[inline]
    pub fn opacity(&self, leaf: Leaf<'_>, si: &SurfaceInteraction) -> f32 {
        leaf.0
            .opacity
            .iter()
            .map(|&p| self.number(p, si).clamp(0.0, 1.0))
            .product()
    }

    /// A microfacet distribution with roughness `alpha` (along ∂p/∂u when `alpha_v` is
    /// given), each at least `min`.
    #[inline]
    fn microfacet(
        &self,
        alpha: Param<f32>,
        alpha_v: Option<Param<f32>>,
        distribution: Distribution,
        si: &SurfaceInteraction,
        min: f32,
    ) -> Microfacet {
        let a = self.number(alpha, si).max(min);
        match alpha_v {
            None => Microfacet::new(a, distribution),
            Some(v) => Microfacet::anisotropic(a, self.number(v, si).max(min), distribution),
        }
    }

    /// The BSDF of `leaf` at `si`, seen from the front of the geometric normal when `front`
    /// (a dielectric's exterior; the back of a one-sided BSDF is black).
    #[inline]
    pub fn bsdf(&self, leaf: Leaf<'_>, si: &SurfaceInteraction, front: bool) -> Bsdf {
        let e = leaf.0;
        if let Some(b) = &e.fixed {
            return b[front as usize];
        }
        if e.one_sided && !front {
            return Bsdf::diffuse(Vec3A::ZERO);
        }
        match e.bsdf {
            SceneBsdf::Diffuse { reflectance } => Bsdf::diffuse(self.rgb(reflectance, si)),
            SceneBsdf::Conductor {
                alpha,
                alpha_v,
                distribution,
                eta,
                k,
                specular_reflectance,
            } => {
                let (a, specular) = (self.number(alpha, si), self.rgb(specular_reflectance, si));
                match alpha_v {
                    None => Bsdf::conductor(a, distribution, eta.into(), k.into(), specular),
                    Some(v) => {
                        let v = self.number(v, si);
                        Bsdf::conductor_uv(a, v, distribution, eta.into(), k.into(), specular)
                    }
                }
            }
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
                e.plastic
                    .expect("a plastic's table is built with its entry")
                    .0,
                e.plastic
                    .expect("a plastic's table is built with its entry")
                    .1,
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
                alpha_v,
                distribution,
                eta,
                specular_reflectance,
                specular_transmittance,
            } => Bsdf::RoughDielectric(RoughDielectric {
                // Mitsuba clamps a texture's roughness away from 0 the same way.
                md: self.microfacet(alpha, alpha_v, distribution, si, 1e-4),
                eta: if front { eta } else { 1.0 / eta },
                r: specular_reflectance.into(),
                t: specular_transmittance.into(),
            }),
            SceneBsdf::Principled(ref p) => Bsdf::Principled(Principled::at(
                p,
                front,
                |c| self.rgb(c, si),
                |x| self.number(x, si),
            )),
            SceneBsdf::PrincipledThin(ref p) => Bsdf::PrincipledThin(PrincipledThin::at(
                p,
                |c| self.rgb(c, si),
                |x| self.number(x, si),
            )),
            SceneBsdf::PPlastic {
                diffuse_reflectance,
                specular_reflectance,
                alpha,
                alpha_v,
                distribution,
                eta,
            } => Bsdf::PPlastic(PPlastic::new(
                self.microfacet(alpha, alpha_v, distribution, si, 1e-4),
                self.rgb(diffuse_reflectance, si),
                self.rgb(specular_reflectance, si),
                eta,
                e.spec_prob,
            )),
            // Flattened into the entry (a null surface's leaf is black and never scatters).
            SceneBsdf::OneSided(_)
            | SceneBsdf::Mask { .. }
            | SceneBsdf::NormalMap { .. }
            | SceneBsdf::BumpMap { .. }
            | SceneBsdf::Blend { .. }
            | SceneBsdf::Null => unreachable!(),
        }
    }
}

#[cfg(test)]
#[path = "material_tests.rs"]
mod tests;
