//! HSV read-out, for comparing with the hue/saturation figures quoted in \[GRC13\]
//! (e.g. "hue 292°, saturation 5 %", §2.1 item 8, §6.9).
//!
//! \[GRC13\] does not say where it measured; an image editor reading the 8-bit
//! display image is by far the most likely, so the default read-out
//! ([`hsv_of_linear`]) encodes linear RGB with the sRGB curve first. Applying
//! [`hsv`] directly to linear values is the "linear variant" of §6.9.

use glam::DVec3;

use crate::spaces::srgb_encode;

/// Hue in degrees [0, 360), saturation and value in [0, 1] for inputs in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hsv {
    pub h: f64,
    pub s: f64,
    pub v: f64,
}

/// HSV of an RGB triple, taken as given (normally sRGB-encoded values in [0, 1]).
pub fn hsv(rgb: DVec3) -> Hsv {
    let (r, g, b) = (rgb.x, rgb.y, rgb.z);
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let delta = max - min;
    let s = if max > 0.0 { delta / max } else { 0.0 };
    let h = if delta <= 0.0 {
        0.0
    } else if max == r {
        60.0 * ((g - b) / delta).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / delta + 2.0)
    } else {
        60.0 * ((r - g) / delta + 4.0)
    };
    Hsv { h, s, v: max }
}

/// HSV as an image editor would read it off the display image: clamp linear
/// RGB to [0, 1], apply the sRGB transfer curve, then [`hsv`].
pub fn hsv_of_linear(rgb_linear: DVec3) -> Hsv {
    let enc = |c: f64| srgb_encode(c.clamp(0.0, 1.0));
    hsv(DVec3::new(
        enc(rgb_linear.x),
        enc(rgb_linear.y),
        enc(rgb_linear.z),
    ))
}

/// HSV of an 8-bit triple (values / 255), the form the paper's numbers take.
pub fn hsv_of_8bit(rgb: [u8; 3]) -> Hsv {
    hsv(DVec3::new(rgb[0] as f64, rgb[1] as f64, rgb[2] as f64) / 255.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_has_zero_hue_and_saturation() {
        let g = hsv(DVec3::splat(0.4));
        assert_eq!((g.h, g.s, g.v), (0.0, 0.0, 0.4));
        assert_eq!(hsv(DVec3::ZERO).s, 0.0);
    }

    #[test]
    fn linear_readout_clamps_before_encoding() {
        // An over-range neutral stays neutral and reads V = 1.
        let x = hsv_of_linear(DVec3::new(3.0, 3.0, 3.0));
        assert_eq!(x.s, 0.0);
        assert!((x.v - 1.0).abs() < 1e-15);
        // Negative components are clamped to 0, giving full saturation.
        let y = hsv_of_linear(DVec3::new(0.5, -0.1, 0.5));
        assert_eq!(y.s, 1.0);
        assert!((y.h - 300.0).abs() < 1e-9);
    }
}
