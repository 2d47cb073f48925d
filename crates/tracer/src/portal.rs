//! Light portals ([`eyeadapt_scene::Portal`]): the environment sampled through the openings of
//! an interior instead of over the whole sphere.
//!
//! A point on the room side of at least one portal is *served* by the portals. From it,
//! next-event estimation picks a portal in proportion to an estimate of the solid angle it
//! subtends (area × cosine / distance² at its centre), draws a point uniformly on its area and
//! reads the environment along the direction to that point. The solid-angle density of a
//! direction is the sum, over the portals its ray crosses, of each one's choice probability
//! × distance² / (area × cosine) at the crossing, and 0 for a direction through no portal: a
//! BSDF-sampled ray that leaves the scene elsewhere (through an opening without a portal)
//! keeps its whole contribution under MIS, so the image stays unbiased wherever portals are
//! put; they only decide how well the sky is found. A point no portal serves (outdoors)
//! samples the environment over the whole sphere as without portals (as in Cycles).
//!
//! Sampling by area rather than by solid angle (Ureña et al. 2013) leaves some variance where
//! a window is close and wide, but needs only arithmetic and square roots: no libm angle
//! functions, whose glibc variants differ with and without FMA, and a fraction of the cost.
use eyeadapt_scene::Portal;
use glam::Vec3A;

/// A portal ready for sampling.
#[derive(Clone, Copy, Debug)]
struct Rect {
    corner: Vec3A,
    u: Vec3A,
    v: Vec3A,
    centre: Vec3A,
    /// Unit normal u × v (towards the room).
    n: Vec3A,
    /// Unit edge directions and lengths, for the crossing test.
    ux: Vec3A,
    vy: Vec3A,
    len_u: f32,
    len_v: f32,
    area: f32,
    /// How far off its plane a point must be to be served: 1e-6 × (`len_u` + `len_v`).
    margin: f32,
}

impl Rect {
    fn new(p: &Portal) -> Rect {
        let (u, v) = (Vec3A::from(p.u), Vec3A::from(p.v));
        let corner = Vec3A::from(p.corner);
        let (len_u, len_v) = (u.length(), v.length());
        Rect {
            corner,
            u,
            v,
            centre: corner + (u + v) * 0.5,
            n: u.cross(v).normalize(),
            ux: u / len_u,
            vy: v / len_v,
            len_u,
            len_v,
            area: u.cross(v).length(),
            margin: 1e-6 * (len_u + len_v),
        }
    }

    /// Whether `o` is on the room side (off the plane by more than a rounding margin).
    #[inline]
    fn serves(&self, o: Vec3A) -> bool {
        self.height(o) > self.margin
    }

    /// How far `o` is off the portal's plane, on the room side.
    #[inline]
    fn height(&self, o: Vec3A) -> f32 {
        (o - self.corner).dot(self.n)
    }

    /// The choice weight at `o` (served): area × cosine / distance² at the centre, the
    /// distance kept at least the portal's size.
    #[inline]
    fn weight(&self, o: Vec3A) -> f32 {
        let d = o - self.centre;
        let d2 = d.length_squared();
        let cos = (d.dot(self.n) / d2.sqrt()).max(1e-4);
        self.area * cos / d2.max(self.area)
    }

    /// Area-to-solid-angle factor distance² / (area × cosine) where the ray from `o` (served)
    /// along unit `d` crosses the portal, or `None` when it misses it.
    #[inline]
    fn crossing(&self, o: Vec3A, d: Vec3A) -> Option<f32> {
        self.crossing_at(self.height(o), o, d)
    }

    /// [`Rect::crossing`] with `o`'s height `h` known.
    #[inline]
    fn crossing_at(&self, h: f32, o: Vec3A, d: Vec3A) -> Option<f32> {
        let cos = -d.dot(self.n);
        if cos <= 0.0 {
            return None;
        }
        let t = h / cos;
        let q = o + d * t - self.corner;
        let (a, b) = (q.dot(self.ux), q.dot(self.vy));
        ((0.0..=self.len_u).contains(&a) && (0.0..=self.len_v).contains(&b))
            .then(|| t * t / (self.area * cos))
    }
}

/// The scene's portals.
#[derive(Clone, Debug, Default)]
pub struct Portals {
    rects: Vec<Rect>,
}

/// What the portals make of the environment at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Through {
    /// No portal serves the point: the environment is sampled over the whole sphere.
    NotServed,
    /// A direction through a portal and its solid-angle density.
    Sample(Vec3A, f32),
    /// The portals serve the point but this sample found no direction.
    Nothing,
}

impl Portals {
    pub fn new(portals: &[Portal]) -> Portals {
        Portals {
            rects: portals.iter().map(Rect::new).collect(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// Sum of the choice weights of the portals that serve `o` (0: none does).
    #[inline]
    fn total(&self, o: Vec3A) -> f32 {
        self.rects
            .iter()
            .filter(|r| r.serves(o))
            .map(|r| r.weight(o))
            .sum()
    }

    /// The share of the whole sky the portals let reach `o`: their approximate solid angle
    /// (the choice weights) over π, at most 1; 1 where none serves `o` (the environment is
    /// then sampled over the sphere). The light choice scales the environment's importance
    /// by it ([`crate::light_pick`]).
    #[inline]
    pub fn sky_share(&self, o: Vec3A) -> f32 {
        match self.total(o) {
            t if t > 0.0 => (t / std::f32::consts::PI).min(1.0),
            _ => 1.0,
        }
    }

    /// Whether light from unit direction `wi` can reach `o` through the portals: `None` where
    /// none serves `o` (or there are none), else whether the ray from `o` along `wi` crosses
    /// one that does. The light choice weighs a directional light by it
    /// ([`crate::light_pick`]).
    #[inline]
    pub fn lets_through(&self, o: Vec3A, wi: Vec3A) -> Option<bool> {
        let mut served = false;
        for r in &self.rects {
            // `serves`, its height kept for the crossing.
            let h = r.height(o);
            if h > r.margin {
                if r.crossing_at(h, o, wi).is_some() {
                    return Some(true);
                }
                served = true;
            }
        }
        served.then_some(false)
    }

    /// A direction from `o` through a portal, drawn with `u`.
    pub fn sample(&self, o: Vec3A, u: [f32; 2]) -> Through {
        let total = self.total(o);
        if total <= 0.0 {
            return Through::NotServed;
        }
        // The portal whose share of the total holds u[0]; u[0] is then stretched over that
        // share so that it stays uniform along the portal's first edge.
        let target = u[0] * total;
        let mut acc = 0.0;
        let mut chosen = None;
        for r in self.rects.iter().filter(|r| r.serves(o)) {
            let w = r.weight(o);
            chosen = Some((r, w, acc));
            if target < acc + w {
                break;
            }
            acc += w;
        }
        let Some((r, w, lo)) = chosen else {
            return Through::NotServed;
        };
        let s = ((target - lo) / w).clamp(0.0, 1.0);
        let y = r.corner + r.u * s + r.v * u[1];
        let d = y - o;
        let d2 = d.length_squared();
        let wi = d / d2.sqrt();
        let cos = -wi.dot(r.n);
        if !(cos > 0.0 && d2 > 0.0) {
            return Through::Nothing;
        }
        // The chosen portal by the point drawn; any other the ray also crosses by its crossing.
        let mut pdf = w / total * d2 / (r.area * cos);
        for other in self
            .rects
            .iter()
            .filter(|x| !std::ptr::eq(*x, r) && x.serves(o))
        {
            if let Some(j) = other.crossing(o, wi) {
                pdf += other.weight(o) / total * j;
            }
        }
        if pdf.is_finite() && pdf > 0.0 {
            Through::Sample(wi, pdf)
        } else {
            Through::Nothing
        }
    }

    /// Solid-angle density with which [`Portals::sample`] at `o` draws unit direction `d`;
    /// `None` when no portal serves `o`.
    pub fn pdf(&self, o: Vec3A, d: Vec3A) -> Option<f32> {
        let mut crossed = 0.0;
        let mut total = 0.0;
        for r in self.rects.iter().filter(|r| r.serves(o)) {
            let w = r.weight(o);
            total += w;
            if let Some(j) = r.crossing(o, d) {
                crossed += w * j;
            }
        }
        (total > 0.0).then(|| crossed / total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::f32::consts::PI;

    /// Two windows in the wall x = −3 facing +x, as in `builtin:interior`.
    fn windows() -> Portals {
        let p = |z0: f32| Portal {
            corner: Vec3::new(-3.0, 0.7, z0),
            u: Vec3::new(0.0, 1.8, 0.0),
            v: Vec3::new(0.0, 0.0, 1.6),
        };
        Portals::new(&[p(-5.0), p(-2.4)])
    }

    /// A low-discrepancy point set (the 2-D golden-ratio sequence) with an offset.
    fn points(n: usize, off: f32) -> impl Iterator<Item = [f32; 2]> {
        (0..n).map(move |i| {
            let a = (off + i as f32 * 0.618_034).fract();
            let b = ((i as f32 + 0.5) / n as f32 + off * 0.37).fract();
            [a, b]
        })
    }

    #[test]
    fn the_sky_share_is_the_openings_solid_angle_over_pi() {
        let p = windows();
        // 8 m from the windows' wall: each 1.8 × 1.6 m opening subtends about area × cos / d².
        let o = Vec3A::new(5.0, 1.6, -3.7);
        let omega = |c: Vec3A| {
            let d = o - c;
            1.8 * 1.6 * (d.x / d.length()) / d.length_squared()
        };
        let want = (omega(Vec3A::new(-3.0, 1.6, -4.2)) + omega(Vec3A::new(-3.0, 1.6, -1.6))) / PI;
        let got = p.sky_share(o);
        assert!((got - want).abs() < 1e-4 * want, "{got} vs {want}");
        // Nearer windows show more sky, never more than the whole of it (a portal's weight
        // keeps the distance at least its size: at its face, 1 of the π).
        let near = p.sky_share(Vec3A::new(0.0, 1.6, -3.7));
        let at = p.sky_share(Vec3A::new(-2.99, 1.6, -4.2));
        assert!(got < near && near < at && at <= 1.0, "{got} {near} {at}");
        // Outdoors no portal serves the point: the whole sky.
        assert_eq!(p.sky_share(Vec3A::new(-4.0, 1.6, -3.7)), 1.0);
        assert_eq!(Portals::new(&[]).sky_share(o), 1.0);
    }

    #[test]
    fn a_direction_gets_through_where_its_ray_crosses_a_serving_portal() {
        let p = windows();
        // Towards the first window's middle (x = −3, y 0.7..2.5, z −5..−3.4), and past it.
        let o = Vec3A::new(1.0, 1.0, -4.2);
        let to = |t: Vec3A| (t - o).normalize();
        for (target, through) in [
            (Vec3A::new(-3.0, 1.6, -4.2), true),
            (Vec3A::new(-3.0, 1.6, -2.0), true),
            (Vec3A::new(-3.0, 1.6, -3.0), false),
            (Vec3A::new(-3.0, 3.0, -4.2), false),
        ] {
            assert_eq!(p.lets_through(o, to(target)), Some(through), "{target}");
        }
        // Away from the wall, and straight up: no portal on the way.
        assert_eq!(p.lets_through(o, Vec3A::X), Some(false));
        assert_eq!(p.lets_through(o, Vec3A::Y), Some(false));
        // Outdoors, or without portals: not served, nothing known.
        assert_eq!(p.lets_through(Vec3A::new(-4.0, 1.0, -4.2), Vec3A::X), None);
        assert_eq!(Portals::new(&[]).lets_through(o, -Vec3A::X), None);
    }

    #[test]
    fn a_sample_goes_through_a_portal_with_the_density_pdf_gives_it() {
        let p = windows();
        for o in [
            Vec3A::new(1.0, 1.0, -3.0),
            Vec3A::new(-2.9, 0.2, -0.1),
            Vec3A::new(2.5, 2.9, -10.0),
        ] {
            for u in points(500, 0.3) {
                let Through::Sample(wi, pdf) = p.sample(o, u) else {
                    panic!("{o} is served: {:?}", p.sample(o, u));
                };
                assert!((wi.length() - 1.0).abs() < 1e-5);
                let q = p.pdf(o, wi).unwrap();
                assert!((q - pdf).abs() <= 1e-3 * pdf, "{o} {u:?}: {q} vs {pdf}");
                // The ray reaches the wall x = −3 inside one of the openings.
                let t = (-3.0 - o.x) / wi.x;
                let y = o + wi * t;
                let inside = (0.7 - 1e-3..=2.5 + 1e-3).contains(&y.y)
                    && ((-5.0 - 1e-3..=-3.4 + 1e-3).contains(&y.z)
                        || (-2.4 - 1e-3..=-0.8 + 1e-3).contains(&y.z));
                assert!(t > 0.0 && inside, "{o} → {y}");
            }
        }
    }

    /// ∫ f dω over the sphere by a midpoint latitude–longitude sum of `nt` × 2`nt` cells.
    fn over_sphere(nt: usize, f: impl Fn(Vec3A) -> f64) -> f64 {
        let np = 2 * nt;
        let mut sum = 0.0f64;
        for i in 0..nt {
            let theta = (i as f32 + 0.5) / nt as f32 * PI;
            let (st, ct) = libm::sincosf(theta);
            for j in 0..np {
                let phi = (j as f32 + 0.5) / np as f32 * 2.0 * PI;
                sum += f(Vec3A::new(st * libm::cosf(phi), ct, st * libm::sinf(phi))) * st as f64;
            }
        }
        sum * (PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64)
    }

    #[test]
    fn the_density_integrates_to_one_over_the_sphere() {
        // ∫ pdf dω by a fine latitude–longitude sum: directions through no portal have 0.
        let p = windows();
        for o in [Vec3A::new(0.5, 1.2, -3.0), Vec3A::new(-2.0, 0.5, -1.0)] {
            let integral = over_sphere(1200, |d| p.pdf(o, d).unwrap() as f64);
            assert!((integral - 1.0).abs() < 0.01, "{o}: ∫ pdf = {integral}");
        }
    }

    #[test]
    fn one_over_the_density_estimates_the_solid_angle_of_the_openings() {
        // E[1/pdf] over samples = the solid angle they cover; the sum above gives it too.
        let p = windows();
        let o = Vec3A::new(0.5, 1.2, -3.0);
        let n = 20_000;
        let mc: f64 = points(n, 0.1)
            .map(|u| match p.sample(o, u) {
                Through::Sample(_, pdf) => 1.0 / pdf as f64,
                other => panic!("{other:?}"),
            })
            .sum::<f64>()
            / n as f64;
        let omega = over_sphere(1500, |d| f64::from(u8::from(p.pdf(o, d).unwrap() > 0.0)));
        assert!(omega > 0.3, "the windows subtend {omega} sr");
        assert!(
            (mc - omega).abs() < 0.01 * omega,
            "E[1/pdf] {mc} vs {omega} sr"
        );
    }

    #[test]
    fn points_behind_or_in_the_portals_plane_are_not_served() {
        let p = windows();
        for o in [Vec3A::new(-4.0, 1.0, -3.0), Vec3A::new(-3.0, 1.0, -3.0)] {
            assert_eq!(p.sample(o, [0.5, 0.5]), Through::NotServed);
            assert_eq!(p.pdf(o, Vec3A::X), None);
        }
        // Served: a direction through no portal has density 0.
        assert_eq!(p.pdf(Vec3A::new(0.0, 1.0, -3.0), Vec3A::Y), Some(0.0));
    }

    #[test]
    fn overlapping_portals_add_their_densities() {
        // The same opening twice: each is chosen half the time and every direction through
        // it crosses both, so the density is the single portal's.
        let w = Portal {
            corner: Vec3::new(-3.0, 0.7, -5.0),
            u: Vec3::new(0.0, 1.8, 0.0),
            v: Vec3::new(0.0, 0.0, 1.6),
        };
        let (one, two) = (Portals::new(&[w]), Portals::new(&[w, w]));
        let o = Vec3A::new(0.0, 1.5, -4.0);
        for u in points(50, 0.7) {
            let (Through::Sample(a, pa), Through::Sample(b, pb)) =
                (one.sample(o, u), two.sample(o, u))
            else {
                panic!("{o} is served")
            };
            assert!((pb - two.pdf(o, b).unwrap()).abs() <= 1e-4 * pb);
            assert!((pb - one.pdf(o, b).unwrap()).abs() <= 1e-4 * pb);
            assert!((pa - one.pdf(o, a).unwrap()).abs() <= 1e-4 * pa);
        }
    }
}
