//! Tests of the eight-wide walk: every light keeps a path, the walk is shallow, probabilities
//! sum to 1 where every light reaches, and the share of sample numbers `pick` sends to each
//! light is the probability `prob` reports for it (bit for bit at the chosen light).
use super::*;

/// `count` point lights of unequal power spread over a 10 m box (a fixed pseudo-random layout).
fn points(count: usize) -> Vec<LightBounds> {
    let key = crate::sampler::hash_key(&[4242]);
    (0..count as u32)
        .map(|i| {
            let mut s = crate::sampler::SampleStream::new(key, i);
            let [a, b] = s.next_2d();
            let p = Vec3A::new(a, b, s.next_1d()) * 10.0 - 5.0;
            LightBounds {
                lo: p,
                hi: p,
                axis: Vec3A::Z,
                cos_o: -1.0,
                cos_e: 0.0,
                phi: 1.0 + (i % 5) as f32,
            }
        })
        .collect()
}

/// A point light's exact importance without a receiver normal: its intensity over d².
fn exact(lights: &[LightBounds], x: Vec3A) -> impl Fn(usize, f32) -> f32 + '_ {
    move |k, _| lights[k].phi / (lights[k].lo - x).length_squared()
}

#[test]
fn every_light_keeps_a_path_and_the_walk_is_shallow() {
    for count in [1, 2, 3, 4, 5, 7, 16, 17, 27, 64, 100, 1000] {
        let lights = points(count);
        let tree = LightTree::build(&lights).unwrap();
        let depth = tree.trails.iter().map(|t| t.1).max().unwrap() as u32;
        // ⌈log₈ count⌉ steps, one more where a median split leaves a node of 2 under a
        // node that has already opened eight children; at least one step.
        let log8 = (libm::logf(count as f32) / libm::logf(8.0) - 1e-6).ceil() as u32;
        assert!(
            depth >= log8.max(1) && depth <= log8 + 1,
            "{count}: depth {depth}"
        );
        for node in &tree.nodes {
            let kids = node.child.iter().take_while(|&&c| c != u32::MAX).count();
            assert!(
                kids >= 2 || count == 1 && kids == 1,
                "{count}: {:?}",
                node.child
            );
            assert!(node.child[kids..].iter().all(|&c| c == u32::MAX));
        }
        // Every light is a leaf exactly once, at the end of its own trail.
        let mut seen = vec![0; count];
        for node in &tree.nodes {
            for j in 0..WIDTH {
                if node.leaves >> j & 1 != 0 {
                    seen[(node.child[j] & !LEAF) as usize] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1), "{count}: {seen:?}");
    }
    let walk = |count| LightTree::build(&points(count)).unwrap().trails;
    // 27 lights (the many-lights benchmark): two steps; four children a node took three, the
    // binary walk five.
    assert_eq!(walk(27).iter().map(|t| t.1).max(), Some(2));
    assert!(walk(64).iter().all(|t| t.1 == 2));
    assert!(walk(512).iter().all(|t| t.1 == 3));
}

#[test]
fn pick_sends_each_light_its_probability_of_the_sample_numbers() {
    for count in [1, 3, 5, 17, 27, 100] {
        let lights = points(count);
        let tree = LightTree::build(&lights).unwrap();
        let x = Vec3A::new(0.3, -0.2, 0.1);
        let probs: Vec<f32> = (0..count)
            .map(|k| tree.prob(k, x, None, exact(&lights, x), None))
            .collect();
        // Every point light reaches x, so the walk never loses a choice.
        let sum: f32 = probs.iter().sum();
        assert!((sum - 1.0).abs() < 1e-5, "{count}: Σ prob = {sum}");
        assert!(probs.iter().all(|&p| p > 0.0));
        // Stratified sample numbers: the share that lands on each light is its probability.
        let strata = 1 << 16;
        let mut hits = vec![0u32; count];
        for s in 0..strata {
            let u = (s as f32 + 0.5) / strata as f32;
            let (k, p) = tree.pick(x, None, u, exact(&lights, x), None).unwrap();
            assert_eq!(p, probs[k], "{count}: pick and prob differ for light {k}");
            hits[k] += 1;
        }
        for (k, &h) in hits.iter().enumerate() {
            let share = h as f32 / strata as f32;
            assert!(
                (share - probs[k]).abs() < 2e-4,
                "{count}: light {k} gets {share} of the choices, prob {}",
                probs[k]
            );
        }
    }
}

#[test]
fn a_light_that_cannot_reach_is_never_chosen() {
    // Every other point light counts 0 at the leaf (as if behind the receiver): it gets
    // probability 0. The share of walks that end at a node all of whose lights count 0 is lost
    // (no light sample), never given to a light that cannot contribute.
    let lights = points(27);
    let tree = LightTree::build(&lights).unwrap();
    let x = Vec3A::new(1.0, 2.0, -1.0);
    let leaf = |k: usize, bound: f32| {
        if k.is_multiple_of(2) { 0.0 } else { bound }
    };
    let probs: Vec<f32> = (0..27).map(|k| tree.prob(k, x, None, leaf, None)).collect();
    for (k, &p) in probs.iter().enumerate() {
        assert_eq!(p > 0.0, k % 2 == 1, "light {k}: {p}");
    }
    let lost = 1.0 - probs.iter().sum::<f32>();
    assert!((-1e-5..0.5).contains(&lost), "lost share {lost}");
    let strata = 4096;
    let mut none = 0;
    for s in 0..strata {
        match tree.pick(x, None, (s as f32 + 0.5) / strata as f32, leaf, None) {
            Some((k, p)) => assert!(k % 2 == 1 && p == probs[k], "u {s}/{strata} chose {k}"),
            None => none += 1,
        }
    }
    let share = none as f32 / strata as f32;
    assert!(
        (share - lost).abs() < 1e-3,
        "{share} of walks lost, expected {lost}"
    );
    // No light reaches: no choice at all.
    assert!(tree.pick(x, None, 0.5, |_, _| 0.0, None).is_none());
    assert_eq!(tree.prob(3, x, None, |_, _| 0.0, None), 0.0);
}
