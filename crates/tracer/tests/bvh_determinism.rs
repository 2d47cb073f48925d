//! The BVH is part of what makes a render's bits: obvhs builds it in parallel (rayon joins,
//! chunks sized by `current_num_threads`, rdst radix sorts) and the tracer collapses it to
//! eight-wide nodes in parallel (`collapse.rs`: rayon joins and one task per subtree below
//! its first nodes), so the node array and the
//! triangle order must come out identical for any thread count, with every preset the
//! renderer may pick (`build_params`).
use eyeadapt_tracer::{Accel, BvhBuildParams, InputTri, build_params};
use glam::Vec3A;

/// A k×k grid (2k² triangles) that is bumpy on one side and exactly flat on the other, plus an
/// exact copy of every 97th triangle: the flat part gives many boxes of the same area and the
/// copies identical Morton codes, so the builder's sorts meet ties, where an unstable or
/// thread-dependent order would show.
fn grid(k: usize) -> Vec<InputTri> {
    let p = |i: usize, j: usize| {
        let (x, z) = (i as f32 / k as f32, j as f32 / k as f32);
        let y = if x < 0.3 {
            0.0
        } else {
            0.1 * libm::sinf(9.0 * x) * libm::cosf(7.0 * z)
        };
        Vec3A::new(x, y, z)
    };
    let mut out = Vec::new();
    for j in 0..k {
        for i in 0..k {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for v in [[a, c, b], [a, d, c]] {
                let copies = if out.len() % 97 == 0 { 2 } else { 1 };
                for _ in 0..copies {
                    out.push(InputTri {
                        v,
                        instance: (i % 3) as u32,
                        prim: out.len() as u32,
                    });
                }
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

/// FNV-1a over the nodes' and the slots' ids: a short name for a tree in a failure message.
fn tree_hash(a: &Accel) -> u64 {
    let nodes = a.nodes().iter().map(|n| format!("{n:?}"));
    let prims = a.info.iter().map(|i| format!("{} {}", i.instance, i.prim));
    nodes
        .chain(prims)
        .flat_map(String::into_bytes)
        .fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
        })
}

/// Builds `tris` with `params` on 1, 2 and 8 threads and asserts the same nodes, the same
/// primitive order and the same per-slot shading data.
fn assert_identical(name: &str, tris: &[InputTri], params: BvhBuildParams) {
    let one = build_in_pool(1, tris, params);
    assert!(one.nodes().len() > 1000, "{name}: a real tree");
    for threads in [2, 8] {
        let other = build_in_pool(threads, tris, params);
        assert!(
            one.nodes() == other.nodes(),
            "{name}: the tree differs between 1 and {threads} threads (hash {:016x} vs {:016x})",
            tree_hash(&one),
            tree_hash(&other)
        );
        let ids = |a: &Accel| {
            a.info
                .iter()
                .map(|i| (i.instance, i.prim))
                .collect::<Vec<_>>()
        };
        assert_eq!(ids(&one), ids(&other), "{name}: slot ids");
    }
}

#[test]
fn builds_are_identical_on_any_thread_count() {
    let tris = grid(225); // 101 250 triangles + 1 044 copies
    for (name, params) in [
        ("fastest", BvhBuildParams::fastest_build()),
        ("very_fast", BvhBuildParams::very_fast_build()),
        ("fast", BvhBuildParams::fast_build()),
        ("medium", BvhBuildParams::medium_build()),
    ] {
        assert_identical(name, &tris, params);
    }
}

/// At 1M triangles obvhs takes code paths that 100k does not reach (its PLOC cost pass goes
/// parallel from 300k clusters, rdst switches sort algorithms with the input size), so the
/// preset the renderer uses at that size is checked there too: about 3 s in release, where it
/// runs by default; with debug assertions obvhs validates every tree, so there it is opt-in
/// (`-- --ignored`).
#[test]
#[cfg_attr(debug_assertions, ignore = "1M triangles: runs in release builds")]
fn builds_of_a_million_triangles_are_identical_on_any_thread_count() {
    let tris = grid(700); // 980 000 triangles + 10 104 copies
    assert_identical("renderer's preset at 1M", &tris, build_params(tris.len()));
}
