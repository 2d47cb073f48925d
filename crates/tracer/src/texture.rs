//! Texture lookups at a surface interaction: bitmaps (nearest or bilinear, with Mitsuba's wrap
//! modes), checkerboards, interpolated vertex colours, face colours and constants.
use crate::emitter::luminance;
use crate::interaction::SurfaceInteraction;
use eyeadapt_scene::{FilterType, Image, Param, Rgb, Texture, WrapMode};
use glam::{Vec2, Vec3A};

/// A texture read as a number: its luminance, as Mitsuba's `eval_1`, which for a
/// `checkerboard` also swaps the two colours (Mitsuba 3.9.1's `eval_1` tests the opposite
/// parity to its `eval`; a roughness or weight checkerboard therefore lies where Mitsuba's
/// does only with the swap).
pub fn eval_1(tex: &Texture, si: &SurfaceInteraction) -> f32 {
    let c = match tex {
        Texture::Checkerboard {
            color0,
            color1,
            to_uv,
        } => eval(
            &Texture::Checkerboard {
                color0: *color1,
                color1: *color0,
                to_uv: *to_uv,
            },
            si,
        ),
        _ => eval(tex, si),
    };
    luminance(c)
}

/// The texture's colour at `si`.
#[inline]
pub fn eval(tex: &Texture, si: &SurfaceInteraction) -> Vec3A {
    match tex {
        Texture::Bitmap(b) => lookup(&b.image, b.to_uv.transform_point2(si.uv), b.filter, b.wrap),
        Texture::Checkerboard {
            color0,
            color1,
            to_uv,
        } => {
            let uv = to_uv.transform_point2(si.uv);
            let upper = |x: f32| x - x.floor() > 0.5;
            if upper(uv.x) == upper(uv.y) {
                (*color0).into()
            } else {
                (*color1).into()
            }
        }
        Texture::MeshAttribute { name } if name == "face_color" => si.face_color,
        Texture::MeshAttribute { .. } => si.color,
        Texture::Constant { value } => (*value).into(),
    }
}

/// The texture's value at `uv` alone (no mesh attributes: those read zero), for what is not
/// a surface: a beam's image, a point sampled on an emitter.
#[inline]
pub fn eval_uv(tex: &Texture, uv: Vec2) -> Vec3A {
    let si = SurfaceInteraction {
        uv,
        ..Default::default()
    };
    eval(tex, &si)
}

/// The texture's mean over its domain: what the choice of light weights a textured
/// emitter by (any positive weight keeps it unbiased). A mesh attribute counts as 1.
pub fn mean(tex: &Texture) -> Vec3A {
    match tex {
        Texture::Bitmap(b) => {
            let n = b.image.texels.len().max(1) as f64;
            let s = b
                .image
                .texels
                .iter()
                .fold(glam::DVec3::ZERO, |a, t| a + t.as_dvec3());
            Vec3A::from((s / n).as_vec3())
        }
        Texture::Checkerboard { color0, color1, .. } => Vec3A::from((*color0 + *color1) * 0.5),
        Texture::MeshAttribute { .. } => Vec3A::ONE,
        Texture::Constant { value } => (*value).into(),
    }
}

/// The mean over the surface of a colour parameter, over its channels too (Mitsuba's
/// `Texture::mean`: a bitmap's mean texel, a checkerboard's two colours alike; vertex
/// colours, unknown before the hit, count as 0.5).
pub fn param_mean(p: Param<Rgb>, textures: &[Texture]) -> f32 {
    let avg = |c: Rgb| (c.x + c.y + c.z) / 3.0;
    match p {
        Param::Const(c) => avg(c),
        Param::Texture(t) => match &textures[t.0 as usize] {
            Texture::Bitmap(b) => {
                let n = b.image.texels.len().max(1) as f64;
                (b.image.texels.iter().map(|&c| avg(c) as f64).sum::<f64>() / n) as f32
            }
            Texture::Checkerboard { color0, color1, .. } => 0.5 * (avg(*color0) + avg(*color1)),
            Texture::MeshAttribute { .. } => 0.5,
            Texture::Constant { value } => avg(*value),
        },
    }
}

/// Texel index `i` of a row or column of `n` texels under `wrap`.
#[inline]
fn wrap_index(i: i64, n: u32, wrap: WrapMode) -> usize {
    let n = n as i64;
    (match wrap {
        WrapMode::Clamp => i.clamp(0, n - 1),
        WrapMode::Repeat => i.rem_euclid(n),
        WrapMode::Mirror => {
            let k = i.rem_euclid(2 * n);
            if k < n { k } else { 2 * n - 1 - k }
        }
    }) as usize
}

/// [`wrap_index`] of `i` and of `i + 1`: for `Repeat` the second follows from the first
/// without another division (two of the four a bilinear lookup made were most of its cost).
#[inline]
fn wrap_pair(i: i64, n: u32, wrap: WrapMode) -> (usize, usize) {
    match wrap {
        WrapMode::Repeat => {
            let a = wrap_index(i, n, wrap);
            (a, if a + 1 == n as usize { 0 } else { a + 1 })
        }
        _ => (wrap_index(i, n, wrap), wrap_index(i + 1, n, wrap)),
    }
}

/// The four texels around (x0, y0) of a bilinear lookup: (x0, y0), (x0 + 1, y0), (x0, y0 + 1),
/// (x0 + 1, y0 + 1), each wrapped.
#[inline]
fn corners(img: &Image, x0: i64, y0: i64, wrap: WrapMode) -> [Vec3A; 4] {
    let (ix0, ix1) = wrap_pair(x0, img.width, wrap);
    let (iy0, iy1) = wrap_pair(y0, img.height, wrap);
    let w = img.width as usize;
    let at = |ix: usize, iy: usize| -> Vec3A { img.texels[iy * w + ix].into() };
    [at(ix0, iy0), at(ix1, iy0), at(ix0, iy1), at(ix1, iy1)]
}

/// The image at `uv` ((0, 0) = top-left corner, (1, 1) = bottom-right). Bilinear filtering
/// interpolates between texel centres (at (i + ½)/width), as Mitsuba does.
pub fn lookup(img: &Image, uv: Vec2, filter: FilterType, wrap: WrapMode) -> Vec3A {
    if img.texels.is_empty() || !uv.is_finite() {
        return Vec3A::ZERO;
    }
    let (w, h) = (img.width, img.height);
    let at = |x: i64, y: i64| -> Vec3A {
        img.texels[wrap_index(y, h, wrap) * w as usize + wrap_index(x, w, wrap)].into()
    };
    let (x, y) = (uv.x as f64 * w as f64, uv.y as f64 * h as f64);
    match filter {
        FilterType::Nearest => at(x.floor() as i64, y.floor() as i64),
        FilterType::Bilinear => {
            let (x, y) = (x - 0.5, y - 0.5);
            let (x0, y0) = (x.floor(), y.floor());
            let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
            let [f00, f10, f01, f11] = corners(img, x0 as i64, y0 as i64, wrap);
            let top = f00 * (1.0 - fx) + f10 * fx;
            let bottom = f01 * (1.0 - fx) + f11 * fx;
            top * (1.0 - fy) + bottom * fy
        }
    }
}

/// The derivatives of [`lookup`] along u and along v (before any `to_uv`): those of the
/// bilinear interpolation between the four texels around `uv`, zero for nearest lookups (as
/// Mitsuba's `eval_1_grad`).
pub fn lookup_grad(img: &Image, uv: Vec2, filter: FilterType, wrap: WrapMode) -> [Vec3A; 2] {
    if img.texels.is_empty() || !uv.is_finite() || filter == FilterType::Nearest {
        return [Vec3A::ZERO; 2];
    }
    let (w, h) = (img.width, img.height);
    let (x, y) = (uv.x as f64 * w as f64 - 0.5, uv.y as f64 * h as f64 - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
    let [f00, f10, f01, f11] = corners(img, x0 as i64, y0 as i64, wrap);
    let dx = (f10 - f00) * (1.0 - fy) + (f11 - f01) * fy;
    let dy = (f01 - f00) * (1.0 - fx) + (f11 - f10) * fx;
    [dx * w as f32, dy * h as f32]
}

#[cfg(test)]
mod tests {
    use super::*;
    use eyeadapt_scene::Rgb;

    /// The shortcut for `Repeat` (and the plain pair for the others) is the two wraps it
    /// replaces, from far negative to far positive indices, including the last texel.
    #[test]
    fn wrap_pair_is_two_wraps() {
        for wrap in [WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror] {
            for n in [1u32, 2, 3, 7, 64] {
                for i in -300i64..300 {
                    let want = (wrap_index(i, n, wrap), wrap_index(i + 1, n, wrap));
                    assert_eq!(wrap_pair(i, n, wrap), want, "{wrap:?} n {n} i {i}");
                }
            }
        }
    }

    /// 2×2: red, green / blue, white (top row first).
    fn image() -> Image {
        Image {
            width: 2,
            height: 2,
            texels: vec![
                Rgb::new(1.0, 0.0, 0.0),
                Rgb::new(0.0, 1.0, 0.0),
                Rgb::new(0.0, 0.0, 1.0),
                Rgb::new(1.0, 1.0, 1.0),
            ],
        }
    }

    fn close(a: Vec3A, b: [f32; 3]) -> bool {
        (a - Vec3A::from(b)).abs().max_element() < 1e-6
    }

    #[test]
    fn nearest_reads_the_texel_under_the_uv() {
        let img = image();
        let n = |u, v| lookup(&img, Vec2::new(u, v), FilterType::Nearest, WrapMode::Repeat);
        assert!(close(n(0.25, 0.25), [1.0, 0.0, 0.0]), "top left");
        assert!(close(n(0.75, 0.25), [0.0, 1.0, 0.0]), "top right");
        assert!(close(n(0.25, 0.75), [0.0, 0.0, 1.0]), "bottom left");
        assert!(
            close(n(1.25, -0.25), [0.0, 0.0, 1.0]),
            "repeat wraps both axes"
        );
    }

    #[test]
    fn bilinear_interpolates_between_texel_centres() {
        let img = image();
        let b = |u, v, w| lookup(&img, Vec2::new(u, v), FilterType::Bilinear, w);
        // Texel centres read the texel exactly.
        assert!(close(b(0.25, 0.25, WrapMode::Clamp), [1.0, 0.0, 0.0]));
        // The image centre is the mean of the four texels.
        assert!(close(b(0.5, 0.5, WrapMode::Clamp), [0.5, 0.5, 0.5]));
        // Halfway from the top-left centre to the top-right one, a quarter of the way down:
        // rows (red+green)/2 and (blue+white)/2, weighted 3/4 and 1/4 → (0.5, 0.5, 0) · ¾ +
        // (0.5, 0.5, 1) · ¼.
        assert!(close(b(0.5, 0.375, WrapMode::Clamp), [0.5, 0.5, 0.25]));
        // At the left edge, clamp holds the border texels; repeat blends in the far column.
        assert!(close(b(0.0, 0.25, WrapMode::Clamp), [1.0, 0.0, 0.0]));
        assert!(close(b(0.0, 0.25, WrapMode::Repeat), [0.5, 0.5, 0.0]));
        // Mirror reflects at the border: the texel left of column 0 is column 0 itself.
        assert!(close(b(0.0, 0.25, WrapMode::Mirror), [1.0, 0.0, 0.0]));
    }

    #[test]
    fn bilinear_gradient_matches_finite_differences() {
        let img = image();
        let (f, w) = (FilterType::Bilinear, WrapMode::Repeat);
        for uv in [
            Vec2::new(0.4, 0.6),
            Vec2::new(0.1, 0.3),
            Vec2::new(0.9, 0.95),
        ] {
            let [du, dv] = lookup_grad(&img, uv, f, w);
            let h = 1e-3;
            let fd =
                |d: Vec2| (lookup(&img, uv + d, f, w) - lookup(&img, uv - d, f, w)) / (2.0 * h);
            assert!(
                (du - fd(Vec2::new(h, 0.0))).abs().max_element() < 1e-2,
                "{uv}: {du}"
            );
            assert!(
                (dv - fd(Vec2::new(0.0, h))).abs().max_element() < 1e-2,
                "{uv}: {dv}"
            );
        }
        assert_eq!(
            lookup_grad(&img, Vec2::splat(0.3), FilterType::Nearest, w),
            [Vec3A::ZERO; 2]
        );
    }

    #[test]
    fn wrap_modes_fold_indices_as_mitsuba_does() {
        let r: Vec<usize> = (-3..6)
            .map(|i| wrap_index(i, 3, WrapMode::Repeat))
            .collect();
        assert_eq!(r, [0, 1, 2, 0, 1, 2, 0, 1, 2]);
        let m: Vec<usize> = (-3..6)
            .map(|i| wrap_index(i, 3, WrapMode::Mirror))
            .collect();
        assert_eq!(m, [2, 1, 0, 0, 1, 2, 2, 1, 0]);
        let c: Vec<usize> = (-3..6).map(|i| wrap_index(i, 3, WrapMode::Clamp)).collect();
        assert_eq!(c, [0, 0, 0, 0, 1, 2, 2, 2, 2]);
    }

    #[test]
    fn checkerboard_alternates_by_quadrant() {
        let tex = Texture::Checkerboard {
            color0: Rgb::splat(0.4),
            color1: Rgb::splat(0.2),
            to_uv: glam::Affine2::from_scale(Vec2::splat(2.0)),
        };
        let mut si = SurfaceInteraction::default();
        let mut at = |u, v| {
            si.uv = Vec2::new(u, v);
            eval(&tex, &si).x
        };
        // to_uv doubles the UV, so each quadrant of [0, 1]² holds a full 2×2 board.
        assert_eq!(at(0.1, 0.1), 0.4);
        assert_eq!(at(0.3, 0.1), 0.2);
        assert_eq!(at(0.3, 0.3), 0.4);
        assert_eq!(at(0.6, 0.1), 0.4);
    }

    /// Mitsuba 3.9.1 reads a checkerboard as a number with its colours the other way round
    /// (its `eval_1` at uv (0.2, 0.2) gives color1, its `eval` color0).
    #[test]
    fn checkerboard_as_a_number_swaps_colours_as_mitsuba() {
        let tex = Texture::Checkerboard {
            color0: Rgb::splat(0.1),
            color1: Rgb::splat(0.9),
            to_uv: glam::Affine2::IDENTITY,
        };
        let mut si = SurfaceInteraction::default();
        for (uv, colour, number) in [((0.2, 0.2), 0.1, 0.9), ((0.7, 0.2), 0.9, 0.1)] {
            si.uv = Vec2::new(uv.0, uv.1);
            assert!((eval(&tex, &si).x - colour).abs() < 1e-6);
            assert!((eval_1(&tex, &si) - number).abs() < 1e-5);
        }
    }
}
