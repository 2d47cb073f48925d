use super::*;
use crate::accel::Accel;
use crate::isa::Baseline;
use crate::wide_walk::WalkStack;
use crate::wide_walk::tests::{p3, soup};
use crate::{InputTri, mix64};
use glam::Vec3A;

/// A 40 × 40 grid of unit squares (two triangles each) in the plane z = 0: rays at its shared
/// edges and vertices have several triangles at exactly one distance.
fn grid() -> Vec<InputTri> {
    let mut tris = Vec::new();
    for j in 0..40 {
        for i in 0..40 {
            let p =
                |di: i32, dj: i32| Vec3A::new((i + di) as f32 - 20.0, (j + dj) as f32 - 20.0, 0.0);
            for v in [[p(0, 0), p(1, 0), p(1, 1)], [p(0, 0), p(1, 1), p(0, 1)]] {
                tris.push(InputTri {
                    v,
                    instance: 0,
                    prim: tris.len() as u32,
                });
            }
        }
    }
    tris
}

/// Packets of eight rays: coherent ones (one origin, directions through a small patch, as a
/// pixel's camera rays; every third aimed at grid points, so at shared edges and vertices) and
/// incoherent ones (eight origins, eight directions), with some finite ends and axis-aligned
/// or −0 components.
fn packets(n: usize, seed: u64) -> Vec<[Ray; 8]> {
    let mut s = seed << 32;
    (0..n)
        .map(|k| {
            let o = p3(&mut s) * 30.0 - 15.0 + Vec3A::new(0.0, 0.0, 20.0);
            let target = (p3(&mut s) - 0.5) * 30.0 * Vec3A::new(1.0, 1.0, 0.0);
            std::array::from_fn(|l| {
                let (o, mut d) = match k % 3 {
                    0 => (
                        o,
                        (target.round() + Vec3A::new(l as f32 % 3.0, 0.0, 0.0) - o),
                    ),
                    1 => (o, target + (p3(&mut s) - 0.5) * 0.05 - o),
                    _ => (p3(&mut s) * 30.0 - 15.0, p3(&mut s) - 0.5),
                };
                if (k + l) % 11 == 0 {
                    d.x = -0.0;
                }
                let tmax = if (k + l) % 5 == 0 {
                    20.0
                } else {
                    f32::INFINITY
                };
                Ray::new(o, d.normalize(), 0.0, tmax)
            })
        })
        .collect()
}

/// The packet walk on the baseline's lanes, and on AVX2's where the CPU has it (the same
/// answers, bit for bit, or the test fails).
fn closest_both(a: &Accel, rays: &[Ray; 8], active: u32) -> [Option<(u32, u32)>; 8] {
    let tmax = rays.map(|r| r.tmax);
    let bits = |h: [Option<SlotHit>; 8]| h.map(|h| h.map(|h| (h.t.to_bits(), h.slot)));
    let mut stack = PacketStack::default();
    #[cfg(target_arch = "x86_64")]
    let base = {
        let r = Rays8::<crate::lanes8::Sse2F8>::new(rays);
        bits(closest8(a, &r, tmax, active, &mut stack))
    };
    #[cfg(not(target_arch = "x86_64"))]
    let base = {
        let r = Rays8::<crate::lanes8::ScalarF8>::new(rays);
        bits(closest8(a, &r, tmax, active, &mut stack))
    };
    #[cfg(target_arch = "x86_64")]
    if crate::isa::avx2().is_some() {
        let r = Rays8::<crate::lanes8::Avx2F8>::new(rays);
        assert_eq!(bits(closest8(a, &r, tmax, active, &mut stack)), base);
    }
    base
}

/// Every lane of every packet against the ray's own walk: returns (lanes compared, lanes hit,
/// lanes that differ).
fn compare(a: &Accel, packets: &[[Ray; 8]]) -> (u32, u32, u32, u32) {
    let (mut n, mut hits, mut differ, mut ties) = (0, 0, 0, 0);
    let mut stack = WalkStack::default();
    for (k, rays) in packets.iter().enumerate() {
        let active = if k % 4 == 3 {
            mix64(k as u64) as u32 & 0xff
        } else {
            0xff
        };
        let got = closest_both(a, rays, active);
        for (l, ray) in rays.iter().enumerate() {
            if active >> l & 1 == 0 {
                assert_eq!(got[l], None, "an inactive lane has no hit");
                continue;
            }
            let alone = a.closest_with(Baseline, ray, &mut stack);
            let alone = alone.map(|h| (h.t.to_bits(), h.slot));
            n += 1;
            hits += got[l].is_some() as u32;
            if got[l] != alone {
                differ += 1;
                ties += (got[l].map(|h| h.0) == alone.map(|h| h.0)) as u32;
                // Only a tie (the same distance, another triangle) or a triangle at a box's
                // rounding edge may differ; never a hit that the ray alone misses by far.
                let (g, s) = (
                    got[l].map(|h| f32::from_bits(h.0)),
                    alone.map(|h| f32::from_bits(h.0)),
                );
                let close = match (g, s) {
                    (Some(g), Some(s)) => (g - s).abs() <= 1e-5 * g.abs().max(s.abs()),
                    _ => false,
                };
                assert!(close, "packet {k} lane {l}: {g:?} against {s:?}");
            }
        }
    }
    (n, hits, differ, ties)
}

#[test]
fn packets_find_what_each_ray_finds_alone() {
    for (name, tris) in [("soup", soup(30_000, 5)), ("grid", grid())] {
        let a = Accel::build(&tris);
        let (n, hits, differ, ties) = compare(&a, &packets(4_000, 9));
        eprintln!(
            "{name}: {hits} hits of {n} lanes, {differ} differ from the single walks, {ties} of them ties"
        );
        assert!(hits > n / 5 && hits < n, "{name}: {hits} hits of {n}");
        // Ties are common only where rays are aimed at shared edges (the grid's); other
        // differences are a box's rounding edge, rarer still.
        let limit = if name == "soup" { n / 10_000 } else { n / 5 };
        assert!(differ <= limit, "{name}: {differ} of {n} differ");
        assert!(
            (differ - ties) * 1_000 <= n,
            "{name}: {} differ and are no ties",
            differ - ties
        );
    }
}

#[test]
fn an_empty_structure_and_no_active_lane_give_no_hits() {
    let empty = Accel::build(&[]);
    let rays = packets(1, 3)[0];
    assert_eq!(closest_both(&empty, &rays, 0xff), [None; 8]);
    let a = Accel::build(&grid());
    assert_eq!(closest_both(&a, &rays, 0), [None; 8]);
}
