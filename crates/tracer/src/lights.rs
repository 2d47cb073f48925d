//! Every light source, for next-event estimation: emissive triangles, point, spot and
//! directional lights ([`crate::emitter`]) and the environment ([`crate::envmap`], drawn
//! through the scene's [`crate::portal`]s where they serve the point);
//! [`crate::light_pick`] chooses which one a shading point samples.
use crate::beam::{self, Lookup};
use crate::emitter::{AreaTri, DeltaLight, Parallelogram, luminance};
use crate::envmap::{EnvSample, Environment};
use crate::light_pick::{LightPicker, Unit};
use crate::light_visibility::Visibility;
use crate::portal::{Portals, Through};
use eyeadapt_scene::{Light, Portal, Texture};
use glam::Vec3A;
use std::f32::consts::PI;

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
    /// For each area triangle, its parallelogram in `quads` (or `u32::MAX`).
    quad_of: Vec<u32>,
    quads: Vec<Parallelogram>,
    pub deltas: Vec<DeltaLight>,
    pub env: Option<Environment>,
    /// Openings the environment is sampled through (none: over the whole sphere).
    portals: Portals,
    /// Chooses among quads, lone triangles, deltas and the environment.
    picker: LightPicker,
    /// For each area triangle, its unit in `picker`.
    unit_of: Vec<u32>,
    /// The scene's textures (textured area lights and beams read them).
    pub textures: Vec<Texture>,
}

impl LightSet {
    /// The light set of the emissive triangles `area` (indexed as hits name them), the delta
    /// lights and the environment; `textures` are the scene's.
    pub fn build(
        area: Vec<AreaTri>,
        lights: &[Light],
        env: Option<Environment>,
        scene_radius: f32,
        textures: &[Texture],
    ) -> LightSet {
        let deltas: Vec<DeltaLight> = lights.iter().map(|l| delta_light(l, textures)).collect();
        let (quad_of, quads) = pair_parallelograms(&area);
        let mut set = LightSet::assemble(area, quad_of, quads, deltas, env, scene_radius);
        set.textures = textures.to_vec();
        set
    }

    fn assemble(
        area: Vec<AreaTri>,
        quad_of: Vec<u32>,
        quads: Vec<Parallelogram>,
        deltas: Vec<DeltaLight>,
        env: Option<Environment>,
        scene_radius: f32,
    ) -> LightSet {
        let env_mean = env.as_ref().map(Environment::mean);
        let picker = LightPicker::build(&area, &quad_of, &quads, &deltas, env_mean, scene_radius);
        let mut unit_of = vec![u32::MAX; area.len()];
        for (k, u) in picker.units.iter().enumerate() {
            if let Unit::Area { first, quad } = *u {
                unit_of[first as usize] = k as u32;
                if quad != u32::MAX {
                    unit_of[first as usize + 1] = k as u32;
                }
            }
        }
        LightSet {
            area,
            quad_of,
            quads,
            deltas,
            env,
            portals: Portals::default(),
            picker,
            unit_of,
            textures: Vec::new(),
        }
    }

    /// The set with the environment sampled through `portals` where they serve the point.
    pub fn with_portals(mut self, portals: &[Portal]) -> LightSet {
        self.portals = Portals::new(portals);
        self.picker = self.picker.through(self.portals.clone());
        self
    }

    /// The set with its light choice weighed by `visibility` (`light_visibility.rs`).
    pub(crate) fn set_visibility(&mut self, visibility: Option<Visibility>) {
        self.picker.see_through(visibility);
    }

    /// The light choice at `x` (normal `n`): a unit and its probability.
    #[cfg(test)]
    pub(crate) fn picker_pick(&self, x: Vec3A, n: Option<Vec3A>, u: f32) -> Option<(usize, f32)> {
        self.picker.pick(x, n, u)
    }

    /// The probability that the light choice at `x` (normal `n`) takes unit `k`.
    #[cfg(test)]
    pub(crate) fn picker_prob(&self, k: usize, x: Vec3A, n: Option<Vec3A>) -> f32 {
        self.picker.prob(k, x, n)
    }

    /// The light choice's visibility grid.
    #[cfg(test)]
    pub(crate) fn picker_visibility(&self) -> Option<&Visibility> {
        self.picker.visibility()
    }

    /// Whether the light choice takes a visibility grid.
    pub(crate) fn takes_visibility(&self) -> bool {
        self.picker.takes_visibility()
    }

    pub fn is_empty(&self) -> bool {
        self.picker.units.is_empty()
    }

    /// Whether the choice of light depends on the shading point (see [`crate::light_pick`]).
    pub fn spatial_choice(&self) -> bool {
        self.picker.is_spatial()
    }

    /// Area of area-light unit `first` (both halves of a parallelogram).
    #[inline]
    fn unit_area(&self, first: usize) -> f32 {
        if self.quad_of[first] == u32::MAX {
            self.area[first].area
        } else {
            self.area[first].area + self.area[first + 1].area
        }
    }

    /// Solid-angle density with which [`LightSet::sample`] at `x` (normal `n`, as given to
    /// `sample`) reaches point `y` of area triangle `i`.
    pub fn pdf_area(&self, i: u32, x: Vec3A, n: Option<Vec3A>, y: Vec3A) -> f32 {
        let a = &self.area[i as usize];
        let d = y - x;
        let d2 = d.length_squared();
        let cos_l = a.n.dot(d).abs() / d2.sqrt();
        if cos_l <= 0.0 {
            return 0.0;
        }
        let unit = self.unit_of[i as usize] as usize;
        let first = match self.picker.units[unit] {
            Unit::Area { first, .. } => first as usize,
            _ => unreachable!("area triangles map to area units"),
        };
        self.picker.prob(unit, x, n) / self.unit_area(first) * d2 / cos_l
    }

    /// Solid-angle density with which [`LightSet::sample`] at `x` (normal `n`) picks
    /// direction `d` to the environment.
    pub fn pdf_env(&self, x: Vec3A, n: Option<Vec3A>, d: Vec3A) -> f32 {
        let Some(env) = &self.env else { return 0.0 };
        self.pdf_env_given(x, n, d, || env.pdf(d))
    }

    /// [`LightSet::pdf_env`] with the environment's own density of `d` supplied by the caller
    /// (who may have it from the same map lookup as the radiance), asked for only where no
    /// portal serves `x`.
    #[inline]
    pub fn pdf_env_given(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        d: Vec3A,
        env_pdf: impl FnOnce() -> f32,
    ) -> f32 {
        if self.env.is_none() {
            return 0.0;
        }
        let p = if self.portals.is_empty() {
            env_pdf()
        } else {
            self.portals.pdf(x, d).unwrap_or_else(env_pdf)
        };
        self.picker.prob(self.picker.units.len() - 1, x, n) * p
    }

    /// Samples a light for the point `x` with geometric normal `n` on the side the light must
    /// be on (`None` for a point without a surface, such as the eye).
    pub fn sample(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        u_pick: f32,
        u: [f32; 2],
    ) -> Option<LightSample> {
        let (k, p) = self.picker.pick(x, n, u_pick)?;
        self.sample_unit(k, p, x, u)
    }

    /// Number of units the light choice chooses among.
    pub(crate) fn unit_count(&self) -> usize {
        self.picker.units.len()
    }

    /// A point (or direction) of unit `k`, chosen with probability `p`, seen from `x`.
    #[inline]
    pub(crate) fn sample_unit(
        &self,
        k: usize,
        p: f32,
        x: Vec3A,
        u: [f32; 2],
    ) -> Option<LightSample> {
        match self.picker.units[k] {
            Unit::Area { first, quad } => {
                let a = &self.area[first as usize];
                // A parallelogram is sampled uniformly over both halves (same emission and
                // normal), a lone triangle uniformly over itself (a textured one by area too,
                // its radiance read where the point falls: unbiased, if noisier than
                // Mitsuba's sampling of the texture).
                let (y, li) = if quad == u32::MAX {
                    let su = u[0].sqrt();
                    let (b1, b2) = (su * (1.0 - u[1]), su * u[1]);
                    (
                        a.v0 + a.e1 * b1 + a.e2 * b2,
                        a.radiance(b1, b2, &self.textures),
                    )
                } else {
                    let q = &self.quads[quad as usize];
                    (q.o + q.e1 * u[0] + q.e2 * u[1], a.emission)
                };
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
                    li,
                    pdf: p / self.unit_area(first as usize) * d2 / cos_l,
                    delta: false,
                })
            }
            Unit::Delta(j) => {
                let a = self.deltas[j as usize].arrival(x, Lookup::Texture(&self.textures))?;
                Some(LightSample {
                    wi: a.wi,
                    dist: a.dist,
                    li: a.li,
                    pdf: p,
                    delta: true,
                })
            }
            Unit::Env => {
                let env = self.env.as_ref()?;
                let through = match self.portals.is_empty() {
                    true => Through::NotServed,
                    false => self.portals.sample(x, u),
                };
                let s = match through {
                    Through::Sample(wi, pdf) => EnvSample {
                        wi,
                        li: env.radiance(wi),
                        pdf,
                    },
                    Through::Nothing => return None,
                    // No portals, or none serves `x`: over the whole sphere.
                    Through::NotServed => env.sample(u)?,
                };
                Some(LightSample {
                    wi: s.wi,
                    dist: f32::INFINITY,
                    li: s.li,
                    pdf: p * s.pdf,
                    delta: false,
                })
            }
        }
    }

    /// Number of area-light triangle pairs sampled as parallelograms.
    pub fn parallelogram_count(&self) -> usize {
        self.quads.len()
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
        let first_delta = self.picker.units.len() - self.deltas.len() - self.env.is_some() as usize;
        for (k, d) in self.deltas.iter().enumerate() {
            out.push((d.colour(), self.picker.power(first_delta + k)));
        }
        if let Some(e) = &self.env {
            out.push((e.mean(), self.picker.power(self.picker.units.len() - 1)));
        }
        out
    }
}

/// The tracer's form of a scene light (`textures`: the scene's, for the beams' means).
fn delta_light(l: &Light, textures: &[Texture]) -> DeltaLight {
    let spot_angles = |cone_deg: f32, falloff_deg: f32| {
        let cone = cone_deg.to_radians();
        let fall = falloff_deg.to_radians().min(cone);
        (cone, fall, 1.0 / (cone - fall).max(1e-6))
    };
    match *l {
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
            let (cone, fall, inv_transition) = spot_angles(cone_deg, falloff_deg);
            DeltaLight::Spot {
                position: position.into(),
                direction: direction.normalize().into(),
                intensity: intensity.into(),
                cos_cone: libm::cosf(cone),
                cos_falloff: libm::cosf(fall),
                cone,
                inv_transition,
            }
        }
        Light::Directional {
            direction,
            irradiance,
        } => DeltaLight::Directional {
            direction: direction.normalize().into(),
            irradiance: irradiance.into(),
        },
        Light::TexturedSpot {
            position,
            frame,
            intensity,
            cone_deg,
            falloff_deg,
            texture,
        } => {
            let (cone, fall, inv_transition) = spot_angles(cone_deg, falloff_deg);
            DeltaLight::TexturedSpot(beam::TexturedSpot {
                position: position.into(),
                to_local: beam::to_local(frame),
                intensity: intensity.into(),
                cos_cone: libm::cosf(cone),
                cos_falloff: libm::cosf(fall),
                cone,
                inv_transition,
                tan_cone: libm::tanf(cone),
                image: beam::Image::new(eyeadapt_scene::Param::Texture(texture), textures),
            })
        }
        Light::Projector {
            position,
            frame,
            irradiance,
            scale,
            tan_half_fov_x,
            aspect,
        } => DeltaLight::Projector(beam::Projector {
            position: position.into(),
            to_local: beam::to_local(frame),
            axis: frame.z_axis.into(),
            image: beam::Image::new(irradiance, textures),
            pi_scale: PI * scale,
            tan_half_fov_x,
            aspect,
        }),
    }
}

/// Finds consecutive emissive triangles that form a parallelogram with equal emission and
/// facing: they share two vertices (the diagonal), and the two others mirror each other across
/// its midpoint. Meshes list a quad's two triangles next to each other (OBJ, PLY, the built-in
/// shapes), so looking at neighbours finds them without a search.
fn pair_parallelograms(area: &[AreaTri]) -> (Vec<u32>, Vec<Parallelogram>) {
    let mut quad_of = vec![u32::MAX; area.len()];
    let mut quads = Vec::new();
    let verts = |a: &AreaTri| [a.v0, a.v0 + a.e1, a.v0 + a.e2];
    let mut i = 0;
    while i + 1 < area.len() {
        let (a, b) = (&area[i], &area[i + 1]);
        // Textured triangles stay triangles (their UVs are per triangle).
        let found = (a.emission == b.emission
            && a.texture == u32::MAX
            && b.texture == u32::MAX
            && a.n.dot(b.n) > 1.0 - 1e-6
            && (a.area - b.area).abs() <= 1e-5 * a.area.max(b.area))
        .then(|| {
            let (va, vb) = (verts(a), verts(b));
            let shared: Vec<Vec3A> = va.iter().copied().filter(|v| vb.contains(v)).collect();
            if shared.len() != 2 {
                return None;
            }
            let x = va.iter().copied().find(|v| !shared.contains(v))?;
            let y = vb.iter().copied().find(|v| !shared.contains(v))?;
            let scale = (shared[0] - shared[1]).length();
            ((x + y - shared[0] - shared[1]).length() <= 1e-5 * scale).then_some(Parallelogram {
                o: x,
                e1: shared[0] - x,
                e2: shared[1] - x,
            })
        })
        .flatten();
        match found {
            Some(q) => {
                quad_of[i] = quads.len() as u32;
                quad_of[i + 1] = quads.len() as u32;
                quads.push(q);
                i += 2;
            }
            None => i += 1,
        }
    }
    (quad_of, quads)
}

#[cfg(test)]
#[path = "lights_tests.rs"]
mod tests;
