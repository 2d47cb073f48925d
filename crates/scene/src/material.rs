//! Materials: a BSDF plus optional one-sided emission.
//!
//! ```toml
//! [[materials]]
//! name = "white"
//! type = "diffuse"
//! reflectance = [0.73, 0.73, 0.73]
//!
//! [[materials]]
//! name = "lamp"
//! type = "diffuse"
//! reflectance = [0.78, 0.78, 0.78]
//! emission = [17.0, 12.0, 4.0]      # radiance, emitted on the front side only
//!
//! [[materials]]
//! name = "brushed"
//! type = "conductor"                # GGX microfacet metal; roughness 0 = perfect mirror
//! roughness = 0.2                   # GGX alpha
//! eta = [0.2, 0.92, 1.1]            # complex index of refraction per channel (default: gold-ish "Au")
//! k = [3.9, 2.45, 2.14]
//!
//! [[materials]]
//! name = "brushed_steel"
//! type = "conductor"                # conductor and dielectric: anisotropic roughness,
//! roughness_u = 0.05                # GGX alpha along ∂p/∂u (Mitsuba `alpha_u`)
//! roughness_v = 0.4                 # and along ∂p/∂v (`alpha_v`), instead of `roughness`
//! normal_map = "bricks"             # any type: a tangent-space normal map (a raw bitmap),
//! bump_map = "dimples"              # a height field and its scale,
//! bump_scale = 0.01
//! opacity = 0.5                     # a cut-out (or opacity_texture),
//! emission_texture = "slide"        # and emitted radiance from a texture
//!
//! [[materials]]
//! name = "bench"
//! type = "plastic"                  # GGX dielectric coating over a Lambertian base
//! reflectance = [0.4, 0.3, 0.2]     # diffuse base
//! roughness = 0.05                  # GGX alpha of the coating, clamped to >= 0.01
//! ior = 1.5
//!
//! [[materials]]
//! name = "window"
//! type = "dielectric"               # glass; `roughness` > 0 makes it rough (GGX)
//! ior = 1.5                         # interior over exterior
//!
//! [[materials]]
//! name = "pane"
//! type = "thin_dielectric"          # a thin sheet, light passes undeflected
//! ior = 1.5
//! ```
use crate::{Principled, PrincipledThin, Rgb, TextureId};

/// A material parameter: a constant, or a texture looked up at each hit (a texture read as a
/// number uses its luminance, as Mitsuba's `eval_1` does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Param<T> {
    Const(T),
    Texture(TextureId),
}

impl<T: Copy> Param<T> {
    /// The value when it is constant.
    pub fn constant(&self) -> Option<T> {
        match *self {
            Param::Const(v) => Some(v),
            Param::Texture(_) => None,
        }
    }
}

impl From<Rgb> for Param<Rgb> {
    fn from(c: Rgb) -> Self {
        Param::Const(c)
    }
}

impl From<f32> for Param<f32> {
    fn from(x: f32) -> Self {
        Param::Const(x)
    }
}

/// The microfacet distribution of a rough surface (Mitsuba's `distribution`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Distribution {
    /// Trowbridge–Reitz (GGX); sampled by its visible normals.
    #[default]
    Ggx,
    /// Beckmann–Spizzichino; sampled by the full distribution D(m)·cos θm.
    Beckmann,
}

/// Index into [`crate::Scene::materials`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MaterialId(pub u32);

/// The scattering part of a material.
#[derive(Clone, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian reflector.
    Diffuse { reflectance: Param<Rgb> },
    /// Microfacet conductor with a per-channel complex IOR; `alpha == 0` is a perfect mirror.
    Conductor {
        /// The roughness; along ∂p/∂u when `alpha_v` is given.
        alpha: Param<f32>,
        /// The roughness along ∂p/∂v of an anisotropic surface (Mitsuba's `alpha_v`; `alpha`
        /// is then its `alpha_u`); `None`: isotropic.
        alpha_v: Option<Param<f32>>,
        distribution: Distribution,
        eta: Rgb,
        k: Rgb,
        specular_reflectance: Param<Rgb>,
    },
    /// Microfacet dielectric coating (`ior`) over a Lambertian base (`reflectance`), after
    /// Mitsuba's `roughplastic` with `nonlinear = false`, or its smooth `plastic` when
    /// `alpha` is a constant 0.
    Plastic {
        reflectance: Param<Rgb>,
        /// Clamped to at least 0.01 where it is evaluated. A constant 0 is a smooth coating:
        /// its transmittance and internal reflectance are the smooth interface's (Mitsuba's
        /// `plastic`), its specular lobe is GGX alpha 0.01.
        alpha: Param<f32>,
        distribution: Distribution,
        ior: f32,
    },
    /// A smooth dielectric interface (glass, water): Fresnel reflection and refraction.
    /// `eta` is the interior's IOR over the exterior's (> 0, ≠ 1 for any refraction); the
    /// front side (the geometric normal's) is the exterior.
    Dielectric {
        eta: f32,
        specular_reflectance: Rgb,
        specular_transmittance: Rgb,
    },
    /// A thin dielectric sheet (a window pane): the two interfaces' inter-reflections summed,
    /// light leaves undeflected.
    ThinDielectric {
        eta: f32,
        specular_reflectance: Rgb,
        specular_transmittance: Rgb,
    },
    /// A rough dielectric interface (Walter et al. 2007), `eta` as for [`Bsdf::Dielectric`].
    RoughDielectric {
        alpha: Param<f32>,
        /// As for [`Bsdf::Conductor`].
        alpha_v: Option<Param<f32>>,
        distribution: Distribution,
        eta: f32,
        specular_reflectance: Rgb,
        specular_transmittance: Rgb,
    },
    /// A reflecting BSDF that is black seen from the back side (Mitsuba's BSDFs outside a
    /// `twosided`); every other BSDF reflects alike on both sides. Transmitting BSDFs are never
    /// wrapped.
    OneSided(Box<Bsdf>),
    /// A cut-out: the inner BSDF where `opacity` is 1, nothing (light passes straight through)
    /// where it is 0, a stochastic mix in between (Mitsuba's `mask`).
    Mask {
        opacity: Param<f32>,
        bsdf: Box<Bsdf>,
    },
    /// The inner BSDF with its shading normal taken from a tangent-space normal map
    /// (Mitsuba's `normalmap`: the texture's RGB in [0, 1] is the normal 2·rgb − 1 in the
    /// frame of the shading normal and ∂p/∂u).
    NormalMap { normals: TextureId, bsdf: Box<Bsdf> },
    /// Mitsuba's `principled` (Disney's BSDF, `principled.rs`).
    Principled(Box<Principled>),
    /// Mitsuba's `principledthin` (a thin principled sheet, `principled.rs`).
    PrincipledThin(Box<PrincipledThin>),
    /// The inner BSDF with its shading normal perturbed by the gradient of a height field
    /// (Mitsuba's `bumpmap`): the texture's value (a number) times `scale` displaces the
    /// surface along its shading normal, in the frame of ∂p/∂u and ∂p/∂v.
    BumpMap {
        height: TextureId,
        scale: f32,
        bsdf: Box<Bsdf>,
    },
    /// A linear blend of two BSDFs (Mitsuba's `blendbsdf`): `bsdfs[0]` where `weight` is 0,
    /// `bsdfs[1]` where it is 1 (a texture is read as a number and clamped to [0, 1]).
    Blend {
        weight: Param<f32>,
        bsdfs: Box<[Bsdf; 2]>,
    },
    /// No surface at all (Mitsuba's `null`): rays pass straight through, as through a mask
    /// of opacity 0.
    Null,
    /// Mitsuba's `pplastic` as its RGB variants render it (no polarisation): a microfacet
    /// Fresnel reflection (`specular_reflectance` × F × D × G / (4 cos cos)) plus the diffuse
    /// base attenuated by the Fresnel transmittance in and out, without roughplastic's
    /// internal-scattering normalisation.
    PPlastic {
        diffuse_reflectance: Param<Rgb>,
        specular_reflectance: Param<Rgb>,
        alpha: Param<f32>,
        alpha_v: Option<Param<f32>>,
        distribution: Distribution,
        /// Interior over exterior IOR.
        eta: f32,
    },
}

/// A named material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub bsdf: Bsdf,
    /// Emitted radiance on the front side (zero for non-emitters).
    pub emission: Rgb,
}

impl Material {
    /// The loud stand-in for missing or unknown materials: a saturated magenta diffuser that
    /// no one mistakes for intended content (it does not emit, so it cannot light the scene).
    pub fn error() -> Material {
        Material {
            name: "<error>".into(),
            bsdf: Bsdf::Diffuse {
                reflectance: Param::Const(Rgb::new(0.8, 0.0, 0.8)),
            },
            emission: Rgb::ZERO,
        }
    }

    pub fn diffuse(name: &str, reflectance: Rgb) -> Material {
        Material {
            name: name.into(),
            bsdf: Bsdf::Diffuse {
                reflectance: Param::Const(reflectance),
            },
            emission: Rgb::ZERO,
        }
    }

    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }
}
