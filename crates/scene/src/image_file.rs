//! Decoding texture files (PNG, JPEG, OpenEXR, Radiance HDR, BMP, TGA) into linear texels.
//!
//! As Mitsuba's `bitmap` does: integer (8- or 16-bit) images are sRGB-encoded and are decoded
//! to linear unless `raw`; floating-point images (EXR, HDR) are linear already. Grey images
//! become grey RGB; alpha is dropped.
use crate::{Image, Rgb};
use std::path::Path;

/// The image at `path`, texels from its top row down.
pub fn load_image(path: &Path, raw: bool) -> Result<Image, String> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| format!("cannot read image {}: {e}", path.display()))?
        .with_guessed_format()
        .map_err(|e| format!("cannot read image {}: {e}", path.display()))?;
    use image::ImageFormat as F;
    let known = |f: F| matches!(f, F::Png | F::Jpeg | F::OpenExr | F::Hdr | F::Bmp | F::Tga);
    if !reader.format().is_some_and(known) {
        return Err(format!(
            "image {}: unknown image format (eyeadapt reads PNG, JPEG, EXR, HDR, BMP and TGA)",
            path.display()
        ));
    }
    let img = reader
        .decode()
        .map_err(|e| format!("image {}: cannot decode it: {e}", path.display()))?;
    let float = matches!(
        img,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    );
    let decode = !float && !raw;
    let rgb = img.to_rgb32f();
    let texels = rgb
        .pixels()
        .map(|p| {
            let c = Rgb::from_array(p.0);
            if decode { c.map(srgb_to_linear) } else { c }
        })
        .collect::<Vec<_>>();
    if texels.iter().any(|t| !t.is_finite()) {
        return Err(format!("image {}: has non-finite texels", path.display()));
    }
    Ok(Image {
        width: rgb.width(),
        height: rgb.height(),
        texels,
    })
}

/// The sRGB transfer function, inverted.
pub(crate) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_bit_files_are_srgb_decoded_unless_raw() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.png");
        // 2 × 1: mid grey 128 and white.
        image::RgbImage::from_raw(2, 1, vec![128, 128, 128, 255, 0, 0])
            .unwrap()
            .save(&p)
            .unwrap();
        let lin = load_image(&p, false).unwrap();
        assert_eq!((lin.width, lin.height), (2, 1));
        // sRGB 128/255 = 0.2158605 linear.
        assert!(
            (lin.texels[0].x - 0.215_860_5).abs() < 1e-5,
            "{}",
            lin.texels[0]
        );
        assert_eq!(lin.texels[1], Rgb::new(1.0, 0.0, 0.0));
        let raw = load_image(&p, true).unwrap();
        assert!((raw.texels[0].x - 128.0 / 255.0).abs() < 1e-6);
    }

    #[test]
    fn unknown_missing_and_corrupt_files_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.xyz");
        std::fs::write(&p, b"not an image at all").unwrap();
        let e = load_image(&p, false).unwrap_err();
        assert!(e.contains("unknown image format"), "{e}");
        let p = dir.path().join("t.png");
        std::fs::write(&p, b"\x89PNG\r\n\x1a\n broken").unwrap();
        let e = load_image(&p, false).unwrap_err();
        assert!(e.contains("cannot decode"), "{e}");
        let e = load_image(&dir.path().join("gone.png"), false).unwrap_err();
        assert!(e.contains("cannot read image"), "{e}");
    }
}
