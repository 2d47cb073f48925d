//! Which lights can be seen from where: a grid over the scene's bounds that holds, for each
//! cell and each unit of the direct light choice ([`crate::light_pick`]), the share of shadow
//! rays from points of the cell to points of the unit that arrive. The spatial light choice
//! multiplies each unit's importance by [`FLOOR`] + (1 − [`FLOOR`]) × that share, so that in a
//! house of rooms a shading point stops spending shadow rays on the light behind the wall,
//! which its distance alone made important. With a light tree (17 to
//! [`crate::light_pick::VISIBILITY_MAX_UNITS`] units) each subtree is weighed by the largest
//! factor of its lights, and each light at the leaves by its own.
//!
//! **Unbiased by construction.** A factor is never 0, so every unit that could be chosen at a
//! point still can, with the same probability in [`crate::lights::LightSet::sample`] and in the
//! densities MIS asks for (both read the same factors); only the variance changes. A cell whose
//! points see nothing (inside a wall) gives every unit [`FLOOR`], which leaves the choice as it
//! was; a unit no point of a cell could sample (behind its one-sided emitter) keeps factor 1.
//!
//! **Deterministic.** The grid is built once per scene, before any frame, from points and light
//! samples of the tracer's own Owen-scrambled Sobol stream keyed by the cell: the same scene
//! gives the same factors on any number of threads.
//!
//! **Cost.** Cubic cells, at most [`MAX_CELLS_PER_SIDE`] along the scene's longest side and
//! fewer where [`POINTS`] × units × cells would pass [`RAY_BUDGET`] shadow rays, traced in
//! parallel: 9–25 ms of a process on the built-in interiors, nothing per sample but a cell
//! lookup and a multiplication per unit (BENCHMARKS.md).
use crate::geometry::RayScratch;
use crate::sampler::{SampleStream, hash_key};
use crate::scene_data::SceneData;
use crate::shadow::shadow_transmittance;
use glam::Vec3A;
use rayon::prelude::*;

/// The smallest factor: the share of its importance a unit keeps in a cell that sees none of it.
pub const FLOOR: f32 = 0.1;

/// Points per cell.
const POINTS: u32 = 8;

/// Most cells along the scene's longest side.
const MAX_CELLS_PER_SIDE: f32 = 48.0;

/// Most shadow rays the build traces (points × units over all cells).
const RAY_BUDGET: f32 = 400_000.0;

/// The grid of per-cell factors.
#[derive(Clone, Debug)]
pub struct Visibility {
    lo: Vec3A,
    /// 1 / the cells' side.
    inv_side: f32,
    dims: [u32; 3],
    /// `dims` as `f32` (exact: at most [`MAX_CELLS_PER_SIDE`] each).
    dims_f: Vec3A,
    units: usize,
    /// `units` factors per cell, cells in x-fastest order.
    factors: Vec<f32>,
}

impl Visibility {
    /// The grid of `scene`'s light choice, or `None` where the choice does not depend on the
    /// shading point or has too many units for a grid ([`crate::light_pick`]).
    pub fn build(scene: &SceneData) -> Option<Visibility> {
        let lights = &scene.lights;
        let units = lights.unit_count();
        if !lights.takes_visibility() {
            return None;
        }
        let lo = scene.geometry.bounds_min;
        let size = scene.geometry.bounds_max - lo;
        if !(lo.is_finite() && size.is_finite() && size.max_element() > 0.0) {
            return None; // no geometry: nothing to hide a light
        }
        let size = size.max(Vec3A::splat(size.max_element() * 1e-6));
        let (side, dims) = cells_for(size, RAY_BUDGET / (POINTS as f32 * units as f32));
        let cells = dims.iter().map(|&d| d as usize).product::<usize>();
        let factors: Vec<f32> = (0..cells)
            .into_par_iter()
            .map_init(
                || scene.geometry.scratch(),
                |scratch, c| cell_factors(scene, scratch, (lo, side, dims), c),
            )
            .flatten_iter()
            .collect();
        Some(Visibility {
            lo,
            inv_side: 1.0 / side,
            dims,
            dims_f: Vec3A::from_array(dims.map(|d| d as f32)),
            units,
            factors,
        })
    }

    /// The factors of the cell holding `x` (none outside the grid).
    #[inline]
    pub fn at(&self, x: Vec3A) -> Option<&[f32]> {
        self.cell(x).map(|c| self.of_cell(c))
    }

    /// The factors of cell `c`, one per unit.
    #[inline]
    pub fn of_cell(&self, c: usize) -> &[f32] {
        &self.factors[c * self.units..(c + 1) * self.units]
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.factors.len() / self.units
    }

    /// The cell holding `x` (none outside the grid).
    #[inline]
    pub fn cell(&self, x: Vec3A) -> Option<usize> {
        let v = (x - self.lo) * self.inv_side;
        // Every coordinate in [0, its number of cells) (no NaN): its floor is its truncation,
        // and the general test below would find the same cell. Most points take this path.
        if (v.cmpge(Vec3A::ZERO) & v.cmplt(self.dims_f)).all() {
            let [i, j, k] = truncate(v);
            let [nx, ny, _] = self.dims;
            return Some(((k * ny + j) * nx + i) as usize);
        }
        self.cell_of(v)
    }

    /// [`Visibility::cell`] for any cell coordinates `v` (NaN, negative, past the grid).
    #[cold]
    fn cell_of(&self, v: Vec3A) -> Option<usize> {
        let c = v.floor();
        if c.min_element() < 0.0 {
            return None;
        }
        let [i, j, k] = c.to_array().map(|v| v as u32);
        let [nx, ny, nz] = self.dims;
        if i >= nx || j >= ny || k >= nz {
            return None;
        }
        Some(((k * ny + j) * nx + i) as usize)
    }
}

/// `v`'s coordinates truncated towards zero, for coordinates in [0, 2³¹).
#[inline(always)]
fn truncate(v: Vec3A) -> [u32; 3] {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__m128i, _mm_cvttps_epi32};
        // SAFETY: SSE2 (and so cvttps2dq) is part of the x86_64 baseline; an __m128i is
        // four i32s.
        let t = unsafe { std::mem::transmute::<__m128i, [i32; 4]>(_mm_cvttps_epi32(v.into())) };
        [t[0] as u32, t[1] as u32, t[2] as u32]
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        v.to_array().map(|c| c as u32)
    }
}

/// The cells' side and the grid's size over a box of `size`: cubes, at most
/// [`MAX_CELLS_PER_SIDE`] along the longest side and at most `max_cells` in all.
fn cells_for(size: Vec3A, max_cells: f32) -> (f32, [u32; 3]) {
    let mut side = size.max_element() / MAX_CELLS_PER_SIDE;
    loop {
        let dims = (size / side).ceil().max(Vec3A::ONE);
        let cells = dims.x * dims.y * dims.z;
        if cells <= max_cells.max(1.0) {
            return (side, dims.to_array().map(|d| d as u32));
        }
        side *= libm::cbrtf(cells / max_cells).max(1.01);
    }
}

/// Cell `c`'s factors: [`POINTS`] points of the cell, a shadow ray from each to each unit.
fn cell_factors(
    scene: &SceneData,
    scratch: &mut RayScratch,
    (lo, side, dims): (Vec3A, f32, [u32; 3]),
    c: usize,
) -> Vec<f32> {
    let lights = &scene.lights;
    let units = lights.unit_count();
    let (nx, ny) = (dims[0] as usize, dims[1] as usize);
    let corner = lo
        + Vec3A::new(
            (c % nx) as f32,
            (c / nx % ny) as f32,
            (c / (nx * ny)) as f32,
        ) * side;
    let key = hash_key(&[0x7669_7369_6269_6c74, c as u64]);
    let (mut tried, mut free) = (vec![0u32; units], vec![0u32; units]);
    for i in 0..POINTS {
        let mut s = SampleStream::new(key, i);
        let [a, b, d, _] = s.next_4d();
        let x = corner + Vec3A::new(a, b, d) * side;
        for k in 0..units {
            let Some(ls) = lights.sample_unit(k, 1.0, x, s.next_2d()) else {
                continue;
            };
            if ls.li.max_element() <= 0.0 {
                continue;
            }
            tried[k] += 1;
            let tr = shadow_transmittance(scene, scratch, x, ls.wi, ls.dist);
            free[k] += (tr.max_element() > 0.0) as u32;
        }
    }
    tried
        .iter()
        .zip(&free)
        .map(|(&t, &f)| {
            if t == 0 {
                1.0
            } else {
                FLOOR + (1.0 - FLOOR) * f as f32 / t as f32
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn three_rooms() -> SceneData {
        SceneData::new(&eyeadapt_scene::load_builtin("three-rooms").unwrap())
    }

    /// Unit `k`'s colour as seen from `x` (which of the three rooms' lights it is).
    fn is_white(scene: &SceneData, k: usize, x: Vec3A) -> bool {
        let li = (0..16u32)
            .filter_map(|i| {
                scene
                    .lights
                    .sample_unit(k, 1.0, x, [0.3 + i as f32 / 40.0, 0.5])
            })
            .map(|ls| ls.li)
            .next()
            .unwrap();
        (li.x - li.z).abs() < 1e-3 * li.max_element()
    }

    #[test]
    fn the_quick_cell_lookup_finds_the_general_one_s_cell() {
        let vis = Visibility {
            lo: Vec3A::new(-3.1, -0.05, -10.2),
            inv_side: 1.0 / 0.37,
            dims: [17, 8, 29],
            dims_f: Vec3A::new(17.0, 8.0, 29.0),
            units: 1,
            factors: vec![1.0; 17 * 8 * 29],
        };
        let hi = vis.lo + vis.dims_f / vis.inv_side;
        let mut f = 0.4142f32;
        let mut next = move || {
            f = (f * 89.17 + 0.31).fract();
            f
        };
        let mut points: Vec<Vec3A> = (0..20_000)
            .map(|_| vis.lo - 1.0 + (hi - vis.lo + 2.0) * Vec3A::new(next(), next(), next()))
            .collect();
        // The grid's faces, a hair either side, and what no grid holds.
        for c in [vis.lo, hi] {
            for d in [-1e-6, 0.0, 1e-6] {
                points.push(c + d);
                points.push(Vec3A::new(c.x + d, 0.3, -4.0));
            }
        }
        for odd in [f32::NAN, f32::INFINITY, -f32::INFINITY, -0.0, 1e30, -1e30] {
            points.push(Vec3A::new(odd, 0.3, -4.0));
            points.push(Vec3A::new(0.1, 0.3, odd));
        }
        let mut inside = 0;
        for x in points {
            let general = vis.cell_of((x - vis.lo) * vis.inv_side);
            assert_eq!(vis.cell(x), general, "{x}");
            inside += general.is_some() as u32;
        }
        assert!(inside > 5_000, "{inside} points inside");
    }

    #[test]
    fn a_room_sees_its_own_light_and_not_the_lights_behind_its_walls() {
        let scene = three_rooms();
        let vis = Visibility::build(&scene).expect("three lights: a spatial choice");
        assert_eq!(vis.units, 3);
        // Room 1 beside its partition wall (z = -5), out of the doorway's sight lines (|x| <
        // 0.6): only its white light is seen.
        let x = Vec3A::new(-1.7, 1.0, -4.6);
        let f = vis.at(x).unwrap();
        for (k, &fk) in f.iter().enumerate() {
            assert!((FLOOR..=1.0).contains(&fk), "factor {fk}");
            if is_white(&scene, k, x) {
                assert!(fk > 0.9, "room 1's own light: {fk}");
            } else {
                assert!(fk < 0.2, "a light behind room 1's walls: {fk}");
            }
        }
        assert_eq!(f.iter().filter(|&&fk| fk > 0.9).count(), 1);
        // Outside the scene's bounds there is nothing to say.
        assert!(vis.at(Vec3A::new(0.0, 50.0, 0.0)).is_none());
        assert!(vis.at(Vec3A::new(0.0, -50.0, 0.0)).is_none());
        // Every factor lies in [FLOOR, 1], and some cells see no light at all (in the walls).
        assert!(vis.factors.iter().all(|f| (FLOOR..=1.0).contains(f)));
        assert!(vis.factors.chunks(3).any(|c| c.iter().all(|&f| f == FLOOR)));
    }

    /// Three rooms with 18 point lights more in room 3: 21 units, so a light tree.
    fn rooms_and_tree() -> SceneData {
        let mut s = eyeadapt_scene::load_builtin("three-rooms").unwrap();
        for k in 0..18 {
            s.lights.push(eyeadapt_scene::Light::Point {
                position: glam::Vec3::new(-1.5 + 0.18 * k as f32, 2.5, -12.5),
                intensity: eyeadapt_scene::Rgb::splat(1.0),
            });
        }
        SceneData::new(&s)
    }

    #[test]
    fn everywhere_the_probabilities_sum_to_one_and_picks_report_them_exactly() {
        for scene in [three_rooms(), rooms_and_tree()] {
            let lights = &scene.lights;
            let units = lights.unit_count();
            let (lo, hi) = (scene.geometry.bounds_min, scene.geometry.bounds_max);
            let key = hash_key(&[0x5eed]);
            let mut inside = 0;
            for i in 0..300 {
                let mut s = SampleStream::new(key, i);
                let [a, b, c, d] = s.next_4d();
                // The bounds and a fifth beyond them on every side (outside the grid).
                let x = lo + (hi - lo) * (Vec3A::new(a, b, c) * 1.4 - 0.2);
                let [e, f] = s.next_2d();
                let n = (d < 0.8).then(|| {
                    let z = 1.0 - 2.0 * e;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let (sin, cos) = crate::trig::sincos_turns(f);
                    Vec3A::new(r * cos, r * sin, z)
                });
                let probs: Vec<f32> = (0..units).map(|k| lights.picker_prob(k, x, n)).collect();
                let sum: f32 = probs.iter().sum();
                // The direct choice sums to 1 wherever a light reaches; a tree's walk may end
                // in a subtree whose bounds reach `x` but none of whose lights do (it then
                // chooses none), with or without the grid.
                let whole = sum == 0.0 || (sum - 1.0).abs() < 1e-4;
                assert!(
                    whole || (units > 16 && sum < 1.0),
                    "{units} units at {x}: probabilities sum to {sum}"
                );
                for j in 0..16 {
                    match lights.picker_pick(x, n, (j as f32 + 0.5) / 16.0) {
                        Some((k, p)) => assert_eq!(p.to_bits(), probs[k].to_bits()),
                        None => assert!(sum == 0.0 || (units > 16 && sum < 1.0), "{sum}"),
                    }
                }
                let v = lights.picker_visibility();
                inside += v.is_some_and(|v| v.cell(x).is_some()) as u32;
            }
            assert!(
                inside > 50 && inside < 250,
                "{inside} of 300 points in the grid"
            );
        }
    }

    #[test]
    fn with_a_light_tree_the_lights_behind_the_walls_lose_their_share() {
        let mut scene = rooms_and_tree();
        assert_eq!(scene.lights.unit_count(), 21);
        let x = Vec3A::new(-1.7, 1.0, -4.6);
        let n = Some(Vec3A::Y);
        let room3 = |lights: &crate::lights::LightSet| -> f32 {
            (3..21).map(|k| lights.picker_prob(k, x, n)).sum()
        };
        let (with, total) = (
            room3(&scene.lights),
            (0..21)
                .map(|k| scene.lights.picker_prob(k, x, n))
                .sum::<f32>(),
        );
        assert!((total - 1.0).abs() < 1e-5, "{total}");
        // Frequencies of the choice follow its probabilities.
        let m = 20_000;
        let mut hits = 0;
        for i in 0..m {
            let (k, p) = scene
                .lights
                .picker_pick(x, n, (i as f32 + 0.5) / m as f32)
                .unwrap();
            assert_eq!(p.to_bits(), scene.lights.picker_prob(k, x, n).to_bits());
            hits += (k >= 3) as u32;
        }
        assert!((hits as f32 / m as f32 - with).abs() < 2e-3);
        scene.lights.set_visibility(None);
        let without = room3(&scene.lights);
        assert!(
            with < 0.5 * without,
            "room 3's share: {with} with the grid, {without} without"
        );
    }

    #[test]
    fn a_scene_without_geometry_or_with_one_light_has_no_grid() {
        let mut s = eyeadapt_scene::Scene {
            environment: Some(eyeadapt_scene::Rgb::splat(0.5)),
            ..Default::default()
        };
        s.lights.push(eyeadapt_scene::Light::Directional {
            direction: glam::Vec3::new(0.2, -1.0, 0.1),
            irradiance: eyeadapt_scene::Rgb::splat(3.0),
        });
        let scene = SceneData::new(&s);
        assert_eq!(scene.lights.unit_count(), 2);
        assert!(Visibility::build(&scene).is_none());
        let cornell = SceneData::new(&eyeadapt_scene::load_builtin("cornell-box").unwrap());
        assert_eq!(cornell.lights.unit_count(), 1);
        assert!(Visibility::build(&cornell).is_none());
    }

    #[test]
    fn the_grid_is_the_same_on_any_number_of_threads() {
        let scene = three_rooms();
        let on = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| Visibility::build(&scene).unwrap())
        };
        let (one, three) = (on(1), on(3));
        assert_eq!(one.dims, three.dims);
        let bits = |v: &Visibility| v.factors.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&one), bits(&three));
    }

    #[test]
    fn the_choice_follows_the_factors_and_its_probabilities_stay_exact() {
        let scene = three_rooms();
        let lights = &scene.lights;
        let mut blind = three_rooms();
        blind.lights.set_visibility(None);
        let vis = lights.picker_visibility().unwrap();
        // Near the doorway of room 1, where the orange light is partly seen, and in the room.
        for x in [Vec3A::new(0.2, 1.0, -4.6), Vec3A::new(-1.2, 1.2, -2.0)] {
            let n = Some(Vec3A::Y);
            let probs: Vec<f32> = (0..3).map(|k| lights.picker_prob(k, x, n)).collect();
            assert!((probs.iter().sum::<f32>() - 1.0).abs() < 1e-5, "{probs:?}");
            // Each probability is the grid-blind one times the cell's factor, renormalised.
            let f = vis.at(x).unwrap();
            let weighed: Vec<f32> = (0..3)
                .map(|k| blind.lights.picker_prob(k, x, n) * f[k])
                .collect();
            let total: f32 = weighed.iter().sum();
            for k in 0..3 {
                assert!(
                    (probs[k] - weighed[k] / total).abs() < 1e-5,
                    "unit {k}: {} against {} (factors {f:?})",
                    probs[k],
                    weighed[k] / total
                );
            }
            assert!(
                f.iter().any(|&fk| fk < 0.99),
                "the grid changes nothing here: {f:?}"
            );
            let mut counts = [0u32; 3];
            let m = 20_000;
            for i in 0..m {
                let u = (i as f32 + 0.5) / m as f32;
                let (k, p) = lights.picker_pick(x, n, u).unwrap();
                assert_eq!(p.to_bits(), probs[k].to_bits());
                counts[k] += 1;
            }
            for k in 0..3 {
                let share = counts[k] as f32 / m as f32;
                assert!(
                    (share - probs[k]).abs() < 1e-3,
                    "{share} against {}",
                    probs[k]
                );
            }
        }
    }
}
