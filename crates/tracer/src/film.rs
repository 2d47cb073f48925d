//! Rendering one frame: camera rays, per-pixel accumulation in f64, and the AOV buffers.
//!
//! Each pixel is computed entirely by one task from its own deterministic sample streams and
//! written into its slot, so the frame is bit-identical for any thread count. Samples whose
//! radiance is NaN or infinite are counted and dropped (the pixel averages the rest).
//!
//! With a tent or Gaussian reconstruction filter ([`PixelFilter`]) the beauty image is the
//! filter-weighted mean of the samples around each pixel, as in Mitsuba's film. Each row's
//! samples are splatted into a private buffer covering the rows they reach; the buffers are
//! then added into the image one row after another, in row order, so the sums (and bits) do
//! not depend on the thread count. The AOVs stay per-pixel means.
use crate::guiding::{Guiding, SdTree, Tally, passes, split_threshold};
use crate::integrator::{AchromaticSpecular, PathSettings};
use crate::scene_data::SceneData;
use crate::trig::sincos_turns;
use eyeadapt_scene::{FilterWeights, PixelFilter, Projection};
use glam::{DVec3, Vec3, Vec3A};
use rayon::prelude::*;
use smallvec::SmallVec;
use std::time::Instant;

#[path = "film_pixel.rs"]
mod pixel;

/// Where the camera is and what it sees (a static camera or one pose of a camera path).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub position: Vec3,
    /// Unit gaze direction.
    pub forward: Vec3,
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_deg: f32,
    pub width: u32,
    pub height: u32,
    /// Pinhole, thin lens or orthographic (the eye sensor always sits at `position`).
    pub projection: Projection,
}

/// A [`View`]'s unit axes, right (`r`), up (`u`) and forward (`f`), orthonormal, and the
/// tangent of half its vertical field of view ([`View::basis`]). The view's ray and frustum
/// methods take it so as not to redo that per ray: give them their own view's basis.
#[derive(Clone, Copy, Debug)]
pub struct Basis {
    pub r: Vec3A,
    pub u: Vec3A,
    pub f: Vec3A,
    tan: f32,
}

impl Basis {
    /// (right, up, forward).
    pub fn axes(&self) -> (Vec3A, Vec3A, Vec3A) {
        (self.r, self.u, self.f)
    }
}

impl View {
    pub fn from_camera(c: &eyeadapt_scene::Camera) -> View {
        View {
            position: c.position,
            forward: c.forward(),
            up: c.up,
            fov_deg: c.fov_deg,
            width: c.width,
            height: c.height,
            projection: c.projection,
        }
    }

    /// The camera's axes, and what its rays share: made once per pixel (or frame), not per
    /// sample (the field of view's `tanf` was 1 % of a Cornell-box render).
    pub fn basis(&self) -> Basis {
        let f = Vec3A::from(self.forward).normalize();
        let r = f.cross(self.up.into()).normalize();
        Basis {
            r,
            u: r.cross(f),
            f,
            tan: libm::tanf(self.fov_deg.to_radians() * 0.5),
        }
    }

    /// Unit direction through image position (x, y) in pixels (y down, (0,0) top-left corner).
    #[inline]
    pub fn ray_dir(&self, basis: Basis, x: f32, y: f32) -> Vec3A {
        let Basis { r, u, f, .. } = basis;
        let (sx, sy) = self.screen(basis, x, y);
        (f + r * sx + u * sy).normalize()
    }

    /// The point of the plane one unit along the view that image position (x, y) looks at,
    /// as (right, up) offsets; a shifted projection moves it by its shift.
    #[inline]
    fn screen(&self, basis: Basis, x: f32, y: f32) -> (f32, f32) {
        let (dx, dy) = match self.projection {
            Projection::Shifted {
                shift_x, shift_y, ..
            } => (shift_x * self.width as f32, shift_y * self.height as f32),
            _ => (0.0, 0.0),
        };
        let tan = basis.tan;
        let aspect = self.width as f32 / self.height as f32;
        let sx = (2.0 * (x + dx) / self.width as f32 - 1.0) * tan * aspect;
        let sy = (1.0 - 2.0 * (y + dy) / self.height as f32) * tan;
        (sx, sy)
    }

    /// A thin lens of `aperture_radius` focused at `focus_distance`: the ray from a uniform
    /// point of the aperture disc (2-D sample `lens`) through where the pinhole ray `d`
    /// (through the plane one unit along the view) crosses the plane in focus.
    #[inline]
    fn lens_ray(
        &self,
        basis: Basis,
        d: Vec3A,
        aperture_radius: f32,
        focus_distance: f32,
        lens: [f32; 2],
    ) -> (Vec3A, Vec3A) {
        let Basis { r, u, .. } = basis;
        let origin = Vec3A::from(self.position);
        let focus = origin + d * focus_distance;
        let rad = aperture_radius * lens[0].sqrt();
        let (s, c) = sincos_turns(lens[1]);
        let o = origin + r * (rad * c) + u * (rad * s);
        (o, (focus - o).normalize())
    }

    /// The camera ray through image position (x, y) (as [`View::ray_dir`]): origin and unit
    /// direction; `lens` is a 2-D sample of the thin lens's aperture (unused otherwise).
    #[inline]
    pub fn ray(&self, basis: Basis, x: f32, y: f32, lens: [f32; 2]) -> (Vec3A, Vec3A) {
        let Basis { r, u, f, .. } = basis;
        let origin = Vec3A::from(self.position);
        match self.projection {
            Projection::Pinhole => (origin, self.ray_dir(basis, x, y)),
            Projection::ThinLens {
                aperture_radius,
                focus_distance,
            } => {
                let (sx, sy) = self.screen(basis, x, y);
                self.lens_ray(
                    basis,
                    f + r * sx + u * sy,
                    aperture_radius,
                    focus_distance,
                    lens,
                )
            }
            Projection::Shifted {
                aperture_radius,
                focus_distance,
                ..
            } => {
                let (sx, sy) = self.screen(basis, x, y);
                let d = f + r * sx + u * sy;
                if aperture_radius > 0.0 {
                    self.lens_ray(basis, d, aperture_radius, focus_distance, lens)
                } else {
                    (origin, d.normalize())
                }
            }
            Projection::Orthographic {
                half_width,
                half_height,
            } => {
                let sx = (2.0 * x / self.width as f32 - 1.0) * half_width;
                let sy = (1.0 - 2.0 * y / self.height as f32) * half_height;
                (origin + r * sx + u * sy, f)
            }
        }
    }

    /// True when direction `d` (unit) lies inside the view frustum.
    pub fn in_frustum(&self, basis: Basis, d: Vec3A) -> bool {
        let Basis { r, u, f, .. } = basis;
        let z = d.dot(f);
        if z <= 0.0 {
            return false;
        }
        // The image's corners, in the plane one unit along the view.
        let (x0, y0) = self.screen(basis, 0.0, self.height as f32);
        let (x1, y1) = self.screen(basis, self.width as f32, 0.0);
        let (sx, sy) = (d.dot(r) / z, d.dot(u) / z);
        (x0..=x1).contains(&sx) && (y0..=y1).contains(&sy)
    }
}

/// Sampling settings of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    pub spp: u32,
    pub path: PathSettings,
    pub seed: u64,
    /// Frame number: part of every sample key, so frames get independent noise.
    pub frame: u32,
    /// How samples become pixels of the beauty image.
    pub filter: PixelFilter,
    /// How the WCAM re-render (the `achromatic` AOV) takes specular first bounces.
    pub wcam_specular: AchromaticSpecular,
    /// Path guiding, learned per frame from the frame's own samples (`guiding/`).
    pub guiding: Guiding,
}

/// Counters of one render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub samples: u64,
    /// Samples dropped because their radiance was NaN or infinite.
    pub invalid_samples: u64,
    pub seconds: f64,
}

/// A rendered frame: beauty plus AOVs, row-major, y down. Each AOV is the per-pixel mean.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[f32; 3]>,
    pub albedo: Vec<[f32; 3]>,
    pub achromatic: Vec<[f32; 3]>,
    pub irradiance: Vec<[f32; 3]>,
    pub normal: Vec<[f32; 3]>,
    /// Mean distance to the first hit over the samples that hit (0 where none did).
    pub depth: Vec<f32>,
    /// Fraction of samples whose camera ray hit an emitter directly.
    pub emitter: Vec<f32>,
    /// Fraction of samples whose camera ray hit any surface.
    pub hit: Vec<f32>,
    pub stats: RenderStats,
}

#[derive(Default, Clone, Copy)]
struct PixelAcc {
    l: DVec3,
    a: DVec3,
    e: DVec3,
    albedo: DVec3,
    normal: DVec3,
    depth: f64,
    hits: u32,
    emitters: u32,
    valid: u32,
    invalid: u32,
}

fn d3(v: Vec3A) -> DVec3 {
    Vec3::from(v).as_dvec3()
}

fn f3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// Renders one frame of `scene` from `view`.
pub fn render(scene: &SceneData, view: &View, settings: &RenderSettings) -> Frame {
    render_with_progress(scene, view, settings, &|| {})
}

/// [`render`], calling `row_done` (from any worker thread) each time a row of pixels is
/// finished, so that callers can show progress inside a frame. The pixels do not depend on it.
/// A guided frame (`settings.guiding`) renders in passes (`guiding/`); rows count in its last
/// pass, which holds about half the samples.
pub fn render_with_progress(
    scene: &SceneData,
    view: &View,
    settings: &RenderSettings,
    row_done: &(dyn Fn() + Sync),
) -> Frame {
    let start = Instant::now();
    let (w, h) = (view.width as usize, view.height as usize);
    let splats = settings.filter != PixelFilter::Box;
    let mut rows = vec![vec![PixelAcc::default(); w]; h];
    let mut beauty = vec![(DVec3::ZERO, 0.0); if splats { w * h } else { 0 }];
    let base = Pass {
        scene,
        view,
        settings,
        samples: 0..settings.spp,
        guide: None,
        row_done,
    };
    match settings.guiding {
        Guiding::Off => base.render(&mut rows, &mut beauty, None),
        Guiding::On => {
            let g = &scene.geometry;
            let mut tree = SdTree::new(g.bounds_min, g.bounds_max);
            let schedule = passes(settings.spp);
            let mut first = 0;
            for (k, &n) in schedule.iter().enumerate() {
                let samples = first..first + n;
                if k + 1 == schedule.len() {
                    let p = Pass {
                        samples,
                        guide: Some(&tree),
                        ..base
                    };
                    p.render(&mut rows, &mut beauty, None);
                } else {
                    let mut tally = Tally::new(&tree);
                    let p = Pass {
                        samples,
                        guide: Some(&tree),
                        row_done: &|| {},
                        ..base
                    };
                    p.render(&mut rows, &mut beauty, Some(&mut tally));
                    tree.learn(&tally, split_threshold(tally.total));
                }
                first += n;
            }
        }
    }
    let mut f = assemble(&rows, splats.then_some(beauty.as_slice()), (w, h));
    f.stats.seconds = start.elapsed().as_secs_f64();
    f
}

/// One pass over the frame: samples `samples` of every pixel, added to the pixels'
/// accumulators (and, with a splatting filter, the beauty sums), sampling from `guide`.
struct Pass<'a> {
    scene: &'a SceneData,
    view: &'a View,
    settings: &'a RenderSettings,
    samples: std::ops::Range<u32>,
    guide: Option<&'a SdTree>,
    row_done: &'a (dyn Fn() + Sync),
}

impl Pass<'_> {
    /// Renders the pass into `rows` and `beauty`; given a `tally`, the paths' training
    /// records are added to it, block after block of rows in row order.
    fn render(
        &self,
        rows: &mut [Vec<PixelAcc>],
        beauty: &mut [(DVec3, f64)],
        mut tally: Option<&mut Tally>,
    ) {
        let (w, h) = (self.view.width as usize, self.view.height as usize);
        let settings = self.settings;
        let reach = settings.filter.reach();
        let splats = settings.filter != PixelFilter::Box;
        // A row's splat buffer: rows y − reach ..= y + reach, each `w` (weighted sum, weight).
        let band = 2 * reach + 1;
        // The filter's table, made once a pass (a Gaussian's is 1 025 `exp`s).
        let weights = settings.filter.weights();
        let learn = tally.is_some();
        let render_row = |(y, row): (usize, &mut Vec<PixelAcc>)| {
            let mut splat = vec![(DVec3::ZERO, 0.0); if splats { band * w } else { 0 }];
            let mut records = Vec::new();
            for (x, acc) in row.iter_mut().enumerate() {
                let recs = learn.then_some(&mut records);
                self.pixel((x, y), acc, &mut splat, &weights, recs);
            }
            (self.row_done)();
            (splat, records)
        };
        // Rows in blocks, so that at most a block's splat buffers and records exist at once
        // (unguided with the box filter there are none: one block).
        let block_rows = if self.guide.is_some() {
            8
        } else if splats {
            32
        } else {
            h.max(1)
        };
        for (b, block) in rows.chunks_mut(block_rows).enumerate() {
            let start = b * block_rows;
            let done: Vec<_> = block
                .par_iter_mut()
                .enumerate()
                .map(|(i, row)| render_row((start + i, row)))
                .collect();
            for (i, (splat, records)) in done.into_iter().enumerate() {
                if splats {
                    add_splats(beauty, &splat, (w, h), start + i, reach);
                }
                if let Some(t) = tally.as_deref_mut() {
                    t.add(&records);
                }
            }
        }
    }
}

/// The frame from the rows' accumulators and, with a splatting filter, the beauty sums.
fn assemble(
    rows: &[Vec<PixelAcc>],
    beauty: Option<&[(DVec3, f64)]>,
    (w, h): (usize, usize),
) -> Frame {
    let mut f = Frame {
        width: w,
        height: h,
        ..Frame::default()
    };
    let n = w * h;
    for v in [
        &mut f.rgb,
        &mut f.albedo,
        &mut f.achromatic,
        &mut f.irradiance,
        &mut f.normal,
    ] {
        v.reserve_exact(n);
    }
    for (i, acc) in rows.iter().flatten().enumerate() {
        let k = if acc.valid > 0 {
            1.0 / acc.valid as f64
        } else {
            0.0
        };
        if let Some(beauty) = beauty {
            let (sum, weight) = beauty[i];
            f.rgb.push(f3(if weight > 0.0 {
                sum / weight
            } else {
                DVec3::ZERO
            }));
        } else {
            f.rgb.push(f3(acc.l * k));
        }
        f.achromatic.push(f3(acc.a * k));
        f.irradiance.push(f3(acc.e * k));
        f.albedo.push(f3(acc.albedo * k));
        f.normal.push(f3(acc.normal.normalize_or_zero()));
        f.depth.push(if acc.hits > 0 {
            (acc.depth / acc.hits as f64) as f32
        } else {
            0.0
        });
        f.emitter.push(acc.emitters as f32 * k as f32);
        f.hit.push(acc.hits as f32 * k as f32);
        f.stats.invalid_samples += acc.invalid as u64;
        f.stats.samples += (acc.valid + acc.invalid) as u64;
    }
    f
}

/// Adds one sample at `(x, dy)` (x in image pixels, dy in [0, 1) within its row) to the row's
/// splat buffer (`band` rows of `w`, the sample's own row in the middle).
fn splat_sample(
    splat: &mut [(DVec3, f64)],
    filter: &FilterWeights,
    (w, reach): (usize, usize),
    (x, dy): (f32, f32),
    l: DVec3,
) {
    let px = x.floor() as i64;
    let r = reach as i64;
    // The filter is separable: each column's weight once, not once per row (the filter's
    // `exp` was 4 % of a Gaussian-filtered render's cycles).
    let wxs: SmallVec<[f32; 16]> = (-r..=r)
        .map(|ox| filter.eval((px + ox) as f32 + 0.5 - x))
        .collect();
    for oy in -r..=r {
        // Pixel centre of row (own row + oy) minus the sample, in pixels.
        let wy = filter.eval(oy as f32 + 0.5 - dy);
        if wy <= 0.0 {
            continue;
        }
        let line = (oy + r) as usize * w;
        for (ox, wx) in (-r..=r).zip(&wxs) {
            let col = px + ox;
            if col < 0 || col >= w as i64 {
                continue;
            }
            let weight = (wx * wy) as f64;
            if weight > 0.0 {
                let cell = &mut splat[line + col as usize];
                cell.0 += l * weight;
                cell.1 += weight;
            }
        }
    }
}

/// Adds row `y`'s splat buffer into the image, dropping what falls outside it.
fn add_splats(
    image: &mut [(DVec3, f64)],
    splat: &[(DVec3, f64)],
    (w, h): (usize, usize),
    y: usize,
    reach: usize,
) {
    for (k, line) in splat.chunks_exact(w.max(1)).enumerate() {
        let Some(ty) = (y + k).checked_sub(reach).filter(|ty| *ty < h) else {
            continue;
        };
        for (dst, src) in image[ty * w..(ty + 1) * w].iter_mut().zip(line) {
            dst.0 += src.0;
            dst.1 += src.1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tent_splat_lands_on_the_neighbours_by_hand() {
        // Three pixels wide, reach 1; a sample at x = 1.25 in the middle of its row.
        let tent = PixelFilter::Tent { radius: 1.0 };
        let mut splat = vec![(DVec3::ZERO, 0.0); 3 * 3];
        splat_sample(
            &mut splat,
            &tent.weights(),
            (3, 1),
            (1.25, 0.5),
            DVec3::splat(2.0),
        );
        // Rows above and below: |offset| = 1, weight 0. Own row: 1 − 0.75, 1 − 0.25, 0.
        let weights: Vec<f64> = splat.iter().map(|c| c.1).collect();
        assert_eq!(weights, [0.0, 0.0, 0.0, 0.25, 0.75, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(splat[4].0, DVec3::splat(1.5));
        // Into a 3 × 2 image as row 0: the band's first row falls above the image.
        let mut image = vec![(DVec3::ZERO, 0.0); 3 * 2];
        splat[7] = (DVec3::ONE, 0.5);
        add_splats(&mut image, &splat, (3, 2), 0, 1);
        assert_eq!(image[1], (DVec3::splat(1.5), 0.75));
        assert_eq!(image[4], (DVec3::ONE, 0.5));
    }
}
