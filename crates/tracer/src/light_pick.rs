//! Which light next-event estimation samples from a given shading point.
//!
//! The choosable *units* are: each quad light (two emissive triangles paired into a
//! parallelogram), each remaining emissive triangle, each point, spot or directional light, and
//! the environment (weighted by its mean radiance). Textured emitters count with their
//! texture's mean.
//!
//! With few units (2 ..= [`SPATIAL_MAX_UNITS`]) the choice depends on the receiving point: each
//! unit is weighted by a conservative estimate of the irradiance it can deliver there — its
//! power, a distance falloff clamped at its own size, and emitter and receiver cosines widened
//! by the angle it subtends (the importance of Conty & Kulla's light tree, for one node). A unit
//! gets weight 0 only where its contribution is exactly 0: the receiver behind the light's
//! emitting plane, the whole light below the receiver's tangent plane, or outside a spot's cone.
//! So the estimator stays unbiased, and in a house of rooms each room's own light gets most of
//! the shadow rays instead of an equal share with lights behind the walls. Visibility comes
//! from a grid built once per scene ([`crate::light_visibility`]): each unit's importance is
//! multiplied by how much of it the point's cell sees, never by less than a floor, so a light
//! in the next room keeps a little of what its distance earns and nothing can become
//! unreachable.
//!
//! With more than [`SPATIAL_MAX_UNITS`] units the choice still depends on the receiving point,
//! through a light tree ([`crate::light_tree`]) over the units that have a position: the cost
//! per shading point grows with the logarithm of their number. Units without a position
//! (directional lights, the environment) compete with the tree's root. With one unit it is
//! chosen always.
//!
//! **Behind light portals** ([`crate::portal`]) the environment's importance (the irradiance
//! of the whole sky) is scaled by the share of the sky the portals serving the point show
//! (their approximate solid angle over π): in a room lit through two windows the sky is a few
//! per cent of the hemisphere, and weighing it as the whole one gave it most of the shadow
//! rays the sun and the lamps needed (the interior's MSE −24 % at equal samples, no cost;
//! docs/benchmarks/portals.md). Likewise a directional light (the sun) can reach a point the
//! portals serve only along a ray through one of them: where its direction crosses none, its
//! importance is multiplied by [`BEHIND_PORTALS`] (not 0: portals need not cover every
//! opening, and a delta light has no MIS to fall back on), so a room in shade stops spending
//! shadow rays on a sun that only lights two patches of its floor (a further −24 % MSE).
//! Points no portal serves, and scenes without portals, keep the full weights, bit for bit.
use crate::beam::Lookup;
use crate::emitter::{AreaTri, DeltaLight, Parallelogram, luminance};
use crate::light_pick4::{AreaUnit, AreaUnits4};
use crate::light_visibility::Visibility;
use crate::portal::Portals;
use glam::Vec3A;
use rest::Rests;
use std::f32::consts::PI;
use tree::Tree;

/// Most units for which the choice depends on the shading point.
pub const SPATIAL_MAX_UNITS: usize = 16;

/// Most units the choice weighs by a visibility grid (`light_visibility.rs`): its build traces
/// a shadow ray to every unit from every point, so more units leave it fewer, larger cells.
pub const VISIBILITY_MAX_UNITS: usize = 64;

/// The factor of a directional light's importance at a point the portals serve when its
/// direction crosses none of them.
pub const BEHIND_PORTALS: f32 = 1.0 / 16.0;

/// What a unit is, as indices into the light set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Emissive triangles `first` (and `first + 1` when `quad` is not `u32::MAX`).
    Area {
        first: u32,
        quad: u32,
    },
    Delta(u32),
    Env,
}

/// What the spatial importance needs of a unit.
#[derive(Clone, Copy, Debug)]
enum Bounds {
    Area(AreaUnit),
    Delta(DeltaLight),
    Env { luminance: f32 },
}

pub struct LightPicker {
    pub units: Vec<Unit>,
    bounds: Vec<Bounds>,
    /// Cumulative power weights over `units`.
    cdf: Vec<f64>,
    total: f64,
    /// Each unit's share of power, `power(k) / total`, as `f32`: no f64 division a vertex.
    probs: Vec<f32>,
    spatial: bool,
    /// With a spatial choice: its area units (the first ones), four to a vector, and the
    /// others (`light_pick_rest.rs`).
    area4: AreaUnits4,
    rest: Rests,
    /// With more than [`SPATIAL_MAX_UNITS`] units: the tree over the positioned ones.
    tree: Option<Tree>,
    /// The openings the environment and the sun reach the interior through (none: they
    /// reach everywhere).
    portals: Portals,
    /// With a spatial choice: which units each part of the scene sees (`light_visibility.rs`).
    visibility: Option<Visibility>,
    /// With a tree and a visibility grid: per cell, [`Tree::seen_factors`], `tree_stride` each
    /// (kept, so that a lookup needs no division).
    tree_seen: Vec<f32>,
    tree_stride: usize,
}

/// What the visibility grid says at a point: each unit's factor and, with a tree, the
/// factors of its root and lanes ([`Tree::seen_factors`]).
#[derive(Clone, Copy)]
struct Seen<'a> {
    units: &'a [f32],
    tree: &'a [f32],
}

/// A point behind portals: the portals (which a sun's direction may cross) and the share of
/// the sky they show there (see the module docs).
#[derive(Clone, Copy)]
struct Behind<'a> {
    portals: &'a Portals,
    sky: f32,
}

/// Luminance used for weights, floored so that a coloured light whose luminance rounds to
/// nothing stays reachable.
fn weight_luminance(c: Vec3A) -> f32 {
    luminance(c).max(1e-6 * c.max_element()).max(0.0)
}

/// cos(max(0, θ − β)) for cos θ = `cos_t` and a half-angle β given by its sine and cosine: the
/// largest cosine any direction within β of the axis can have.
#[inline]
fn widened_cos(cos_t: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_t >= cos_b {
        1.0
    } else {
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        cos_t * cos_b + sin_t * sin_b
    }
}

impl LightPicker {
    pub fn build(
        area: &[AreaTri],
        quad_of: &[u32],
        quads: &[Parallelogram],
        deltas: &[DeltaLight],
        env: Option<Vec3A>,
        scene_radius: f32,
    ) -> LightPicker {
        let r = scene_radius.max(1e-3);
        let mut units = Vec::new();
        let mut bounds = Vec::new();
        let mut weights: Vec<f64> = Vec::new();
        let mut i = 0;
        while i < area.len() {
            let a = &area[i];
            let q = quad_of[i];
            let (corners, total_area) = if q == u32::MAX {
                let v = [a.v0, a.v0 + a.e1, a.v0 + a.e2];
                ([v[0], v[1], v[2], v[2]], a.area)
            } else {
                let p = &quads[q as usize];
                (
                    [p.o, p.o + p.e1, p.o + p.e1 + p.e2, p.o + p.e2],
                    a.area + area[i + 1].area,
                )
            };
            let centre = if q == u32::MAX {
                (corners[0] + corners[1] + corners[2]) / 3.0
            } else {
                (corners[0] + corners[2]) * 0.5
            };
            let radius = corners
                .iter()
                .map(|c| (*c - centre).length())
                .fold(0.0f32, f32::max);
            let power = total_area * weight_luminance(a.emission);
            units.push(Unit::Area {
                first: i as u32,
                quad: q,
            });
            bounds.push(Bounds::Area(AreaUnit {
                centre,
                radius,
                normal: a.n,
                corners,
                power,
            }));
            weights.push((PI * power) as f64);
            i += if q == u32::MAX { 1 } else { 2 };
        }
        for (k, d) in deltas.iter().enumerate() {
            units.push(Unit::Delta(k as u32));
            bounds.push(Bounds::Delta(*d));
            weights.push(match *d {
                DeltaLight::Point { intensity, .. } => 4.0 * PI * weight_luminance(intensity),
                DeltaLight::Spot {
                    intensity,
                    cos_cone,
                    cos_falloff,
                    ..
                } => {
                    2.0 * PI * (1.0 - 0.5 * (cos_cone + cos_falloff)) * weight_luminance(intensity)
                }
                // What crosses the scene's bounding disc.
                DeltaLight::Directional { irradiance, .. } => {
                    PI * r * r * weight_luminance(irradiance)
                }
                DeltaLight::TexturedSpot(s) => {
                    2.0 * PI
                        * (1.0 - 0.5 * (s.cos_cone + s.cos_falloff))
                        * weight_luminance(s.colour())
                }
                DeltaLight::Projector(p) => weight_luminance(p.power()),
            } as f64);
        }
        if let Some(e) = env {
            units.push(Unit::Env);
            bounds.push(Bounds::Env {
                luminance: weight_luminance(e),
            });
            weights.push((PI * weight_luminance(e) * PI * r * r) as f64);
        }
        let mut cdf = Vec::with_capacity(weights.len());
        let mut total = 0.0;
        for w in weights {
            total += w.max(1e-12);
            cdf.push(total);
        }
        let lo = std::iter::once(0.0).chain(cdf.clone());
        let probs = Vec::from_iter(cdf.iter().zip(lo).map(|(c, lo)| ((c - lo) / total) as f32));
        let spatial = (2..=SPATIAL_MAX_UNITS).contains(&units.len());
        // Area units come first: the spatial choice weighs them four at a time.
        let area4 = spatial.then(|| {
            let area: Vec<AreaUnit> = bounds
                .iter()
                .map_while(|b| match b {
                    Bounds::Area(a) => Some(*a),
                    _ => None,
                })
                .collect();
            AreaUnits4::pack(&area)
        });
        let rest = area4.as_ref().map(|a| Rests::new(&bounds[a.len()..]));
        let tree = (units.len() > SPATIAL_MAX_UNITS)
            .then(|| Tree::build(&bounds))
            .flatten();
        LightPicker {
            units,
            bounds,
            cdf,
            total,
            probs,
            spatial,
            area4: area4.unwrap_or_default(),
            rest: rest.unwrap_or_default(),
            tree,
            portals: Portals::default(),
            visibility: None,
            tree_seen: Vec::new(),
            tree_stride: 0,
        }
    }

    /// Weighs each unit's importance by how much of it the shading point's part of the scene
    /// sees (`light_visibility.rs`).
    pub fn see_through(&mut self, visibility: Option<Visibility>) {
        self.tree_seen = match (&self.tree, &visibility) {
            (Some(t), Some(v)) => (0..v.cells())
                .flat_map(|c| t.seen_factors(v.of_cell(c)))
                .collect(),
            _ => Vec::new(),
        };
        self.tree_stride = visibility
            .as_ref()
            .map_or(0, |v| self.tree_seen.len() / v.cells());
        self.visibility = visibility;
    }

    /// Whether the choice depends on the shading point and has at most
    /// [`VISIBILITY_MAX_UNITS`] units: what [`LightPicker::see_through`] acts on.
    pub fn takes_visibility(&self) -> bool {
        self.is_spatial() && self.units.len() <= VISIBILITY_MAX_UNITS
    }

    /// The visibility grid, if any.
    #[cfg(test)]
    pub fn visibility(&self) -> Option<&Visibility> {
        self.visibility.as_ref()
    }

    /// What the visibility grid says at `x`, with a tree.
    #[inline]
    fn seen_by_tree(&self, x: Vec3A) -> Option<Seen<'_>> {
        let v = self.visibility.as_ref()?;
        let c = v.cell(x)?;
        let stride = self.tree_stride;
        Some(Seen {
            units: v.of_cell(c),
            tree: &self.tree_seen[c * stride..(c + 1) * stride],
        })
    }

    /// The environment and directional lights reach the interior only through `portals`:
    /// at a point they serve, the environment's importance is scaled by the share of the sky
    /// they show there, and a directional light's by [`BEHIND_PORTALS`] where its direction
    /// crosses none of them.
    pub fn through(mut self, portals: Portals) -> LightPicker {
        self.portals = portals;
        self
    }

    /// What the portals say at `x` (nothing without portals).
    #[inline]
    fn behind(&self, x: Vec3A) -> Option<Behind<'_>> {
        (!self.portals.is_empty()).then(|| Behind {
            portals: &self.portals,
            sky: self.portals.sky_share(x),
        })
    }

    /// Whether the choice depends on the shading point.
    pub fn is_spatial(&self) -> bool {
        self.spatial || self.tree.is_some()
    }

    /// Whether the choice goes through a light tree.
    #[cfg(test)]
    pub fn has_tree(&self) -> bool {
        self.tree.is_some()
    }

    /// Unit `k`'s power weight (flux in luminance units, floored at 1e-12).
    pub fn power(&self, k: usize) -> f64 {
        let lo = if k == 0 { 0.0 } else { self.cdf[k - 1] };
        self.cdf[k] - lo
    }

    /// Probability of choosing unit `k` regardless of the shading point (its share of power).
    #[cfg(test)]
    pub fn power_prob(&self, k: usize) -> f64 {
        self.power(k) / self.total
    }

    /// Chooses a unit for a shading point `x` with (geometric, viewer-side) normal `n`, or
    /// `None` for a point that only looks from, like the eye. Returns the unit's index and the
    /// probability of that choice; `None` when no unit can contribute at `x`.
    #[inline]
    pub fn pick(&self, x: Vec3A, n: Option<Vec3A>, u: f32) -> Option<(usize, f32)> {
        if self.cdf.is_empty() {
            return None;
        }
        if let Some(t) = &self.tree {
            return t.pick(
                &self.bounds,
                (x, n, self.behind(x)),
                u,
                self.seen_by_tree(x),
            );
        }
        if !self.spatial {
            let target = u as f64 * self.total;
            let k = self
                .cdf
                .partition_point(|&c| c <= target)
                .min(self.cdf.len() - 1);
            return Some((k, self.probs[k]));
        }
        let mut w = [0.0f32; SPATIAL_MAX_UNITS];
        let total = self.importances(x, n, &mut w);
        if total <= 0.0 {
            return None;
        }
        let target = u * total;
        let mut acc = 0.0;
        let mut last = 0;
        for (k, &wk) in w[..self.units.len()].iter().enumerate() {
            if wk > 0.0 {
                acc += wk;
                last = k;
                if target < acc {
                    return Some((k, wk / total));
                }
            }
        }
        // Rounding left `target` at or above the running sum: the last unit that can contribute.
        Some((last, w[last] / total))
    }

    /// Probability that [`LightPicker::pick`] at (`x`, `n`) chooses unit `k`.
    #[inline]
    pub fn prob(&self, k: usize, x: Vec3A, n: Option<Vec3A>) -> f32 {
        if let Some(t) = &self.tree {
            return t.prob(
                &self.bounds,
                k,
                (x, n, self.behind(x)),
                self.seen_by_tree(x),
            );
        }
        if !self.spatial {
            return self.probs[k];
        }
        let mut w = [0.0f32; SPATIAL_MAX_UNITS];
        let total = self.importances(x, n, &mut w);
        if total <= 0.0 { 0.0 } else { w[k] / total }
    }

    /// Every unit's importance at (`x`, `n`) into `w`; returns their sum.
    fn importances(&self, x: Vec3A, n: Option<Vec3A>, w: &mut [f32; SPATIAL_MAX_UNITS]) -> f32 {
        // Four at a time and bit for bit what `importance` gives (light_pick4.rs); the others
        // (bit for bit `unit_importance`'s) overwrite what it left past the last area unit.
        self.area4.importances(x, n, w);
        let (a, all) = (self.area4.len(), self.units.len());
        self.rest.importances(x, n, self.behind(x), &mut w[a..all]);
        // One pass over the units (the grid has a factor for each), summed in their order.
        let w = &mut w[..self.units.len()];
        let mut total = 0.0;
        match self.visibility.as_ref().and_then(|v| v.at(x)) {
            Some(f) => w.iter_mut().zip(f).for_each(|(wk, fk)| {
                *wk *= fk;
                total += *wk;
            }),
            None => w.iter().for_each(|&wk| total += wk),
        }
        total
    }
}

/// [`importance`], behind portals with the environment's scaled by the share of the sky
/// they show and a directional light's by whether its direction crosses one.
#[inline]
fn unit_importance(b: &Bounds, x: Vec3A, n: Option<Vec3A>, behind: Option<Behind>) -> f32 {
    let w = importance(b, x, n);
    let Some(at) = behind else { return w };
    match b {
        Bounds::Env { .. } => w * at.sky,
        Bounds::Delta(DeltaLight::Directional { direction, .. }) => {
            match at.portals.lets_through(x, -*direction) {
                Some(false) => w * BEHIND_PORTALS,
                _ => w,
            }
        }
        _ => w,
    }
}

/// How far `x` is in front of an area unit's plane, or `None` where the unit delivers nothing
/// there: `x` behind (or in) the one-sided emitter's plane, where every point of it faces away,
/// or the unit entirely below the receiver's tangent plane (linear in the light point, so the
/// corners decide for the whole polygon).
#[inline]
fn area_front(
    centre: Vec3A,
    normal: Vec3A,
    corners: &[Vec3A; 4],
    x: Vec3A,
    n: Option<Vec3A>,
) -> Option<f32> {
    let front = (x - centre).dot(normal);
    if front <= 0.0 {
        return None;
    }
    if let Some(n) = n
        && corners.iter().all(|c| (*c - x).dot(n) <= 0.0)
    {
        return None;
    }
    Some(front)
}

/// A unit's weight as a leaf of the light tree, given its node's bound there: an area unit
/// keeps the bound where it can deliver anything (the exact zero tests of [`importance`]) and
/// gets 0 elsewhere; a delta light gets its own importance (its cone and beam tests).
#[inline(always)]
fn tree_leaf(b: &Bounds, x: Vec3A, n: Option<Vec3A>, bound: f32) -> f32 {
    match *b {
        Bounds::Area(AreaUnit {
            centre,
            normal,
            ref corners,
            power,
            ..
        }) => match area_front(centre, normal, corners, x, n) {
            Some(_) if power > 0.0 => bound,
            _ => 0.0,
        },
        _ => importance(b, x, n),
    }
}

/// Estimated irradiance a unit delivers at `x` (normal `n`; scalar irradiance without one);
/// exactly 0 only where it delivers none.
#[inline]
fn importance(b: &Bounds, x: Vec3A, n: Option<Vec3A>) -> f32 {
    match *b {
        Bounds::Area(AreaUnit {
            centre,
            radius,
            normal,
            corners,
            power,
        }) => {
            let Some(front) = area_front(centre, normal, &corners, x, n) else {
                return 0.0;
            };
            let to = centre - x;
            let d2 = to.length_squared();
            let d = d2.sqrt();
            let sin_b = (radius / d).min(1.0);
            let cos_b = (1.0 - sin_b * sin_b).max(0.0).sqrt();
            let cos_e = widened_cos(front / d, sin_b, cos_b);
            let cos_r = match n {
                Some(n) => widened_cos(n.dot(to) / d, sin_b, cos_b),
                None => 1.0,
            };
            // Floors keep a unit that can contribute (the exact tests above) choosable when
            // rounding takes a widened cosine to 0.
            power * cos_e.max(1e-3) * cos_r.max(1e-3) / d2.max(radius * radius).max(1e-12)
        }
        Bounds::Delta(ref l) => {
            // A beam's image counts with its mean: positive wherever the beam reaches.
            let Some(a) = l.arrival(x, Lookup::Mean) else {
                return 0.0;
            };
            let cos_r = match n {
                Some(n) => a.wi.dot(n),
                None => 1.0,
            };
            if cos_r <= 0.0 || a.li.max_element() <= 0.0 {
                return 0.0;
            }
            weight_luminance(a.li) * cos_r
        }
        Bounds::Env { luminance } => match n {
            Some(_) => PI * luminance,
            None => 4.0 * PI * luminance,
        },
    }
}

#[path = "light_pick_tree.rs"]
mod tree;

#[path = "light_pick_rest.rs"]
mod rest;

#[cfg(test)]
#[path = "light_pick_tests.rs"]
mod tests;
