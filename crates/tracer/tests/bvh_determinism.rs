//! The BVH is part of what makes a render's bits: obvhs builds it in parallel, so the node
//! array and the triangle order must come out identical for any thread count, with every
//! preset the renderer uses (`build_params`: medium below 256k triangles, fast above).
use eyeadapt_tracer::{Accel, BvhBuildParams, InputTri};
use glam::Vec3A;

/// A bumpy k×k grid (2k² triangles) with a few exact duplicates of positions, so that the
/// builder meets ties in its sort keys.
fn grid(k: usize) -> Vec<InputTri> {
    let p = |i: usize, j: usize| {
        let (x, z) = (i as f32 / k as f32, j as f32 / k as f32);
        Vec3A::new(x, 0.1 * (9.0 * x).sin() * (7.0 * z).cos(), z)
    };
    let mut out = Vec::new();
    for j in 0..k {
        for i in 0..k {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for v in [[a, c, b], [a, d, c]] {
                out.push(InputTri {
                    v,
                    n: None,
                    material: (i % 3) as u32,
                    light: u32::MAX,
                });
            }
        }
    }
    out
}

fn build_in_pool(threads: usize, tris: &[InputTri], params: BvhBuildParams) -> Accel {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| Accel::build_with(tris, params))
}

#[test]
fn builds_are_identical_on_any_thread_count() {
    let tris = grid(230); // 105 800 triangles
    for (name, params) in [
        ("medium", BvhBuildParams::medium_build()),
        ("fast", BvhBuildParams::fast_build()),
    ] {
        let one = build_in_pool(1, &tris, params);
        assert!(one.bvh().nodes.len() > 1000, "{name}: a real tree");
        for threads in [2, 8] {
            let other = build_in_pool(threads, &tris, params);
            assert!(
                one.bvh().nodes == other.bvh().nodes,
                "{name}: nodes differ between 1 and {threads} threads"
            );
            assert_eq!(
                one.bvh().primitive_indices,
                other.bvh().primitive_indices,
                "{name}: triangle order differs between 1 and {threads} threads"
            );
        }
    }
}
