//! Every light source, for next-event estimation: emissive triangles, point and spot lights
//! and the constant environment, chosen in proportion to their power.
use crate::accel::InputTri;
use eyeadapt_scene::Light;
use glam::Vec3A;
use std::f32::consts::PI;

#[inline]
pub fn luminance(c: Vec3A) -> f32 {
    0.212_639 * c.x + 0.715_168_7 * c.y + 0.072_192_32 * c.z
}

#[derive(Clone, Copy, Debug)]
pub struct AreaTri {
    pub v0: Vec3A,
    pub e1: Vec3A,
    pub e2: Vec3A,
    pub n: Vec3A,
    pub area: f32,
    pub emission: Vec3A,
}

#[derive(Clone, Copy, Debug)]
pub enum DeltaLight {
    Point {
        position: Vec3A,
        intensity: Vec3A,
    },
    Spot {
        position: Vec3A,
        direction: Vec3A,
        intensity: Vec3A,
        cos_cone: f32,
        cos_falloff: f32,
        cone: f32,
        inv_transition: f32,
    },
}

impl DeltaLight {
    pub fn position(&self) -> Vec3A {
        match *self {
            DeltaLight::Point { position, .. } | DeltaLight::Spot { position, .. } => position,
        }
    }

    /// Radiant intensity towards direction `w` (unit, leaving the light).
    pub fn intensity(&self, w: Vec3A) -> Vec3A {
        match *self {
            DeltaLight::Point { intensity, .. } => intensity,
            DeltaLight::Spot {
                direction,
                intensity,
                cos_cone,
                cos_falloff,
                cone,
                inv_transition,
                ..
            } => {
                let c = direction.dot(w);
                if c <= cos_cone {
                    Vec3A::ZERO
                } else if c >= cos_falloff {
                    intensity
                } else {
                    // Linear in angle between the beam width and the cutoff (Mitsuba's `spot`).
                    intensity * ((cone - c.clamp(-1.0, 1.0).acos()) * inv_transition)
                }
            }
        }
    }
}

/// A light sample as seen from a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3A,
    /// Distance to the light point (∞ for the environment).
    pub dist: f32,
    /// Radiance arriving along `wi` divided by nothing: for delta lights, intensity / d².
    pub li: Vec3A,
    /// Solid-angle density including the choice of light (1-weighted for delta lights).
    pub pdf: f32,
    pub delta: bool,
}

pub struct LightSet {
    pub area: Vec<AreaTri>,
    pub deltas: Vec<DeltaLight>,
    pub env: Option<Vec3A>,
    /// Cumulative selection weights over [area..., deltas..., env].
    cdf: Vec<f64>,
    total: f64,
}

impl LightSet {
    pub fn build(
        tris: &[InputTri],
        emission: &[Vec3A],
        lights: &[Light],
        env: Option<Vec3A>,
        scene_radius: f32,
    ) -> LightSet {
        let mut area = Vec::new();
        for t in tris.iter().filter(|t| t.light != u32::MAX) {
            let e1 = t.v[1] - t.v[0];
            let e2 = t.v[2] - t.v[0];
            let c = e1.cross(e2);
            area.push(AreaTri {
                v0: t.v[0],
                e1,
                e2,
                n: c.normalize(),
                area: 0.5 * c.length(),
                emission: emission[t.material as usize],
            });
        }
        let deltas: Vec<DeltaLight> = lights
            .iter()
            .map(|l| match *l {
                Light::Point {
                    position,
                    intensity,
                } => DeltaLight::Point {
                    position: position.into(),
                    intensity: intensity.into(),
                },
                Light::Spot {
                    position,
                    direction,
                    intensity,
                    cone_deg,
                    falloff_deg,
                } => {
                    let cone = cone_deg.to_radians();
                    let fall = falloff_deg.to_radians().min(cone);
                    DeltaLight::Spot {
                        position: position.into(),
                        direction: direction.normalize().into(),
                        intensity: intensity.into(),
                        cos_cone: cone.cos(),
                        cos_falloff: fall.cos(),
                        cone,
                        inv_transition: 1.0 / (cone - fall).max(1e-6),
                    }
                }
            })
            .collect();
        let env = env.filter(|e| e.max_element() > 0.0);
        let mut weights: Vec<f64> = area
            .iter()
            .map(|a| (PI * a.area * luminance(a.emission)) as f64)
            .collect();
        for d in &deltas {
            weights.push(match *d {
                DeltaLight::Point { intensity, .. } => 4.0 * PI * luminance(intensity),
                DeltaLight::Spot {
                    intensity,
                    cos_cone,
                    cos_falloff,
                    ..
                } => 2.0 * PI * (1.0 - 0.5 * (cos_cone + cos_falloff)) * luminance(intensity),
            } as f64);
        }
        if let Some(e) = env {
            let r = scene_radius.max(1e-3);
            weights.push((PI * luminance(e) * PI * r * r) as f64);
        }
        let mut cdf = Vec::with_capacity(weights.len());
        let mut total = 0.0;
        for w in weights {
            // A light whose luminance is zero but which still has colour (pure blue) must
            // remain reachable: give it a floor.
            total += w.max(1e-12);
            cdf.push(total);
        }
        LightSet {
            area,
            deltas,
            env,
            cdf,
            total,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }

    fn prob(&self, i: usize) -> f32 {
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        ((self.cdf[i] - lo) / self.total) as f32
    }

    /// Selection probability of area triangle `i`.
    pub fn area_prob(&self, i: u32) -> f32 {
        self.prob(i as usize)
    }

    /// Solid-angle density of hitting area light `i` at `y` (normal `n`) from `x`.
    pub fn pdf_area(&self, i: u32, x: Vec3A, y: Vec3A) -> f32 {
        let a = &self.area[i as usize];
        let d = y - x;
        let d2 = d.length_squared();
        let cos_l = a.n.dot(d).abs() / d2.sqrt();
        if cos_l <= 0.0 {
            return 0.0;
        }
        self.prob(i as usize) / a.area * d2 / cos_l
    }

    pub fn pdf_env(&self) -> f32 {
        if self.env.is_some() {
            self.prob(self.cdf.len() - 1) / (4.0 * PI)
        } else {
            0.0
        }
    }

    /// Samples a light for the point `x`.
    pub fn sample(&self, x: Vec3A, u_pick: f32, u: [f32; 2]) -> Option<LightSample> {
        if self.cdf.is_empty() {
            return None;
        }
        let target = u_pick as f64 * self.total;
        let i = self
            .cdf
            .partition_point(|&c| c <= target)
            .min(self.cdf.len() - 1);
        let p = self.prob(i);
        let n_area = self.area.len();
        if i < n_area {
            let a = &self.area[i];
            let su = u[0].sqrt();
            let y = a.v0 + a.e1 * (su * (1.0 - u[1])) + a.e2 * (su * u[1]);
            let d = y - x;
            let d2 = d.length_squared();
            let dist = d2.sqrt();
            if dist <= 0.0 {
                return None;
            }
            let wi = d / dist;
            let cos_l = -a.n.dot(wi);
            if cos_l <= 0.0 {
                return None; // back side of a one-sided emitter
            }
            Some(LightSample {
                wi,
                dist,
                li: a.emission,
                pdf: p / a.area * d2 / cos_l,
                delta: false,
            })
        } else if i < n_area + self.deltas.len() {
            let l = &self.deltas[i - n_area];
            let d = l.position() - x;
            let d2 = d.length_squared();
            let dist = d2.sqrt();
            if dist <= 0.0 {
                return None;
            }
            let wi = d / dist;
            Some(LightSample {
                wi,
                dist,
                li: l.intensity(-wi) / d2,
                pdf: p,
                delta: true,
            })
        } else {
            let env = self.env?;
            let z = 1.0 - 2.0 * u[0];
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * PI * u[1];
            Some(LightSample {
                wi: Vec3A::new(r * phi.cos(), r * phi.sin(), z),
                dist: f32::INFINITY,
                li: env,
                pdf: p / (4.0 * PI),
                delta: false,
            })
        }
    }

    /// Total luminous power of each light as the `dominant` estimator needs it:
    /// (emission colour, flux in Y units), area lights grouped by emission colour.
    pub fn fluxes(&self) -> Vec<(Vec3A, f64)> {
        let mut out: Vec<(Vec3A, f64)> = Vec::new();
        for a in &self.area {
            let f = (PI * a.area * luminance(a.emission)) as f64;
            match out.iter_mut().find(|(c, _)| *c == a.emission) {
                Some(e) => e.1 += f,
                None => out.push((a.emission, f)),
            }
        }
        for (k, d) in self.deltas.iter().enumerate() {
            let i = self.area.len() + k;
            let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
            let intensity = match *d {
                DeltaLight::Point { intensity, .. } | DeltaLight::Spot { intensity, .. } => {
                    intensity
                }
            };
            out.push((intensity, self.cdf[i] - lo));
        }
        if let Some(e) = self.env {
            let i = self.cdf.len() - 1;
            let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
            out.push((e, self.cdf[i] - lo));
        }
        out
    }
}
