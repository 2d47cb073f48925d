//! glTF textures as entries of the scene's texture table.
//!
//! An image (external file, data URI or buffer view, PNG or JPEG) is decoded once; each way a
//! material reads it becomes its own [`Bitmap`] of linear texels, made once per (image, use,
//! factor):
//! - base colour: the sRGB-encoded RGB decoded to linear (glTF §3.9.2), times the base colour
//!   factor;
//! - roughness: glTF's metallic-roughness texture holds roughness in G (and metallic in B),
//!   linear; the texel becomes the GGX α = (factor · G)² the BSDFs take, as a grey texel (a
//!   number parameter reads a texture's luminance, which is the grey value itself);
//! - opacity: the base colour texture's alpha times the factor's, cut to 0 or 1 at
//!   `alphaCutoff` in MASK mode, as it is in BLEND mode (a grey texel, as for roughness).
//!
//! The sampler's magnification filter picks nearest or bilinear lookups, its wrap modes
//! Mitsuba's repeat / mirror / clamp (one mode for both axes: a sampler that differs between S
//! and T is read with S's and warned about). `KHR_texture_transform` becomes the bitmap's
//! `to_uv`; the transformed coordinates are in glTF's convention, which is the scene's
//! ((0, 0) the image's top-left corner, v down).
use super::read::{GltfFile, at, check_regular, uri_to_path};
// Largest decoded image accepted: the bitmap textures' bound, so that a hostile header cannot
// ask for more memory than the machine has.
use crate::image_file::MAX_TEXELS;
use crate::{Bitmap, Diagnostic, FilterType, Image, Rgb, Scene, Texture, TextureId, WrapMode};
use glam::{Affine2, Mat2, Vec2};
use std::collections::HashMap;
use std::sync::Arc;

/// How a material reads an image.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub enum Use {
    /// sRGB colour times the factor (RGB bits of the factor in the key).
    BaseColor([u32; 3]),
    /// (factor · G)², the factor's bits in the key.
    Alpha(u32),
    /// Opacity: factor · A, cut to 0 or 1 at `cutoff` for glTF's MASK mode (bits in the key).
    Opacity { factor: u32, cutoff: Option<u32> },
    /// A tangent-space normal, linear RGB = (n + 1) / 2, its x and y times the normal
    /// texture's `scale` (bits in the key) and the result renormalised, so that the texel
    /// stays in [0, 1] and is what [`crate::Bsdf::NormalMap`] reads.
    Normal(u32),
}

/// A texture reference: a material's `textureInfo` or its normal texture (which glTF
/// gives a `scale` instead of a factor, and the `gltf` crate no `KHR_texture_transform`).
pub struct TexRef<'a> {
    pub texture: gltf::Texture<'a>,
    pub tex_coord: u32,
    pub transform: Option<gltf::texture::TextureTransform<'a>>,
}

impl<'a> From<&gltf::texture::Info<'a>> for TexRef<'a> {
    fn from(info: &gltf::texture::Info<'a>) -> TexRef<'a> {
        TexRef {
            texture: info.texture(),
            tex_coord: info.tex_coord(),
            transform: info.texture_transform(),
        }
    }
}

/// Decoded images and the textures made from them, for one file.
pub struct Textures<'a> {
    file: &'a GltfFile,
    /// Channel values in [0, 1] (RGBA, not yet sRGB-decoded), by image index.
    decoded: HashMap<usize, Arc<Decoded>>,
    made: HashMap<(usize, Use, SamplerKey), TextureId>,
}

struct Decoded {
    width: u32,
    height: u32,
    rgba: Vec<[f32; 4]>,
}

/// What of a texture reference changes the lookup: filter, wrap and transform bits.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct SamplerKey {
    filter: FilterType,
    wrap: WrapMode,
    to_uv: [u32; 6],
}

impl<'a> Textures<'a> {
    pub fn new(file: &'a GltfFile) -> Textures<'a> {
        Textures {
            file,
            decoded: HashMap::new(),
            made: HashMap::new(),
        }
    }

    /// The texture table entry for `info` read as `usage`; `pointer` is the JSON pointer of
    /// the texture reference (messages). Errors name the image; a UV set other than 0 is a
    /// warning (read with TEXCOORD_0).
    pub fn get<'r>(
        &mut self,
        scene: &mut Scene,
        info: impl Into<TexRef<'r>>,
        usage: Use,
        pointer: &str,
        warnings: &mut Vec<Diagnostic>,
    ) -> Result<TextureId, Diagnostic> {
        let TexRef {
            texture: tex,
            tex_coord,
            transform,
        } = info.into();
        let image = tex.source().index();
        let set = transform
            .as_ref()
            .and_then(|t| t.tex_coord())
            .unwrap_or(tex_coord);
        if set != 0 {
            warnings.push(at(
                &self.file.path,
                &format!("{pointer}/texCoord"),
                format!("UV set {set} is read as TEXCOORD_0 (only the first UV set is kept)"),
            ));
        }
        let key = SamplerKey {
            filter: filter(&tex.sampler()),
            wrap: wrap(&self.file.path, &tex, warnings),
            to_uv: to_uv(transform.as_ref()).to_cols_array().map(f32::to_bits),
        };
        if let Some(id) = self.made.get(&(image, usage, key)) {
            return Ok(*id);
        }
        let decoded = self.decode(image)?;
        let texels = decoded.rgba.iter().map(|p| texel(p, usage)).collect();
        let id = scene.add_texture(Texture::Bitmap(Bitmap {
            filename: self.file.path.join(format!("#images/{image}")),
            image: Arc::new(Image {
                width: decoded.width,
                height: decoded.height,
                texels,
            }),
            raw: true,
            filter: key.filter,
            wrap: key.wrap,
            to_uv: Affine2::from_cols_array(&key.to_uv.map(f32::from_bits)),
        }));
        self.made.insert((image, usage, key), id);
        Ok(id)
    }

    /// The mean of channel `c` (0 = R … 3 = A) of the image `info` names.
    pub fn channel_mean(
        &mut self,
        info: &gltf::texture::Info,
        c: usize,
    ) -> Result<f32, Diagnostic> {
        let d = self.decode(info.texture().source().index())?;
        let sum: f64 = d.rgba.iter().map(|p| f64::from(p[c])).sum();
        Ok((sum / d.rgba.len().max(1) as f64) as f32)
    }

    /// The smallest and largest value of channel `c` of the image `info` names.
    pub fn channel_range(
        &mut self,
        info: &gltf::texture::Info,
        c: usize,
    ) -> Result<(f32, f32), Diagnostic> {
        let d = self.decode(info.texture().source().index())?;
        Ok(d.rgba
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[c]), hi.max(p[c]))
            }))
    }

    fn decode(&mut self, index: usize) -> Result<Arc<Decoded>, Diagnostic> {
        if let Some(d) = self.decoded.get(&index) {
            return Ok(d.clone());
        }
        let file = self.file;
        let image = file
            .document
            .images()
            .nth(index)
            .expect("gltf validated texture sources");
        let pointer = format!("/images/{index}");
        let base = file.path.parent().unwrap_or(std::path::Path::new("."));
        let source = image.source();
        if let gltf::image::Source::Uri { uri, .. } = &source
            && !uri.starts_with("data:")
        {
            check_regular(&base.join(uri_to_path(uri)), "image")
                .map_err(|m| at(&file.path, &format!("{pointer}/uri"), m))?;
        }
        let data =
            gltf::image::Data::from_source(source, Some(base), &file.buffers).map_err(|e| {
                at(
                    &file.path,
                    &pointer,
                    format!("cannot decode the image: {e}"),
                )
            })?;
        if u64::from(data.width) * u64::from(data.height) > MAX_TEXELS {
            return Err(at(
                &file.path,
                &pointer,
                format!(
                    "the image is {}×{} texels, more than the {MAX_TEXELS} accepted",
                    data.width, data.height
                ),
            ));
        }
        let rgba = channels(&data)
            .ok_or_else(|| at(&file.path, &pointer, "the image's pixel data is truncated"))?;
        let d = Arc::new(Decoded {
            width: data.width,
            height: data.height,
            rgba,
        });
        self.decoded.insert(index, d.clone());
        Ok(d)
    }
}

/// One linear texel of `usage` from channel values `p`.
fn texel(p: &[f32; 4], usage: Use) -> Rgb {
    use crate::image_file::srgb_to_linear;
    match usage {
        Use::BaseColor(f) => {
            let f = Rgb::from_array(f.map(f32::from_bits));
            Rgb::new(
                srgb_to_linear(p[0]),
                srgb_to_linear(p[1]),
                srgb_to_linear(p[2]),
            ) * f
        }
        Use::Alpha(f) => {
            let r = (f32::from_bits(f) * p[1]).clamp(0.0, 1.0);
            Rgb::splat(r * r)
        }
        Use::Opacity { factor, cutoff } => {
            let a = (f32::from_bits(factor) * p[3]).clamp(0.0, 1.0);
            Rgb::splat(match cutoff {
                Some(c) if a >= f32::from_bits(c) => 1.0,
                Some(_) => 0.0,
                None => a,
            })
        }
        Use::Normal(scale) => {
            let s = f32::from_bits(scale);
            let n = glam::Vec3::new(
                (2.0 * p[0] - 1.0) * s,
                (2.0 * p[1] - 1.0) * s,
                2.0 * p[2] - 1.0,
            )
            .normalize_or(glam::Vec3::Z);
            (n + Rgb::ONE) * 0.5
        }
    }
}

/// The image's pixels as RGBA in [0, 1] (grey replicated, missing alpha 1), or `None` when
/// the data is shorter than its size says.
fn channels(d: &gltf::image::Data) -> Option<Vec<[f32; 4]>> {
    use gltf::image::Format as F;
    let (n, bytes) = match d.format {
        F::R8 => (1, 1),
        F::R8G8 => (2, 1),
        F::R8G8B8 => (3, 1),
        F::R8G8B8A8 => (4, 1),
        F::R16 => (1, 2),
        F::R16G16 => (2, 2),
        F::R16G16B16 => (3, 2),
        F::R16G16B16A16 => (4, 2),
        F::R32G32B32FLOAT => (3, 4),
        F::R32G32B32A32FLOAT => (4, 4),
    };
    let count = d.width as usize * d.height as usize;
    let stride = n * bytes;
    if d.pixels.len() < count * stride {
        return None;
    }
    let value = |b: &[u8]| -> f32 {
        match bytes {
            1 => f32::from(b[0]) / 255.0,
            2 => f32::from(u16::from_ne_bytes([b[0], b[1]])) / 65535.0,
            _ => f32::from_ne_bytes([b[0], b[1], b[2], b[3]]),
        }
    };
    Some(
        d.pixels
            .chunks_exact(stride)
            .take(count)
            .map(|px| {
                let c = |i: usize| value(&px[i * bytes..(i + 1) * bytes]);
                match n {
                    1 => [c(0), c(0), c(0), 1.0],
                    2 => [c(0), c(0), c(0), c(1)],
                    3 => [c(0), c(1), c(2), 1.0],
                    _ => [c(0), c(1), c(2), c(3)],
                }
            })
            .collect(),
    )
}

fn filter(s: &gltf::texture::Sampler) -> FilterType {
    match s.mag_filter() {
        Some(gltf::texture::MagFilter::Nearest) => FilterType::Nearest,
        _ => FilterType::Bilinear,
    }
}

fn wrap(file: &std::path::Path, tex: &gltf::Texture, warnings: &mut Vec<Diagnostic>) -> WrapMode {
    use gltf::texture::WrappingMode as W;
    let mode = |w: W| match w {
        W::ClampToEdge => WrapMode::Clamp,
        W::MirroredRepeat => WrapMode::Mirror,
        W::Repeat => WrapMode::Repeat,
    };
    let s = tex.sampler();
    let (ws, wt) = (mode(s.wrap_s()), mode(s.wrap_t()));
    if ws != wt {
        let pointer = match s.index() {
            Some(i) => format!("/samplers/{i}/wrapT"),
            None => format!("/textures/{}/sampler", tex.index()),
        };
        warnings.push(at(
            file,
            &pointer,
            "different wrap modes for S and T: both are read with wrapS's",
        ));
    }
    ws
}

/// `KHR_texture_transform` as a UV transform: translation · rotation · scale, where the
/// extension's GLSL `mat3(cos, sin, 0, −sin, cos, 0, 0, 0, 1)` is column-major: u′ = u cos −
/// v sin, v′ = u sin + v cos.
fn to_uv(t: Option<&gltf::texture::TextureTransform>) -> Affine2 {
    let Some(t) = t else {
        return Affine2::IDENTITY;
    };
    let (s, c) = libm::sincosf(t.rotation());
    let rotation = Mat2::from_cols(Vec2::new(c, s), Vec2::new(-s, c));
    let scale = Mat2::from_diagonal(Vec2::from_array(t.scale()));
    Affine2::from_mat2_translation(rotation * scale, Vec2::from_array(t.offset()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base_colour_texels_are_decoded_from_srgb_and_scaled() {
        let f = [0.5f32, 1.0, 2.0].map(f32::to_bits);
        let t = texel(&[1.0, 0.5, 0.0, 1.0], Use::BaseColor(f));
        assert!((t.x - 0.5).abs() < 1e-6);
        assert!((t.y - 0.214_041).abs() < 1e-5, "{t}");
        assert_eq!(t.z, 0.0);
    }

    #[test]
    fn roughness_texels_become_ggx_alpha_from_the_green_channel() {
        // G = 0.6 (R and B, occlusion and metallic, are ignored), factor 0.5: α = 0.3².
        let t = texel(&[0.9, 0.6, 0.1, 1.0], Use::Alpha(0.5f32.to_bits()));
        assert!((t - Rgb::splat(0.09)).abs().max_element() < 1e-6, "{t}");
    }

    #[test]
    fn opacity_texels_are_the_alpha_channel_cut_in_mask_mode() {
        let p = [0.2, 0.2, 0.2, 0.6];
        let blend = Use::Opacity {
            factor: 0.5f32.to_bits(),
            cutoff: None,
        };
        assert!((texel(&p, blend).x - 0.3).abs() < 1e-6);
        let mask = |c: f32| Use::Opacity {
            factor: 1.0f32.to_bits(),
            cutoff: Some(c.to_bits()),
        };
        assert_eq!(texel(&p, mask(0.5)), Rgb::ONE);
        assert_eq!(texel(&p, mask(0.7)), Rgb::ZERO);
    }

    #[test]
    fn grey_and_sixteen_bit_pixels_are_read() {
        let d = gltf_image(gltf::image::Format::R16, 2, 1, {
            let mut v = 65535u16.to_ne_bytes().to_vec();
            v.extend(0u16.to_ne_bytes());
            v
        });
        assert_eq!(
            channels(&d).unwrap(),
            vec![[1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0]]
        );
        let short = gltf_image(gltf::image::Format::R8G8B8, 2, 2, vec![0; 11]);
        assert!(channels(&short).is_none());
    }

    fn gltf_image(
        format: gltf::image::Format,
        w: u32,
        h: u32,
        pixels: Vec<u8>,
    ) -> gltf::image::Data {
        gltf::image::Data {
            pixels,
            format,
            width: w,
            height: h,
        }
    }
}
