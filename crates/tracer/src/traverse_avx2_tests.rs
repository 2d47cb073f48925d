use super::*;
use crate::InputTri;
use crate::isa::{Baseline, NodeTest, avx2};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use std::time::Duration;

/// Three uniform numbers in [0, 1) from a counter hashed with `mix64`.
fn p3(s: &mut u64) -> [f32; 3] {
    [0, 1, 2].map(|_| {
        *s += 1;
        (crate::mix64(*s) >> 40) as f32 / (1u64 << 24) as f32
    })
}

/// A few thousand random triangles (some tiny, some long) to build real nodes from.
fn soup(n: usize) -> Vec<InputTri> {
    let mut s = 7u64 << 32;
    (0..n)
        .map(|k| {
            let c = Vec3A::from(p3(&mut s)) * 20.0 - 10.0;
            let size = if k % 3 == 0 { 0.01 } else { 2.0 };
            let e = |s: &mut u64| (Vec3A::from(p3(s)) - 0.5) * size;
            InputTri {
                v: [c, c + e(&mut s), c + e(&mut s)],
                instance: 0,
                prim: k as u32,
            }
        })
        .collect()
}

#[test]
fn avx2_node_tests_give_the_baseline_masks_bit_for_bit() {
    let Some(wide) = avx2() else {
        eprintln!("no AVX2 on this CPU: nothing to compare");
        return;
    };
    let tris = soup(3000);
    let input: Vec<_> = tris.iter().map(InputTri::triangle).collect();
    let bvh = &build_cwbvh_from_tris(
        &input,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let mut s = 11u64 << 32;
    let (mut compared, mut entered) = (0, 0);
    for k in 0..4000 {
        let o = Vec3A::from(p3(&mut s)) * 30.0 - 15.0;
        // Aimed at a triangle, so that the ray enters the nodes on the way to it.
        let target = tris[k * 7 % tris.len()].v[0];
        let mut d = (target - o).normalize();
        // Axis-parallel directions and signed zeros: 1/d is huge or infinite-clamped there.
        match k % 5 {
            0 => d = Vec3A::new(0.0, -0.0, 1.0),
            1 => d.x = -0.0,
            _ => {}
        }
        let tmax = if k % 2 == 0 { f32::INFINITY } else { 8.0 };
        let ray = Ray::new(o, d, 0.0, tmax);
        let oct = bvh.new_traversal(ray.direction).oct_inv4;
        for (i, node) in bvh.nodes.iter().enumerate() {
            let a = Baseline.meta(node, &ray, oct);
            assert_eq!(a, wide.meta(node, &ray, oct), "node {i}");
            compared += 1;
            entered += (a != 0) as usize;
        }
    }
    // The comparison means something only if many nodes are entered and many are not.
    assert!(
        entered > compared / 50 && entered < compared,
        "{entered} of {compared}"
    );
}
