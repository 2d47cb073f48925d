//! Eight rays walked together, one per lane ([`crate::lanes8`]): a pixel's camera rays, which
//! enter nearly the same nodes and hit nearly the same triangles, so that one node's boxes and
//! one triangle are tested against all eight at once instead of eight times over.
//!
//! At each node, each child's box is tested against the rays that entered the node; a leaf
//! child's triangles are tested one at a time against the rays that entered the leaf (the
//! watertight test of [`crate::tri4`], a ray per lane); the inner children entered are pushed
//! with their rays, the nearest (for the packet's first ray that enters it) on top. Per lane,
//! the arithmetic is the single ray's ([`crate::wide_test`], [`Tri4::hit_lane`]): the same box
//! distances, the same triangle distances, bit for bit. Only the order of the visits differs,
//! and with it which of two triangles at exactly the same distance wins, or, where rounding
//! puts a box's entry a hair past a triangle inside it, whether that triangle is seen. A ray
//! alone may answer those otherwise: in `packet_tests.rs`, none of 27 962 rays into a random
//! soup, and 2 393 of 27 962 rays aimed at a grid's shared edges and corners (all but 4 of
//! them ties); in a render, rarely (the built-in interior at 128 × 96, 16 spp: one pixel).
//! A packet always gives the same answers, on every instruction set, so it must always be
//! made of the same rays: [`crate::film`] groups a pixel's samples by index.
use crate::accel::{Accel, SlotHit};
use crate::lanes8::F8;
use crate::tri4::{Shear, Tri4};
use crate::wide_bvh::Node8;
use crate::wide_test::{FAR_SCALE, NODE_EPSILON};
use obvhs::ray::Ray;

/// What the walk needs of eight rays, a lane each.
#[derive(Clone, Copy)]
pub struct Rays8<V> {
    o: [V; 3],
    inv: [V; 3],
    /// The shear of each ray ([`Shear`]): sx, sy, sz, and the origin along kx, ky, kz.
    s: [V; 3],
    so: [V; 3],
    /// Per sheared axis, the lanes whose source axis is 1 and those whose is 2.
    k1: [V; 3],
    k2: [V; 3],
    tmin: V,
}

impl<V: F8> Rays8<V> {
    #[inline(always)]
    pub fn new(rays: &[Ray; 8]) -> Rays8<V> {
        let mut o = [[0.0; 8]; 3];
        let mut inv = [[0.0; 8]; 3];
        let mut s = [[0.0; 8]; 3];
        let mut so = [[0.0; 8]; 3];
        let (mut k1, mut k2) = ([0u32; 3], [0u32; 3]);
        let mut tmin = [0.0; 8];
        for (l, ray) in rays.iter().enumerate() {
            let shear = Shear::new(ray);
            let (scale, origin, k) = (shear.scale(), shear.origin(), shear.k());
            let (ro, ri) = (ray.origin.to_array(), ray.inv_direction.to_array());
            for a in 0..3 {
                o[a][l] = ro[a];
                inv[a][l] = ri[a];
                s[a][l] = scale[a];
                so[a][l] = origin[a];
                k1[a] |= ((k[a] == 1) as u32) << l;
                k2[a] |= ((k[a] == 2) as u32) << l;
            }
            tmin[l] = ray.tmin;
        }
        // Spelled out: a function passed to `map` is not inlined into the AVX2 copy.
        let load3 = |a: &[[f32; 8]; 3]| [V::load(&a[0]), V::load(&a[1]), V::load(&a[2])];
        let mask3 = |k: [u32; 3]| [V::mask_of(k[0]), V::mask_of(k[1]), V::mask_of(k[2])];
        Rays8 {
            o: load3(&o),
            inv: load3(&inv),
            s: load3(&s),
            so: load3(&so),
            k1: mask3(k1),
            k2: mask3(k2),
            tmin: V::load(&tmin),
        }
    }
}

/// A node waiting on the packet's stack: its index, the lanes that entered it, and the entry
/// distance of the first of them (the order key).
type Pending = (u32, u32, f32);

/// A packet walk's stack, kept from packet to packet so that it is allocated once per worker.
#[derive(Clone, Debug, Default)]
pub struct PacketStack(Vec<Pending>);

/// The closest hits of the rays of `active` (bit l: lane l), each within its tmin and `tmax[l]`,
/// in `accel`. `stack` is scratch space, reused.
#[inline(always)]
pub fn closest8<V: F8>(
    accel: &Accel,
    rays: &Rays8<V>,
    tmax: [f32; 8],
    active: u32,
    PacketStack(stack): &mut PacketStack,
) -> [Option<SlotHit>; 8] {
    let (nodes, packs) = accel.walk_data();
    let mut best = V::load(&tmax);
    let mut slot = [u32::MAX; 8];
    stack.clear();
    if !nodes.is_empty() && active != 0 {
        stack.push((0, active, 0.0));
    }
    let (eps, far_scale) = (V::splat(NODE_EPSILON), V::splat(FAR_SCALE));
    while let Some((index, entered, _)) = stack.pop() {
        let node = &nodes[index as usize];
        let base = stack.len();
        for c in 0..8 {
            let child = node.child[c];
            if child == 0 {
                continue;
            }
            // The slab test of `crate::wide_test`, per lane: near and far planes by the sign of
            // 1/d there, here the lesser and greater of the two distances (the same values).
            let (nx, fx) = slab(node, c, 0, rays);
            let (ny, fy) = slab(node, c, 1, rays);
            let (nz, fz) = slab(node, c, 2, rays);
            let near = nx.max(ny).max(nz.max(eps));
            let far = fx.min(fy.min(fz)).mul(far_scale).min(best);
            let hit = near.le(far).movemask() & entered;
            if hit == 0 {
                continue;
            }
            if node.leaves >> c & 1 == 0 {
                let key = near.store()[hit.trailing_zeros() as usize];
                stack.push((child, hit, key));
                let mut j = stack.len() - 1;
                while j > base && stack[j - 1].2 < key {
                    stack.swap(j, j - 1);
                    j -= 1;
                }
                continue;
            }
            // A leaf: one block, its slots the child's bits (`crate::wide_bvh`), highest first
            // (of equal distances the highest slot wins, as in a single ray's block test).
            let first = node.prim_base + child.trailing_zeros();
            let block = first / 4;
            let mut lanes = (child >> (block * 4 - node.prim_base)) & 0xf;
            while lanes != 0 {
                let lane = 31 - lanes.leading_zeros();
                lanes &= !(1 << lane);
                let (ok, t, det) = triangle(&packs[block as usize], lane as usize, rays, best);
                let ok = ok.movemask() & hit;
                if ok == 0 {
                    continue;
                }
                let t = t.div(det);
                let closer = t.lt(best).movemask() & ok;
                if closer != 0 {
                    best = best.blend(t, V::mask_of(closer));
                    for (l, s) in slot.iter_mut().enumerate() {
                        if closer >> l & 1 != 0 {
                            *s = block * 4 + lane;
                        }
                    }
                }
            }
        }
    }
    let t = best.store();
    std::array::from_fn(|l| {
        (slot[l] != u32::MAX).then_some(SlotHit {
            t: t[l],
            slot: slot[l],
        })
    })
}

/// Child `c`'s entry and exit distances along axis `a` of `node`, per lane. (Functions, not
/// closures, here and below: a closure is not inlined into the AVX2 copy of the walk, and its
/// lane operations would stay calls.)
#[inline(always)]
fn slab<V: F8>(node: &Node8, c: usize, a: usize, rays: &Rays8<V>) -> (V, V) {
    let t0 = V::splat(node.planes[2 * a][c])
        .sub(rays.o[a])
        .mul(rays.inv[a]);
    let t1 = V::splat(node.planes[2 * a + 1][c])
        .sub(rays.o[a])
        .mul(rays.inv[a]);
    (t0.min(t1), t0.max(t1))
}

/// Vertex `i` of triangle `lane` of `pack` relative to each ray's origin and sheared
/// ([`Tri4::hit_lane`]).
#[inline(always)]
fn vertex<V: F8>(pack: &Tri4, i: usize, lane: usize, r: &Rays8<V>) -> (V, V, V) {
    let c = pack.vertex(i, lane);
    let (c0, c1, c2) = (V::splat(c[0]), V::splat(c[1]), V::splat(c[2]));
    let x = c0.blend(c1, r.k1[0]).blend(c2, r.k2[0]).sub(r.so[0]);
    let y = c0.blend(c1, r.k1[1]).blend(c2, r.k2[1]).sub(r.so[1]);
    let z = c0.blend(c1, r.k1[2]).blend(c2, r.k2[2]).sub(r.so[2]);
    (x.sub(r.s[0].mul(z)), y.sub(r.s[1].mul(z)), z)
}

/// Triangle `lane` of `pack` against every ray: the lanes that hit it within [tmin, `tmax`] (a
/// mask), and the distances as t ÷ det ([`Tri4::hit_lane`]'s arithmetic in each lane).
#[inline(always)]
fn triangle<V: F8>(pack: &Tri4, lane: usize, r: &Rays8<V>, tmax: V) -> (V, V, V) {
    let (ax, ay, az) = vertex(pack, 0, lane, r);
    let (bx, by, bz) = vertex(pack, 1, lane, r);
    let (cx, cy, cz) = vertex(pack, 2, lane, r);
    let u = cx.mul(by).sub(cy.mul(bx));
    let v = ax.mul(cy).sub(ay.mul(cx));
    let w = bx.mul(ay).sub(by.mul(ax));
    let det = u.add(v).add(w);
    let t = u.mul(az).add(v.mul(bz)).add(w.mul(cz)).mul(r.s[2]);
    let sign_bit = V::splat(f32::from_bits(crate::triangle::SIGN));
    let sign = det.and(sign_bit);
    let zero = V::splat(0.0);
    let inside = u
        .xor(sign)
        .ge(zero)
        .and(v.xor(sign).ge(zero).and(w.xor(sign).ge(zero)));
    let abs_det = sign_bit.andnot(det);
    let scaled = t.xor(sign);
    let within = scaled
        .ge(r.tmin.mul(abs_det))
        .and(scaled.le(tmax.mul(abs_det)));
    let ok = inside.and(det.ne(zero)).and(within);
    (ok, t, det)
}

impl Accel {
    /// [`closest8`] of `rays` (those of `active`) within their own (tmin, tmax), on this
    /// process's lanes: AVX2's where [`crate::isa::wide`] allows it, else the baseline's. The
    /// same answers on both.
    pub fn closest8(
        &self,
        rays: &[Ray; 8],
        active: u32,
        stack: &mut PacketStack,
    ) -> [Option<SlotHit>; 8] {
        let tmax = rays.map(|r| r.tmax);
        #[cfg(target_arch = "x86_64")]
        {
            if crate::isa::wide().is_some() {
                // SAFETY: `wide` is `Some` only where the CPU has AVX2.
                return unsafe { closest8_avx2(self, rays, tmax, active, stack) };
            }
            let r = Rays8::<crate::lanes8::Sse2F8>::new(rays);
            closest8(self, &r, tmax, active, stack)
        }
        #[cfg(not(target_arch = "x86_64"))]
        closest8(
            self,
            &Rays8::<crate::lanes8::ScalarF8>::new(rays),
            tmax,
            active,
            stack,
        )
    }
}

/// [`closest8`] on AVX2's lanes, compiled for AVX2 so that every lane operation inlines.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
unsafe fn closest8_avx2(
    accel: &Accel,
    rays: &[Ray; 8],
    tmax: [f32; 8],
    active: u32,
    stack: &mut PacketStack,
) -> [Option<SlotHit>; 8] {
    let r = Rays8::<crate::lanes8::Avx2F8>::new(rays);
    closest8(accel, &r, tmax, active, stack)
}

#[cfg(test)]
#[path = "packet_tests.rs"]
mod tests;
