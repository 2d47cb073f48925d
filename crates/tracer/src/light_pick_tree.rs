//! The light tree of a [`LightPicker`](super::LightPicker) with more than
//! [`SPATIAL_MAX_UNITS`](super::SPATIAL_MAX_UNITS) units: the choice among the units that have
//! a position goes down a [`LightTree`], and the units without one (directional lights, the
//! environment) compete with its root.
use super::{Behind, Bounds, Seen, importance, tree_leaf, unit_importance, weight_luminance};
use crate::emitter::DeltaLight;
use crate::light_pick4::AreaUnit;
use crate::light_tree::{LightBounds, LightTree};
use glam::Vec3A;
use std::f32::consts::PI;

/// The light tree of a picker and how its leaves map to units.
pub(super) struct Tree {
    tree: LightTree,
    /// The unit of each tree light.
    unit: Vec<u32>,
    /// The bounds of each tree light's unit (a copy of `bounds[unit[i]]`, one lookup less a leaf).
    leaf_bounds: Vec<Bounds>,
    /// Each unit's tree light, `u32::MAX` for the units outside it.
    leaf: Vec<u32>,
    /// Units outside the tree (no position: directional lights, the environment).
    unbounded: Vec<u32>,
}

impl Tree {
    /// The tree over the units of `bounds` that have a position; `None` when none has.
    pub(super) fn build(bounds: &[Bounds]) -> Option<Tree> {
        let mut lights = Vec::new();
        let mut unit = Vec::new();
        let mut leaf = vec![u32::MAX; bounds.len()];
        let mut unbounded = Vec::new();
        for (k, b) in bounds.iter().enumerate() {
            match light_bounds(b) {
                Some(lb) => {
                    leaf[k] = lights.len() as u32;
                    lights.push(lb);
                    unit.push(k as u32);
                }
                None => unbounded.push(k as u32),
            }
        }
        Some(Tree {
            tree: LightTree::build(&lights)?,
            leaf_bounds: unit.iter().map(|&k| bounds[k as usize]).collect(),
            unit,
            leaf,
            unbounded,
        })
    }

    /// The root's importance (its light's own when the tree is one leaf) and the unbounded
    /// units' at (`x`, `n`) with the sky's share `sky`, and their sum.
    fn top(
        &self,
        bounds: &[Bounds],
        (x, n, behind): (Vec3A, Option<Vec3A>, Option<Behind>),
        seen: Option<Seen>,
    ) -> (f32, f32) {
        let root = if self.unit.len() == 1 {
            importance(&bounds[self.unit[0] as usize], x, n)
        } else {
            self.tree.root_importance(x, n)
        } * seen.map_or(1.0, |s| s.tree[0]);
        let rest: f32 = self
            .unbounded
            .iter()
            .map(|&k| unbounded_importance(bounds, k as usize, (x, n, behind), seen))
            .sum();
        (root, root + rest)
    }

    /// Per cell of a visibility grid: the root's factor (the largest of the tree's units'),
    /// then the tree's lane factors ([`LightTree::lane_factors`]), from the cell's unit
    /// factors `units`.
    pub(super) fn seen_factors(&self, units: &[f32]) -> Vec<f32> {
        let lanes = self.tree.lane_factors(|i| units[self.unit[i] as usize]);
        let root = self
            .unit
            .iter()
            .fold(0.0f32, |a, &k| a.max(units[k as usize]));
        std::iter::once(root).chain(lanes).collect()
    }

    pub(super) fn pick(
        &self,
        bounds: &[Bounds],
        (x, n, behind): (Vec3A, Option<Vec3A>, Option<Behind>),
        u: f32,
        seen: Option<Seen>,
    ) -> Option<(usize, f32)> {
        let leaf = |i: usize, w: f32| tree_leaf(&self.leaf_bounds[i], x, n, w);
        let lanes = seen.map(|s| &s.tree[1..]);
        if self.unbounded.is_empty() {
            // Nothing competes with the root: the walk alone chooses (and finds no light where
            // the root's children reach none).
            let (i, p) = self.tree.pick(x, n, u, leaf, lanes)?;
            return Some((self.unit[i] as usize, p));
        }
        let (root, total) = self.top(bounds, (x, n, behind), seen);
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let target = u * total;
        if target < root {
            let v = (target / root).min(1.0 - f32::EPSILON / 2.0);
            let (i, p) = self.tree.pick(x, n, v, leaf, lanes)?;
            return Some((self.unit[i] as usize, root / total * p));
        }
        let mut acc = root;
        let mut last = None;
        for &k in &self.unbounded {
            let w = unbounded_importance(bounds, k as usize, (x, n, behind), seen);
            if w > 0.0 {
                acc += w;
                last = Some((k as usize, w / total));
                if target < acc {
                    break;
                }
            }
        }
        // Rounding may leave `target` at the running sum: the last unit that can contribute.
        last.or_else(|| {
            let (i, p) = self
                .tree
                .pick(x, n, 1.0 - f32::EPSILON / 2.0, leaf, lanes)?;
            Some((self.unit[i] as usize, root / total * p))
        })
    }

    pub(super) fn prob(
        &self,
        bounds: &[Bounds],
        k: usize,
        (x, n, behind): (Vec3A, Option<Vec3A>, Option<Behind>),
        seen: Option<Seen>,
    ) -> f32 {
        let leaf = |i: usize, w: f32| tree_leaf(&self.leaf_bounds[i], x, n, w);
        let lanes = seen.map(|s| &s.tree[1..]);
        if self.unbounded.is_empty() {
            return self.tree.prob(self.leaf[k] as usize, x, n, leaf, lanes);
        }
        let (root, total) = self.top(bounds, (x, n, behind), seen);
        if total.is_nan() || total <= 0.0 {
            return 0.0;
        }
        match self.leaf[k] {
            u32::MAX => unbounded_importance(bounds, k, (x, n, behind), seen) / total,
            i => root / total * self.tree.prob(i as usize, x, n, leaf, lanes),
        }
    }
}

/// The importance of unit `k`, one without a position, times its visibility factor.
#[inline]
fn unbounded_importance(
    bounds: &[Bounds],
    k: usize,
    (x, n, behind): (Vec3A, Option<Vec3A>, Option<Behind>),
    seen: Option<Seen>,
) -> f32 {
    unit_importance(&bounds[k], x, n, behind) * seen.map_or(1.0, |s| s.units[k])
}

/// A unit's bounds for the light tree; `None` for a unit without a position.
fn light_bounds(b: &Bounds) -> Option<LightBounds> {
    let at = |p: Vec3A, phi: f32| LightBounds {
        lo: p,
        hi: p,
        axis: Vec3A::Z,
        cos_o: -1.0,
        cos_e: 0.0,
        phi,
    };
    Some(match *b {
        Bounds::Area(AreaUnit {
            normal,
            corners,
            power,
            ..
        }) => LightBounds {
            lo: corners.iter().fold(Vec3A::INFINITY, |a, c| a.min(*c)),
            hi: corners.iter().fold(Vec3A::NEG_INFINITY, |a, c| a.max(*c)),
            axis: normal,
            cos_o: 1.0,
            cos_e: 0.0,
            phi: power,
        },
        Bounds::Delta(DeltaLight::Point {
            position,
            intensity,
        }) => at(position, weight_luminance(intensity)),
        Bounds::Delta(DeltaLight::Spot {
            position,
            direction,
            intensity,
            cos_cone,
            ..
        }) => LightBounds {
            axis: direction.normalize_or(Vec3A::Z),
            cos_o: if direction.length_squared() > 0.0 {
                cos_cone
            } else {
                -1.0
            },
            cos_e: 1.0,
            ..at(position, weight_luminance(intensity))
        },
        // Textured spots and projectors as if they shone everywhere (their cones are in a
        // frame that may be scaled): conservative, and their own importance decides at the leaf.
        Bounds::Delta(DeltaLight::TexturedSpot(ref s)) => {
            at(s.position, weight_luminance(s.colour()))
        }
        Bounds::Delta(DeltaLight::Projector(ref p)) => {
            at(p.position, weight_luminance(p.power()) / PI)
        }
        Bounds::Delta(DeltaLight::Directional { .. }) | Bounds::Env { .. } => return None,
    })
}
