//! Tests of the CWBVH node test: its hit masks against obvhs's, bit for bit, on random rays
//! and real nodes; a −0.0 direction component; the bit-count table.
use super::*;
use crate::sampler::mix64;
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::rt_triangle::RtTriangle;
use obvhs::triangle::Triangle;
use std::time::Duration;

fn unit(r: u64) -> f32 {
    (r >> 40) as f32 / (1u64 << 24) as f32
}

#[test]
fn node_test_equals_obvhs_bit_for_bit() {
    // A bumpy grid plus a few huge and tiny triangles, so nodes of every scale occur.
    let mut tris = Vec::new();
    for j in 0..40 {
        for i in 0..40 {
            let p = |a: usize, b: usize| {
                let (x, z) = (a as f32 * 0.1, b as f32 * 0.1);
                Vec3A::new(x, 0.2 * libm::sinf(3.0 * x) * libm::cosf(2.0 * z), z)
            };
            tris.push(Triangle {
                v0: p(i, j),
                v1: p(i + 1, j),
                v2: p(i + 1, j + 1),
            });
            tris.push(Triangle {
                v0: p(i, j),
                v1: p(i + 1, j + 1),
                v2: p(i, j + 1),
            });
        }
    }
    tris.push(Triangle {
        v0: Vec3A::new(-50.0, 3.0, -50.0),
        v1: Vec3A::new(50.0, 3.0, -50.0),
        v2: Vec3A::new(0.0, 3.0, 80.0),
    });
    let bvh = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let mut differ = 0;
    let mut hits = 0;
    for k in 0..20_000u64 {
        let r = mix64(k);
        let o = Vec3A::new(
            unit(r) * 6.0 - 1.0,
            unit(mix64(r)) * 4.0 - 1.0,
            unit(mix64(r ^ 7)) * 6.0 - 1.0,
        );
        let mut d = Vec3A::new(
            unit(mix64(r ^ 1)) - 0.5,
            unit(mix64(r ^ 2)) - 0.5,
            unit(mix64(r ^ 3)) - 0.5,
        );
        // Some rays exactly along an axis (a zero direction component).
        if k % 7 == 0 {
            d.x = 0.0;
        }
        let tmax = if k % 3 == 0 { f32::INFINITY } else { 2.0 };
        let ray = Ray::new(o, d.normalize(), 0.0, tmax);
        let oct = obvhs_octant(&bvh, &ray);
        for node in &bvh.nodes {
            let a = node_hits(node, &ray, oct);
            let b = node.intersect_ray(&ray, oct);
            differ += (a != b) as u32;
            hits += (a != 0) as u32;
        }
    }
    assert_eq!(differ, 0);
    assert!(hits > 10_000, "the rays must actually enter nodes ({hits})");
}

#[test]
fn a_negative_zero_direction_component_still_hits() {
    // A wall of triangles at z = 5 in front of a ray whose x component is −0.0.
    let mut tris = Vec::new();
    for i in 0..64 {
        let x = i as f32 * 0.25 - 8.0;
        tris.push(Triangle {
            v0: Vec3A::new(x, -1.0, 5.0 + 0.01 * i as f32),
            v1: Vec3A::new(x + 0.25, -1.0, 5.0 + 0.01 * i as f32),
            v2: Vec3A::new(x, 1.0, 5.0 + 0.01 * i as f32),
        });
    }
    let bvh = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let rt: Vec<RtTriangle> = bvh
        .primitive_indices
        .iter()
        .map(|&i| RtTriangle::from(&tris[i as usize]))
        .collect();
    for dx in [0.0f32, -0.0] {
        let ray = Ray::new(
            Vec3A::new(0.1, -0.5, 0.0),
            Vec3A::new(dx, 0.0, 1.0),
            0.0,
            100.0,
        );
        let hit = closest_hit(
            &bvh,
            crate::isa::Baseline,
            ray,
            &mut Traversal::default(),
            |i, r| rt[i as usize].intersect(r),
        );
        let t = hit.map(|h| h.t).unwrap_or(f32::INFINITY);
        assert!((t - 5.32).abs() < 1e-4, "dx = {dx:?}: t = {t}");
    }
}

#[test]
fn ones_counts_the_bits_of_every_byte() {
    for b in 0..256u32 {
        assert_eq!(ONES[b as usize] as u32, b.count_ones(), "{b:#010b}");
    }
}

fn obvhs_octant(bvh: &CwBvh, ray: &Ray) -> u32 {
    bvh.new_traversal(ray.direction).oct_inv4
}
