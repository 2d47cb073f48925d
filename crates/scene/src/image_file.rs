//! Decoding bitmap files (PNG, JPEG, BMP, TGA, HDR, EXR) into linear texels, once per file.
//!
//! Mitsuba's rule (`raw = false`): integer formats (8- and 16-bit PNG, JPEG, BMP, TGA) hold
//! sRGB-encoded values and are decoded to linear with the sRGB transfer function; float formats
//! (HDR, EXR) are linear already. With `raw = true` values are taken as they are (integers
//! divided by their maximum). Grey images are replicated into RGB; alpha is ignored.
use crate::{Image, Rgb};
use image::{DynamicImage, ImageReader};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The sRGB transfer function, inverted (IEC 61966-2-1).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        libm::powf((c + 0.055) / 1.055, 2.4)
    }
}

/// Most texels a texture may have, bitmap or glTF image (16384², 3 GiB as linear f32).
pub const MAX_TEXELS: u64 = 1 << 28;

/// Decodes `path`; the message names the file and what is wrong with it.
pub fn load_image(path: &Path, raw: bool) -> Result<Image, String> {
    let file = crate::open_input(path)
        .map_err(|e| format!("cannot read image {}: {e}", path.display()))?;
    decode_image(std::io::BufReader::new(file), path, raw)
}

/// Decodes an image file's bytes read from `input`; `path` names it (and its extension the
/// format) in messages.
fn decode_image(
    input: impl std::io::BufRead + std::io::Seek,
    path: &Path,
    raw: bool,
) -> Result<Image, String> {
    // The extension names the format (as `ImageReader::open` does) unless the content says
    // otherwise.
    let mut reader = ImageReader::new(input);
    if let Ok(format) = image::ImageFormat::from_path(path) {
        reader.set_format(format);
    }
    let reader = reader
        .with_guessed_format()
        .map_err(|e| format!("cannot read texture file {}: {e}", path.display()))?;
    use image::ImageFormat as F;
    let known = |f: F| matches!(f, F::Png | F::Jpeg | F::OpenExr | F::Hdr | F::Bmp | F::Tga);
    if !reader.format().is_some_and(known) {
        return Err(format!(
            "texture file {}: unknown image format (expected PNG, JPEG, BMP, TGA, HDR or EXR)",
            path.display()
        ));
    }
    let too_large = |w: u32, h: u32| {
        format!(
            "texture file {} is {w}x{h} pixels, more than the {MAX_TEXELS} texels a texture may have",
            path.display()
        )
    };
    // The decoder allocates at most `image`'s default 512 MiB; a header asking for more is a
    // Limits error, told with the size the header claims.
    let img = reader
        .decode()
        .map_err(|e| match (&e, image::image_dimensions(path)) {
            (image::ImageError::Limits(_), Ok((w, h))) => too_large(w, h),
            _ => format!("cannot decode texture file {}: {e}", path.display()),
        })?;
    // Linear f32 texels take 12 bytes each, up to 24 times the decoded bytes.
    if img.width() as u64 * img.height() as u64 > MAX_TEXELS {
        return Err(too_large(img.width(), img.height()));
    }
    let float = matches!(
        img,
        DynamicImage::ImageRgb32F(_) | DynamicImage::ImageRgba32F(_)
    );
    let decode = |c: f32| if float || raw { c } else { srgb_to_linear(c) };
    let texels = linear_texels(&img, decode);
    if let Some(bad) = texels.iter().find(|t| crate::check_colour(**t).is_err()) {
        return Err(format!(
            "texture file {} has an unusable texel {bad:?} (NaN, infinite, negative or huge)",
            path.display()
        ));
    }
    Ok(Image {
        width: img.width(),
        height: img.height(),
        texels,
    })
}

/// The texels of `img`, each channel as `to_rgb32f` gives it passed through `decode`. The
/// channels of an 8-bit image take 256 values, so each is decoded once (sRGB decoding costs a
/// `powf` per channel, 7 % of setting up `builtin:interior`): the same bits.
fn linear_texels(img: &DynamicImage, decode: impl Fn(f32) -> f32) -> Vec<Rgb> {
    use DynamicImage as D;
    // Each byte value's channels as the float conversion gives them for this layout (they
    // differ in the last bit between layouts).
    let probe = |v: u8| match img {
        D::ImageLuma8(_) => Some(D::ImageLuma8(image::GrayImage::from_pixel(
            1,
            1,
            image::Luma([v]),
        ))),
        D::ImageLumaA8(_) => Some(D::ImageLumaA8(image::GrayAlphaImage::from_pixel(
            1,
            1,
            image::LumaA([v, 255]),
        ))),
        D::ImageRgb8(_) => Some(D::ImageRgb8(image::RgbImage::from_pixel(
            1,
            1,
            image::Rgb([v; 3]),
        ))),
        D::ImageRgba8(_) => Some(D::ImageRgba8(image::RgbaImage::from_pixel(
            1,
            1,
            image::Rgba([v, v, v, 255]),
        ))),
        _ => None,
    };
    if probe(0).is_some() {
        let lut: Vec<[f32; 3]> = (0..=255u8)
            .map(|v| {
                let p = probe(v)
                    .expect("an 8-bit layout")
                    .to_rgb32f()
                    .get_pixel(0, 0)
                    .0;
                p.map(&decode)
            })
            .collect();
        return img
            .to_rgb8()
            .pixels()
            .map(|p| {
                let c = |i: usize| lut[p[i] as usize][i];
                Rgb::new(c(0), c(1), c(2))
            })
            .collect();
    }
    img.to_rgb32f()
        .pixels()
        .map(|p| Rgb::new(decode(p[0]), decode(p[1]), decode(p[2])))
        .collect()
}

/// Decoded images by (file, raw), so every texture naming a file shares one copy; files
/// embedded in the binary (the built-in scenes' images) are read from memory instead.
#[derive(Default)]
pub struct ImageCache {
    decoded: HashMap<(PathBuf, bool), Arc<Image>>,
    embedded: HashMap<PathBuf, &'static [u8]>,
}

impl ImageCache {
    /// A cache in which `files` (path, bytes) stand for the files at those paths.
    pub fn with_embedded(files: impl IntoIterator<Item = (PathBuf, &'static [u8])>) -> Self {
        ImageCache {
            decoded: HashMap::new(),
            embedded: files.into_iter().collect(),
        }
    }

    pub fn get(&mut self, path: &Path, raw: bool) -> Result<Arc<Image>, String> {
        let key = (path.to_path_buf(), raw);
        if let Some(img) = self.decoded.get(&key) {
            return Ok(img.clone());
        }
        let img = Arc::new(match self.embedded.get(path) {
            Some(bytes) => decode_image(std::io::Cursor::new(*bytes), path, raw)?,
            None => load_image(path, raw)?,
        });
        self.decoded.insert(key, img.clone());
        Ok(img)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decoding_matches_the_standard() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        // 0.5 encoded is 0.2140 linear; the linear segment below 0.04045.
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-5);
        assert!((srgb_to_linear(0.04) - 0.04 / 12.92).abs() < 1e-7);
    }

    #[test]
    fn png_is_decoded_from_srgb_unless_raw() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        let mut img = image::RgbImage::new(2, 1);
        img.put_pixel(0, 0, image::Rgb([255, 128, 0]));
        img.put_pixel(1, 0, image::Rgb([0, 0, 255]));
        img.save(&path).unwrap();
        let lin = load_image(&path, false).unwrap();
        assert_eq!((lin.width, lin.height), (2, 1));
        assert!((lin.texels[0].x - 1.0).abs() < 1e-6);
        assert!((lin.texels[0].y - srgb_to_linear(128.0 / 255.0)).abs() < 1e-6);
        let raw = load_image(&path, true).unwrap();
        assert!((raw.texels[0].y - 128.0 / 255.0).abs() < 1e-6);
        assert_eq!(raw.texels[1], Rgb::new(0.0, 0.0, 1.0));
    }

    /// The byte table gives every 8-bit layout exactly the texels of decoding each channel of
    /// `to_rgb32f`, as before it: every byte value in every channel, sRGB and raw.
    #[test]
    fn eight_bit_images_decode_through_the_table_bit_for_bit() {
        let rgba = image::RgbaImage::from_fn(256, 3, |x, y| {
            let b = x as u8;
            image::Rgba([
                b,
                b.wrapping_mul(7).wrapping_add(y as u8),
                255 - b,
                b ^ 0x5a,
            ])
        });
        let images = [
            DynamicImage::ImageRgba8(rgba.clone()),
            DynamicImage::ImageRgb8(DynamicImage::ImageRgba8(rgba.clone()).to_rgb8()),
            DynamicImage::ImageLuma8(DynamicImage::ImageRgba8(rgba.clone()).to_luma8()),
            DynamicImage::ImageLumaA8(DynamicImage::ImageRgba8(rgba).to_luma_alpha8()),
        ];
        for img in &images {
            for decode in [srgb_to_linear, |c| c] {
                let want: Vec<[u32; 3]> = img
                    .to_rgb32f()
                    .pixels()
                    .map(|p| [0, 1, 2].map(|i| decode(p[i]).to_bits()))
                    .collect();
                let got: Vec<[u32; 3]> = linear_texels(img, decode)
                    .iter()
                    .map(|t| [t.x.to_bits(), t.y.to_bits(), t.z.to_bits()])
                    .collect();
                assert_eq!(got, want, "{:?}", img.color());
            }
        }
    }

    #[test]
    fn bad_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let missing = load_image(&dir.path().join("none.png"), false).unwrap_err();
        assert!(missing.contains("none.png") && missing.contains("does not exist"));
        let junk = dir.path().join("junk.png");
        std::fs::write(&junk, b"this is not an image").unwrap();
        let e = load_image(&junk, false).unwrap_err();
        assert!(e.contains("junk.png"), "{e}");
        let corrupt = dir.path().join("cut.png");
        let mut png = Vec::new();
        image::RgbImage::new(4, 4)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        std::fs::write(&corrupt, &png[..png.len() / 2]).unwrap();
        let e = load_image(&corrupt, false).unwrap_err();
        assert!(e.contains("cut.png") && e.contains("decode"), "{e}");
    }
}
