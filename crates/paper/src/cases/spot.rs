//! Case 4's spot from the scene's geometry: where its light lands first, and which statue
//! pixels it reaches ("the spotlight only lights the only white object", "the white statue is
//! partially lit", \[GRC13\] §4.1, §5.2).
use eyeadapt_scene::{Light, Scene};
use eyeadapt_tracer::{Frame, RayScratch, SceneData, View};
use glam::{Vec3, Vec3A};

/// The scene's (first) spot light.
#[derive(Clone, Copy, Debug)]
pub(super) struct Spot {
    pub position: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    pub intensity: Vec3,
    pub cone_deg: f32,
    pub falloff_deg: f32,
}

impl Spot {
    pub fn of(scene: &Scene) -> Option<Spot> {
        scene.lights.iter().find_map(|l| match *l {
            Light::Spot {
                position,
                direction,
                intensity,
                cone_deg,
                falloff_deg,
            } => Some(Spot {
                position,
                axis: direction.normalize(),
                intensity,
                cone_deg,
                falloff_deg,
            }),
            _ => None,
        })
    }

    /// The spot's relative intensity at angle `theta` (radians) from its axis, as the renderer
    /// applies it: 1 inside the core, a linear ramp to 0 at the cone.
    fn profile(&self, theta: f32) -> f32 {
        let cone = self.cone_deg.to_radians();
        let fall = self.falloff_deg.to_radians().min(cone);
        if theta <= fall {
            1.0
        } else if theta < cone {
            (cone - theta) / (cone - fall).max(1e-6)
        } else {
            0.0
        }
    }

    /// An orthonormal pair across the axis.
    fn across(&self) -> (Vec3, Vec3) {
        let a = self.axis.any_orthonormal_vector();
        (a, self.axis.cross(a))
    }
}

/// The share of the spot's emitted power whose rays hit material `material` first: a 128 ×
/// 128 grid of directions over the cone (cell midpoints, uniform in cos θ and φ, so each
/// carries the same solid angle), each weighted by the spot's profile. No noise: geometry.
pub(super) fn power_share(data: &SceneData, spot: &Spot, material: u32) -> f64 {
    const N: usize = 128;
    let cos_cone = libm::cosf(spot.cone_deg.to_radians());
    let (a, b) = spot.across();
    let mut scratch = data.geometry.scratch();
    let (mut on, mut all) = (0.0f64, 0.0f64);
    for i in 0..N {
        let c = 1.0 - (1.0 - cos_cone) * (i as f32 + 0.5) / N as f32;
        let (s, theta) = (
            (1.0 - c * c).max(0.0).sqrt(),
            libm::acosf(c.clamp(-1.0, 1.0)),
        );
        let w = spot.profile(theta) as f64;
        for j in 0..N {
            let phi = std::f32::consts::TAU * (j as f32 + 0.5) / N as f32;
            let d = (spot.axis * c + (a * libm::cosf(phi) + b * libm::sinf(phi)) * s).normalize();
            let (o, d) = (Vec3A::from(spot.position), Vec3A::from(d));
            all += w;
            let hit = data
                .geometry
                .intersect_with(&mut scratch, o, d, f32::INFINITY);
            if hit.is_some_and(|h| {
                data.geometry
                    .interaction(o, d, &h, data.parameterisation)
                    .material
                    == material
            }) {
                on += w;
            }
        }
    }
    on / all
}

/// Of `pixels` (indices into `img`), those whose first-hit point (the depth AOV along the
/// pixel's centre ray) the spot lights directly ([`lights`]).
pub(super) fn lit(
    data: &SceneData,
    spot: &Spot,
    img: &Frame,
    view: &View,
    pixels: &[usize],
) -> Vec<usize> {
    let basis = view.basis();
    let mut scratch = data.geometry.scratch();
    pixels
        .iter()
        .copied()
        .filter(|&i| {
            let (x, y) = (i % img.width, i / img.width);
            let d = view.ray_dir(basis, x as f32 + 0.5, y as f32 + 0.5);
            let p = view.position + Vec3::from(d) * img.depth[i];
            lights(data, &mut scratch, spot, p)
        })
        .collect()
}

/// Does the spot light point `p` directly: inside its cone, and the first thing the spot's
/// ray towards it meets (within 1 cm)?
pub(super) fn lights(data: &SceneData, scratch: &mut RayScratch, spot: &Spot, p: Vec3) -> bool {
    let to = p - spot.position;
    let dist = to.length();
    let dir = to / dist;
    if dir.dot(spot.axis) < libm::cosf(spot.cone_deg.to_radians()) {
        return false;
    }
    let o = Vec3A::from(spot.position);
    data.geometry
        .intersect_with(scratch, o, Vec3A::from(dir), f32::INFINITY)
        .is_some_and(|h| h.t >= dist - 0.01)
}
