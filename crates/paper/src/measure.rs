//! Read-outs on rendered frames: which pixels belong to a surface region, their mean colour,
//! and the HSV read-out of the paper.
//!
//! A pixel belongs to a [`Region`] when every sample of it hit a surface and none saw an
//! emitter, its albedo AOV equals the region material's reflectance (within 3 %, which drops
//! pixels that straddle an edge), its first-hit point (camera position + depth AOV × the ray
//! through the pixel centre) lies inside the region's box, and — when asked — its shading
//! normal faces away from a given point (a light: the pixel is not lit by it directly).
//!
//! Because the CAT is linear, the mean of an adapted region is the CAT matrix times the mean of
//! the raw region: region means are taken once, on the raw frame, in f64.
use eyeadapt_color::{Hsv, hsv_of_linear, luminance};
use eyeadapt_scene::{Bsdf, Scene};
use eyeadapt_tracer::{Frame, View};
use glam::{DVec3, Vec3, Vec3A};

/// A set of pixels defined in world space.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub name: String,
    /// Material whose reflectance the pixels' albedo must show.
    pub material: String,
    /// World-space box the first-hit points must lie in.
    pub min: Vec3,
    pub max: Vec3,
    /// Keep only pixels whose normal faces away from this point.
    pub facing_away_from: Option<Vec3>,
}

impl Region {
    pub fn new(name: &str, material: &str, min: [f32; 3], max: [f32; 3]) -> Region {
        Region {
            name: name.into(),
            material: material.into(),
            min: Vec3::from(min),
            max: Vec3::from(max),
            facing_away_from: None,
        }
    }

    /// The bounding box of every mesh made of `material`, shrunk by `shrink` (a fraction of
    /// the extent, on each side) along axes where the box has extent and padded by 1 cm along
    /// flat axes (a quad's normal).
    pub fn from_material(scene: &Scene, name: &str, material: &str, shrink: f32) -> Region {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for inst in scene.instances.iter().filter(|i| {
            i.material
                .is_some_and(|id| scene.materials[id.0 as usize].name == material)
        }) {
            for p in &scene.mesh(inst.mesh).positions {
                let p = inst.to_world.point(*p);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        let ext = hi - lo;
        for a in 0..3 {
            if ext[a] > 1e-3 {
                lo[a] += shrink * ext[a];
                hi[a] -= shrink * ext[a];
            } else {
                lo[a] -= 0.01;
                hi[a] += 0.01;
            }
        }
        Region::new(name, material, lo.to_array(), hi.to_array())
    }

    pub fn facing_away_from(mut self, p: Vec3) -> Region {
        self.facing_away_from = Some(p);
        self
    }
}

/// The diffuse reflectance of a named material (None if unknown or not diffuse).
pub fn reflectance(scene: &Scene, material: &str) -> Option<DVec3> {
    scene
        .materials
        .iter()
        .find(|m| m.name == material)
        .and_then(|m| match m.bsdf {
            Bsdf::Diffuse { reflectance } => reflectance.constant().map(|r| r.as_dvec3()),
            _ => None,
        })
}

/// Mean raw linear colour of a region and how many pixels it has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionMean {
    pub rgb: DVec3,
    /// Mean first-hit irradiance AOV (linear sRGB): the light the surface receives.
    pub irradiance: DVec3,
    pub pixels: usize,
    /// The region material's reflectance.
    pub reflectance: DVec3,
}

/// Indices of the region's pixels in `frame` seen from `view`.
pub fn region_pixels(scene: &Scene, frame: &Frame, view: &View, r: &Region) -> Vec<usize> {
    let Some(rho) = reflectance(scene, &r.material) else {
        return Vec::new();
    };
    let rho = rho.as_vec3();
    let basis = view.basis();
    let origin = Vec3A::from(view.position);
    let (lo, hi) = (Vec3A::from(r.min), Vec3A::from(r.max));
    let mut out = Vec::new();
    for y in 0..frame.height {
        for x in 0..frame.width {
            let i = y * frame.width + x;
            if frame.hit[i] < 1.0 || frame.emitter[i] > 0.0 {
                continue;
            }
            let a = Vec3::from(frame.albedo[i]);
            if ((a - rho).abs() - 0.03 * rho.max(Vec3::splat(0.01))).max_element() > 0.0 {
                continue;
            }
            let d = view.ray_dir(basis, x as f32 + 0.5, y as f32 + 0.5);
            let p = origin + d * frame.depth[i];
            if p.cmplt(lo).any() || p.cmpgt(hi).any() {
                continue;
            }
            if let Some(l) = r.facing_away_from {
                let n = Vec3A::from(frame.normal[i]);
                if n.dot(Vec3A::from(l) - p) >= 0.0 {
                    continue;
                }
            }
            out.push(i);
        }
    }
    out
}

/// Pixels whose first-hit point (from the depth AOV) lies in the box, whatever their material.
pub fn pixels_in_box(frame: &Frame, view: &View, min: Vec3, max: Vec3) -> Vec<usize> {
    let basis = view.basis();
    let origin = Vec3A::from(view.position);
    let (lo, hi) = (Vec3A::from(min), Vec3A::from(max));
    (0..frame.width * frame.height)
        .filter(|&i| {
            if frame.hit[i] <= 0.0 {
                return false;
            }
            let (x, y) = (i % frame.width, i / frame.width);
            let d = view.ray_dir(basis, x as f32 + 0.5, y as f32 + 0.5);
            let p = origin + d * frame.depth[i];
            !(p.cmplt(lo).any() || p.cmpgt(hi).any())
        })
        .collect()
}

/// Mean raw colour over a region (NaN with 0 pixels).
pub fn region_mean(scene: &Scene, frame: &Frame, view: &View, r: &Region) -> RegionMean {
    let px = region_pixels(scene, frame, view, r);
    let mean = |v: &[[f32; 3]]| {
        px.iter()
            .map(|&i| Vec3::from(v[i]).as_dvec3())
            .sum::<DVec3>()
            / px.len() as f64
    };
    RegionMean {
        rgb: mean(&frame.rgb),
        irradiance: mean(&frame.irradiance),
        pixels: px.len(),
        reflectance: reflectance(scene, &r.material).unwrap_or(DVec3::NAN),
    }
}

/// The paper's HSV read-out of a linear colour, at equal luminance with the reference
/// reflectance: the colour is scaled so that its luminance equals `Y(reference)` (what a
/// white-balanced display of a correctly exposed surface of that reflectance shows), then
/// clamped, sRGB-encoded and converted to HSV (estimators.md §6.9). Hue and saturation are
/// nearly independent of the scale; fixing it keeps the clamp and the sRGB toe from deciding.
pub fn equal_luminance_hsv(linear: DVec3, reference: DVec3) -> Hsv {
    let y = luminance(linear);
    let k = if y > 0.0 {
        luminance(reference) / y
    } else {
        0.0
    };
    hsv_of_linear(linear * k)
}

/// Signed smallest difference of two hues in degrees, in (−180, 180].
pub fn hue_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 { d - 360.0 } else { d }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hue_difference_wraps() {
        assert_eq!(hue_diff(10.0, 350.0), 20.0);
        assert_eq!(hue_diff(350.0, 10.0), -20.0);
        assert_eq!(hue_diff(180.0, 0.0), 180.0);
    }

    #[test]
    fn equal_luminance_readout_ignores_scale() {
        let rho = DVec3::new(0.75, 0.31, 0.074);
        let a = equal_luminance_hsv(rho * 7.0, rho);
        let b = hsv_of_linear(rho);
        assert!((a.h - b.h).abs() < 1e-9 && (a.s - b.s).abs() < 1e-9);
    }

    #[test]
    fn regions_select_by_material_box_and_facing() {
        let scene = eyeadapt_scene::load_builtin("cornell-green-floor").unwrap();
        let view = View::from_camera(scene.camera.as_ref().unwrap());
        let view = View {
            width: 48,
            height: 48,
            ..view
        };
        let data = eyeadapt_tracer::SceneData::new(&scene);
        let s = eyeadapt_tracer::RenderSettings {
            spp: 2,
            path: eyeadapt_tracer::PathSettings {
                max_depth: 2,
                rr_depth: 5,
            },
            seed: 0,
            frame: 0,
            filter: eyeadapt_scene::PixelFilter::Box,
            wcam_specular: Default::default(),
            guiding: Default::default(),
        };
        let f = eyeadapt_tracer::render(&data, &view, &s);
        let patch = Region::from_material(&scene, "white patch", "cc19", 0.2);
        assert!(!region_pixels(&scene, &f, &view, &patch).is_empty());
        // The same box with another material's albedo selects nothing.
        let wrong = Region {
            material: "cc01".into(),
            ..patch.clone()
        };
        assert!(region_pixels(&scene, &f, &view, &wrong).is_empty());
        // Back-wall pixels face the camera, so "facing away from the camera" drops them all.
        let wall = Region::new("wall", "white", [0.1, 0.3, 0.54], [0.45, 0.5, 0.57]);
        assert!(!region_pixels(&scene, &f, &view, &wall).is_empty());
        let away = wall.facing_away_from(view.position);
        assert!(region_pixels(&scene, &f, &view, &away).is_empty());
    }
}
