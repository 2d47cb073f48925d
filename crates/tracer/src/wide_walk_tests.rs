use super::*;
use crate::InputTri;
use crate::accel::Accel;
use crate::isa::Baseline;
use crate::wide_bvh::Node8;
use glam::Vec3A;

/// Three uniform numbers in [0, 1) from a counter hashed with `mix64`.
pub(crate) fn p3(s: &mut u64) -> Vec3A {
    Vec3A::from([0, 1, 2].map(|_| {
        *s += 1;
        (crate::mix64(*s) >> 40) as f32 / (1u64 << 24) as f32
    }))
}

/// Random triangles (a third tiny, the rest up to 2 long) in a 20-unit cube.
pub(crate) fn soup(n: usize, seed: u64) -> Vec<InputTri> {
    let mut s = seed << 32;
    (0..n)
        .map(|k| {
            let c = p3(&mut s) * 20.0 - 10.0;
            let size = if k % 3 == 0 { 0.01 } else { 2.0 };
            let mut e = || (p3(&mut s) - 0.5) * size;
            InputTri {
                v: [c, c + e(), c + e()],
                instance: 0,
                prim: k as u32,
            }
        })
        .collect()
}

/// Rays from around the soup, a third aimed at one of its triangles, some along the axes or
/// with a −0 component, half of them with a finite end.
fn rays(tris: &[InputTri], n: usize) -> Vec<Ray> {
    let mut s = 23u64 << 32;
    (0..n)
        .map(|k| {
            let o = p3(&mut s) * 30.0 - 15.0;
            let mut d = if k % 3 == 0 {
                (tris[k * 7 % tris.len()].v[0] - o).normalize()
            } else {
                (p3(&mut s) - 0.5).normalize()
            };
            match k % 7 {
                0 => d = Vec3A::new(0.0, -0.0, 1.0),
                1 => d.x = -0.0,
                _ => {}
            }
            let d = d.normalize();
            let tmax = if k % 2 == 0 { f32::INFINITY } else { 9.0 };
            Ray::new(o, d, 0.0, tmax)
        })
        .collect()
}

#[test]
fn avx2_box_test_gives_the_baseline_masks_and_distances_bit_for_bit() {
    let Some(wide) = crate::isa::avx2() else {
        eprintln!("no AVX2 on this CPU: nothing to compare");
        return;
    };
    let tris = soup(3000, 7);
    let accel = Accel::build(&tris);
    let (mut compared, mut entered) = (0, 0);
    for ray in rays(&tris, 3000) {
        let slab = Slab::new(&ray);
        for node in &accel.wide().nodes {
            let (a, na) = Baseline.node8(node, &slab, ray.tmax);
            let (b, nb) = wide.node8(node, &slab, ray.tmax);
            assert_eq!(a, b);
            assert_eq!(na.map(f32::to_bits), nb.map(f32::to_bits));
            compared += 1;
            entered += a.count_ones();
        }
    }
    assert!(
        compared > 1_000_000 && entered > 20_000,
        "{compared} {entered}"
    );
}

/// The box of child `c` of `node`, as (min, max).
fn child_box(node: &Node8, c: usize) -> (Vec3A, Vec3A) {
    let p = |r: usize| node.planes[r][c];
    (Vec3A::new(p(0), p(2), p(4)), Vec3A::new(p(1), p(3), p(5)))
}

#[test]
fn every_triangle_lies_in_the_box_of_each_child_on_its_way_from_the_root() {
    // (What a walk needs is that no box on the way cuts a triangle off; each leaf is one
    // block of four slots.)
    let tris = soup(5000, 9);
    let accel = Accel::build(&tris);
    let nodes = &accel.wide().nodes;
    let all = (Vec3A::NEG_INFINITY, Vec3A::INFINITY);
    let (mut todo, mut triangles, mut empty) = (vec![(0u32, all)], 0, 0);
    while let Some((n, (lo, hi))) = todo.pop() {
        let node = &nodes[n as usize];
        for c in 0..8 {
            let (l, h) = child_box(node, c);
            let (l, h) = (l.max(lo), h.min(hi));
            if node.leaves >> c & 1 == 1 {
                let mut slots = node.child[c];
                assert!(slots != 0 && slots >> (slots.trailing_zeros() & !3) < 16);
                while slots != 0 {
                    let slot = node.prim_base + slots.trailing_zeros();
                    slots &= slots - 1;
                    let within = |p: Vec3A| p.cmpge(l).all() && p.cmple(h).all();
                    assert!(accel.vertices(slot).into_iter().all(within), "slot {slot}");
                    triangles += 1;
                }
            } else if node.child[c] != 0 {
                todo.push((node.child[c], (l, h)));
            } else {
                let (l, h) = child_box(node, c);
                assert!(
                    l.x == f32::INFINITY && h.x == f32::NEG_INFINITY,
                    "empty child"
                );
                empty += 1;
            }
        }
    }
    assert_eq!(triangles, accel.triangle_count());
    assert!(empty > 0 && nodes.len() > 100, "{empty} {}", nodes.len());
}

#[test]
fn a_deep_structure_grows_the_stack_and_still_finds_every_closest_hit() {
    // Nested shells of ever smaller triangles around one point: a deep tree, and rays through
    // the middle enter many children at every level.
    let mut tris = Vec::new();
    let mut s = 5u64 << 32;
    for level in 0..24 {
        let r = 8.0 * 0.6f32.powi(level);
        for k in 0..64 {
            let c = (p3(&mut s) - 0.5).normalize() * r;
            let e = (p3(&mut s) - 0.5) * r * 0.3;
            let f = (p3(&mut s) - 0.5) * r * 0.3;
            tris.push(InputTri {
                v: [c, c + e, c + f],
                instance: 0,
                prim: (level * 64 + k) as u32,
            });
        }
    }
    let accel = Accel::build(&tris);
    let mut stack = WalkStack::default();
    let mut hits = 0;
    for ray in rays(&tris, 2000) {
        let ray = Ray::new(ray.origin * 0.01, ray.direction, 0.0, ray.tmax);
        let got = accel.closest(&ray, &mut stack);
        // Every hit the exhaustive walk reports (it never shortens the ray, so it never
        // prunes), nearest of them: what ordering and pruning must not lose.
        let every = {
            let mut best = f32::INFINITY;
            accel.each_hit_with(Baseline, &ray, &mut WalkStack::default(), &mut |h| {
                best = best.min(h.t);
                false
            });
            best
        };
        assert_eq!(
            got.map(|h| h.t.to_bits()),
            every.is_finite().then(|| every.to_bits())
        );
        hits += got.is_some() as u32;
    }
    assert!(
        stack.entries.len() > 16,
        "the stack grew to {}",
        stack.entries.len()
    );
    assert!(hits > 300, "{hits}");
}

#[test]
fn a_negative_zero_direction_component_still_hits() {
    // A wall of triangles at z = 5 + 0.01 i in front of rays whose x component is ±0 (1/d is
    // then ∓ a large number, and the near plane must follow its sign).
    let tris: Vec<InputTri> = (0..64)
        .map(|i| {
            let (x, z) = (i as f32 * 0.25 - 8.0, 5.0 + 0.01 * i as f32);
            InputTri {
                v: [
                    Vec3A::new(x, -1.0, z),
                    Vec3A::new(x + 0.25, -1.0, z),
                    Vec3A::new(x, 1.0, z),
                ],
                instance: 0,
                prim: i,
            }
        })
        .collect();
    let accel = Accel::build(&tris);
    for dx in [0.0f32, -0.0] {
        let ray = Ray::new(
            Vec3A::new(0.1, -0.5, 0.0),
            Vec3A::new(dx, 0.0, 1.0),
            0.0,
            100.0,
        );
        let t = accel.closest(&ray, &mut WalkStack::default()).map(|h| h.t);
        assert!(
            (t.unwrap_or(f32::INFINITY) - 5.32).abs() < 1e-4,
            "dx = {dx:?}: {t:?}"
        );
        assert!(!accel.unblocked(&ray, &mut WalkStack::default()));
    }
}

/// A structure past `PREFETCH_MIN_BYTES` of nodes is walked with the prefetching node test; its
/// closest hits, shadow answers and paired walks are those of the same nodes walked without.
#[test]
fn prefetching_walks_answer_what_plain_walks_do() {
    let tris = soup(30_000, 9);
    let fetching = Accel::build(&tris);
    assert!(fetching.wide().prefetch, "{} nodes", fetching.nodes().len());
    let plain = Accel::build(&tris).without_prefetch();
    let key = |h: Option<crate::accel::SlotHit>| h.map(|h| (h.t.to_bits(), h.slot));
    let (mut a, mut b) = (WalkStack::default(), WalkStack::default());
    let (mut hits, mut blocked) = (0, 0);
    for ray in rays(&tris, 3000) {
        let shadow = Ray::new(ray.origin, -ray.direction, 0.0, 6.0);
        let got = fetching.closest(&ray, &mut a);
        assert_eq!(key(got), key(plain.closest(&ray, &mut b)));
        let free = fetching.unblocked(&shadow, &mut a);
        assert_eq!(free, plain.unblocked(&shadow, &mut b));
        let (mut c, mut d) = (WalkStack::default(), WalkStack::default());
        let (pair_hit, pair_free) =
            fetching.closest_and_unblocked_with(Baseline, (&ray, &mut c), (&shadow, &mut d));
        assert_eq!((key(pair_hit), pair_free), (key(got), free));
        #[cfg(target_arch = "x86_64")]
        if let Some(wide) = crate::isa::avx2() {
            assert_eq!(key(fetching.closest_with(wide, &ray, &mut a)), key(got));
            assert_eq!(fetching.unblocked_with(wide, &shadow, &mut a), free);
        }
        hits += got.is_some() as u32;
        blocked += !free as u32;
    }
    assert!((300..2700).contains(&hits), "{hits} hits");
    assert!((300..2700).contains(&blocked), "{blocked} blocked");
}
