//! How materials feed a fingerprint: the BSDF tree, variant by variant.
use super::{Feed, tag};
use crate::{Bsdf, Distribution, Material, Principled, PrincipledThin};
use sha2::Sha256;

impl Feed for Material {
    fn feed(&self, h: &mut Sha256) {
        let Material {
            name,
            bsdf,
            emission,
        } = self;
        name.feed(h);
        emission.feed(h);
        bsdf.feed(h);
    }
}

impl Feed for Distribution {
    /// GGX feeds nothing, so the fingerprints of scenes from before the distribution existed
    /// (all GGX) stay the same.
    fn feed(&self, h: &mut Sha256) {
        match self {
            Distribution::Ggx => {}
            Distribution::Beckmann => tag(h, 1),
        }
    }
}

impl Feed for Bsdf {
    fn feed(&self, h: &mut Sha256) {
        match self {
            Bsdf::Diffuse { reflectance } => {
                tag(h, 0);
                reflectance.feed(h);
            }
            Bsdf::Conductor {
                alpha,
                alpha_v,
                distribution,
                eta,
                k,
                specular_reflectance,
            } => {
                tag(h, 1);
                alpha.feed(h);
                feed_alpha_v(alpha_v, h);
                distribution.feed(h);
                eta.feed(h);
                k.feed(h);
                specular_reflectance.feed(h);
            }
            Bsdf::Plastic {
                reflectance,
                alpha,
                distribution,
                ior,
            } => {
                tag(h, 2);
                reflectance.feed(h);
                alpha.feed(h);
                distribution.feed(h);
                ior.feed(h);
            }
            Bsdf::Dielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            } => {
                tag(h, 3);
                eta.feed(h);
                specular_reflectance.feed(h);
                specular_transmittance.feed(h);
            }
            Bsdf::ThinDielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            } => {
                tag(h, 4);
                eta.feed(h);
                specular_reflectance.feed(h);
                specular_transmittance.feed(h);
            }
            Bsdf::RoughDielectric {
                alpha,
                alpha_v,
                distribution,
                eta,
                specular_reflectance,
                specular_transmittance,
            } => {
                tag(h, 5);
                alpha.feed(h);
                feed_alpha_v(alpha_v, h);
                distribution.feed(h);
                eta.feed(h);
                specular_reflectance.feed(h);
                specular_transmittance.feed(h);
            }
            // Wrappers (and the null surface) are tagged 6–8 and 11–13.
            Bsdf::OneSided(_)
            | Bsdf::Mask { .. }
            | Bsdf::NormalMap { .. }
            | Bsdf::BumpMap { .. }
            | Bsdf::Blend { .. }
            | Bsdf::Null => feed_wrapper(self, h),
            Bsdf::Principled(p) => {
                tag(h, 9);
                p.feed(h);
            }
            Bsdf::PrincipledThin(p) => {
                tag(h, 10);
                p.feed(h);
            }
            Bsdf::PPlastic {
                diffuse_reflectance,
                specular_reflectance,
                alpha,
                alpha_v,
                distribution,
                eta,
            } => {
                tag(h, 14);
                diffuse_reflectance.feed(h);
                specular_reflectance.feed(h);
                alpha.feed(h);
                feed_alpha_v(alpha_v, h);
                distribution.feed(h);
                eta.feed(h);
            }
        }
    }
}

impl Feed for Principled {
    fn feed(&self, h: &mut Sha256) {
        let Principled {
            base_color,
            roughness,
            metallic,
            spec_tint,
            anisotropic,
            sheen,
            sheen_tint,
            clearcoat,
            clearcoat_gloss,
            spec_trans,
            flatness,
            eta,
        } = self;
        base_color.feed(h);
        for p in [
            roughness,
            metallic,
            spec_tint,
            anisotropic,
            sheen,
            sheen_tint,
            clearcoat,
            clearcoat_gloss,
            spec_trans,
            flatness,
        ] {
            p.feed(h);
        }
        eta.feed(h);
    }
}

impl Feed for PrincipledThin {
    fn feed(&self, h: &mut Sha256) {
        let PrincipledThin {
            base_color,
            roughness,
            spec_tint,
            anisotropic,
            sheen,
            sheen_tint,
            spec_trans,
            flatness,
            diff_trans,
            eta,
        } = self;
        base_color.feed(h);
        for p in [
            roughness,
            spec_tint,
            anisotropic,
            sheen,
            sheen_tint,
            spec_trans,
            flatness,
            diff_trans,
            eta,
        ] {
            p.feed(h);
        }
    }
}

/// A BSDF that wraps others (or none): its tag, its own parameters, then what it wraps.
fn feed_wrapper(b: &Bsdf, h: &mut Sha256) {
    match b {
        Bsdf::OneSided(b) => {
            tag(h, 6);
            b.feed(h);
        }
        Bsdf::Mask { opacity, bsdf } => {
            tag(h, 7);
            opacity.feed(h);
            bsdf.feed(h);
        }
        Bsdf::NormalMap { normals, bsdf } => {
            tag(h, 8);
            normals.0.feed(h);
            bsdf.feed(h);
        }
        Bsdf::BumpMap {
            height,
            scale,
            bsdf,
        } => {
            tag(h, 11);
            height.0.feed(h);
            scale.feed(h);
            bsdf.feed(h);
        }
        Bsdf::Blend { weight, bsdfs } => {
            tag(h, 12);
            weight.feed(h);
            bsdfs[0].feed(h);
            bsdfs[1].feed(h);
        }
        Bsdf::Null => tag(h, 13),
        _ => unreachable!("Bsdf::feed passes only wrappers"),
    }
}

/// An anisotropic surface's second roughness; nothing for an isotropic one, so that the
/// fingerprints of scenes from before anisotropy stay the same. (Its tag, 2, differs from
/// Beckmann's 1, which may follow.)
fn feed_alpha_v(alpha_v: &Option<crate::Param<f32>>, h: &mut Sha256) {
    if let Some(a) = alpha_v {
        tag(h, 2);
        a.feed(h);
    }
}
