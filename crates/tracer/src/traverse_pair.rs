//! Two walks of one structure, stepped in turn: a path's shadow ray and its next ray.
//!
//! One walk is a chain of dependent steps (a node's test decides the next node to load), so a
//! lone ray leaves most of the core idle while it waits on loads and on the node test's
//! latency. The shadow ray of a vertex's light sample and the ray that continues the path
//! from the same vertex do not depend on each other; walking them together, one step of each
//! per round, gives the core two independent chains to overlap.
//!
//! Each walk takes exactly the steps it takes alone ([`Cursor8::step`]), with its own ray,
//! stack and leaf test, so the results are those of two separate walks, bit for bit.
use crate::isa::NodeTest;
use crate::wide_bvh::WideBvh;
use crate::wide_walk::{Cursor8, Leaves, WalkStack};
use obvhs::ray::Ray;

/// One walk's own part: its ray, its stack and its leaf test (as for
/// [`crate::wide_walk::walk8`]).
pub struct Walk<'a, L> {
    pub ray: &'a mut Ray,
    pub stack: &'a mut WalkStack,
    pub leaves: L,
}

impl<L: Leaves> Walk<'_, L> {
    #[inline(always)]
    fn step<T: NodeTest, const O: bool>(&mut self, bvh: &WideBvh, at: &mut Cursor8<T, O>) -> bool {
        at.step(bvh, self.ray, self.stack, &mut self.leaves)
    }

    #[inline(always)]
    fn finish<T: NodeTest, const O: bool>(&mut self, bvh: &WideBvh, at: &mut Cursor8<T, O>) {
        while !self.step(bvh, at) {}
    }
}

/// Walks `a` (a closest-hit ray, nearest child first) and `b` (a shadow ray, in child order)
/// through `bvh`, one step of each in turn until one is over, then the other to its end.
#[inline(always)]
pub fn walk_pair<La: Leaves, Lb: Leaves>(
    bvh: &WideBvh,
    isa: impl NodeTest,
    mut a: Walk<La>,
    mut b: Walk<Lb>,
) {
    let Some(mut at_a) = Cursor8::<_, true>::start(bvh, isa, a.ray) else {
        return;
    };
    let Some(mut at_b) = Cursor8::<_, false>::start(bvh, isa, b.ray) else {
        return;
    };
    loop {
        let a_done = a.step(bvh, &mut at_a);
        let b_done = b.step(bvh, &mut at_b);
        match (a_done, b_done) {
            (false, false) => continue,
            (true, false) => b.finish(bvh, &mut at_b),
            (false, true) => a.finish(bvh, &mut at_a),
            (true, true) => {}
        }
        return;
    }
}

#[cfg(test)]
mod tests {
    use crate::accel::Accel;
    use crate::isa::{Baseline, NodeTest};
    use crate::wide_walk::WalkStack;
    use crate::wide_walk::tests::{p3, soup};
    use obvhs::ray::Ray;

    /// Walked together or one after the other, a closest-hit ray and a shadow ray get the
    /// same answers, on every instruction set here.
    fn compare(accel: &Accel, test: impl NodeTest, name: &str) {
        let mut s = 17u64 << 32;
        let (mut st, mut st_shadow) = (WalkStack::default(), WalkStack::default());
        let (mut hits, mut blocked) = (0, 0);
        for k in 0..3000 {
            let o = p3(&mut s) * 30.0 - 15.0;
            let d = (p3(&mut s) - 0.5).normalize();
            let ray = Ray::new(o, d, 0.0, f32::INFINITY);
            // Shadow rays from the same origin: to the sky, or to a point at some distance.
            let to = p3(&mut s) * 20.0 - 10.0;
            let tmax = if k % 3 == 0 {
                f32::INFINITY
            } else {
                (to - o).length()
            };
            let shadow = Ray::new(o, (to - o).normalize(), 0.0, tmax);
            let (h, free) =
                accel.closest_and_unblocked_with(test, (&ray, &mut st), (&shadow, &mut st_shadow));
            let alone = accel.closest_with(test, &ray, &mut st);
            let free_alone = accel.unblocked_with(test, &shadow, &mut st);
            let key = |h: Option<crate::accel::SlotHit>| h.map(|h| (h.t.to_bits(), h.slot));
            assert_eq!(key(h), key(alone), "{name}: ray {k}");
            assert_eq!(free, free_alone, "{name}: shadow ray {k}");
            hits += h.is_some() as u32;
            blocked += !free as u32;
        }
        // Both outcomes of both queries occur often, so the walks end in either order.
        assert!((500..2500).contains(&hits), "{name}: {hits} hits");
        assert!((500..2500).contains(&blocked), "{name}: {blocked} blocked");
    }

    #[test]
    fn walking_two_rays_together_answers_what_walking_them_apart_does() {
        let tris = soup(4000, 3);
        let accel = Accel::build(&tris);
        compare(&accel, Baseline, "baseline");
        #[cfg(target_arch = "x86_64")]
        if let Some(wide) = crate::isa::avx2() {
            compare(&accel, wide, "AVX2");
        }
    }
}
