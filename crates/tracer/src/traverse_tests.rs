//! Tests of the node test: its hit masks (byte planes, float planes, per-child words) against
//! obvhs's, bit for bit, on random rays and real nodes; a −0.0 direction component; the
//! per-node tables (bit counts, child words).
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
            let sel = ChildSelect::new(ray.direction);
            assert_eq!(sel.oct_inv4, oct);
            let float = node_hits_float(&FloatPlanes::of(node), sel, &ray);
            differ += (float != a) as u32;
            differ += (node_hits_words(node, &ChildWords::of(node), sel, &ray) != a) as u32;
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

#[test]
fn child_words_of_leaves_inner_and_empty_children() {
    // Leaves of 2 slots at 0, 3 slots at 2 and 1 slot at 23; inner children in slots 3
    // and 6 (meta 24 + slot); empty slots 5 and 7.
    let node = CwBvhNode {
        child_meta: [
            0b0110_0000,
            0b1110_0010,
            0b0010_0000 | 23,
            24 + 3,
            0,
            0,
            24 + 6,
            0,
        ],
        ..Default::default()
    };
    let w = ChildWords::of(&node).w;
    assert_eq!(
        w,
        [0b11, 0b11100, 1 << 23, 0xff00_0000, 0, 0, 0xff00_0000, 0]
    );
    // A ray with all direction components negative has oct_inv4 0: inner child c keeps
    // bit 24 + c; all positive: 7, so bit 24 + (c ^ 7).
    let neg = ChildSelect::new(Vec3A::new(-1.0, -1.0, -1.0));
    let pos = ChildSelect::new(Vec3A::new(1.0, 1.0, 1.0));
    assert_eq!((neg.oct_inv4, pos.oct_inv4), (0, 0x0707_0707));
    assert_eq!(w[3] & neg.w[3], 1 << 27);
    assert_eq!(w[6] & pos.w[6], 1 << 25);
    assert_eq!(w[2] & pos.w[2], 1 << 23);
}

fn obvhs_octant(bvh: &CwBvh, ray: &Ray) -> u32 {
    bvh.new_traversal(ray.direction).oct_inv4
}
