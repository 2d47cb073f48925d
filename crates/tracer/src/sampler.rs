//! Stateless, deterministic low-discrepancy sampling.
//!
//! Every random number is a pure function of (key, sample index, dimension), where the key is
//! a hash of (seed, frame, pixel) — or of (seed, "eye sensor") for the common-random-number
//! sensor. Nothing depends on the thread that computes it, so images are bit-identical for any
//! thread count or chunking.
//!
//! Dimensions are consumed in 4-D chunks of a Sobol sequence; each chunk gets its own
//! Owen-scrambled, index-shuffled copy of the first four Sobol dimensions (Burley 2020,
//! "Practical Hash-based Owen Scrambling", JCGT 9(4)). The shuffle keeps the first 2^k
//! samples of a pixel a (0, k, 2)-net in each pair of dimensions, so power-of-two sample
//! counts are stratified.

use crate::scramble4::{scramble4, unit};

/// Direction numbers of the first four Sobol dimensions (Joe–Kuo parameters).
const SOBOL: [[u32; 32]; 4] = sobol_directions();

const fn sobol_directions() -> [[u32; 32]; 4] {
    let mut v = [[0u32; 32]; 4];
    let mut i = 0;
    while i < 32 {
        v[0][i] = 1u32 << (31 - i);
        i += 1;
    }
    // (s, a, m) for dimensions 2, 3, 4 of new-joe-kuo-6.21201.
    let s = [1usize, 2, 3];
    let a = [0u32, 1, 1];
    let m = [[1u32, 0, 0], [1, 3, 0], [1, 3, 1]];
    let mut d = 0;
    while d < 3 {
        let sd = s[d];
        let mut j = 0;
        while j < 32 {
            if j < sd {
                v[d + 1][j] = m[d][j] << (31 - j);
            } else {
                let mut x = v[d + 1][j - sd] ^ (v[d + 1][j - sd] >> sd);
                let mut k = 1;
                while k < sd {
                    if (a[d] >> (sd - 1 - k)) & 1 == 1 {
                        x ^= v[d + 1][j - k];
                    }
                    k += 1;
                }
                v[d + 1][j] = x;
            }
            j += 1;
        }
        d += 1;
    }
    v
}

#[cfg(test)]
fn sobol(mut index: u32, dim: usize) -> u32 {
    let mut x = 0;
    let mut bit = 0;
    while index != 0 {
        if index & 1 != 0 {
            x ^= SOBOL[dim][bit];
        }
        index >>= 1;
        bit += 1;
    }
    x
}

#[inline]
pub(crate) fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

#[cfg(test)]
fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

/// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hashes a list of words into a key. Each word is mixed in sequence (not XOR-ed), so small
/// integers in different positions never collide (the overlap trap of additive seeding).
pub fn hash_key(words: &[u64]) -> u64 {
    words
        .iter()
        .fold(0x6a09_e667_f3bc_c909, |h, &w| mix64(h ^ mix64(w)))
}

/// Bit-reversed Sobol points of the first four dimensions, indexed by the bytes of the
/// *bit-reversed* index: `rev(sobol(i)) = XOR_k REV_SOBOL_BYTES[k][byte k of rev(i)]`. Both
/// maps are linear over GF(2), so working in the reversed domain lets Owen scrambling
/// (reverse, Laine–Karras, reverse) skip two of its three bit reversals. 16 KiB, const-built.
pub(crate) static REV_SOBOL_BYTES: [[[u32; 4]; 256]; 4] = rev_sobol_byte_tables();

const fn rev_sobol_byte_tables() -> [[[u32; 4]; 256]; 4] {
    let mut t = [[[0u32; 4]; 256]; 4];
    let mut byte = 0;
    while byte < 4 {
        let mut v = 0;
        while v < 256 {
            let mut d = 0;
            while d < 4 {
                let mut x = 0u32;
                let mut bit = 0;
                while bit < 8 {
                    // Bit `bit` of byte `byte` of rev(i) is bit 31 - (8·byte + bit) of i.
                    if (v >> bit) & 1 == 1 {
                        x ^= SOBOL[d][31 - (byte * 8 + bit)];
                    }
                    bit += 1;
                }
                t[byte][v][d] = x.reverse_bits();
                d += 1;
            }
            v += 1;
        }
        byte += 1;
    }
    t
}

/// The four Sobol dimensions of the index whose bit reversal is `rev_index`, bit-reversed.
#[cfg(test)]
fn rev_sobol4(rev_index: u32) -> [u32; 4] {
    let b = rev_index.to_le_bytes();
    let t = |k: usize| &REV_SOBOL_BYTES[k][b[k] as usize];
    let (t0, t1, t2, t3) = (t(0), t(1), t(2), t(3));
    [
        t0[0] ^ t1[0] ^ t2[0] ^ t3[0],
        t0[1] ^ t1[1] ^ t2[1] ^ t3[1],
        t0[2] ^ t1[2] ^ t2[2] ^ t3[2],
        t0[3] ^ t1[3] ^ t2[3] ^ t3[3],
    ]
}

/// Chunks drawn from the scrambled Sobol sequence; later chunks (deeper bounces, whose share
/// of the variance is small) use plain hashing, which costs a fraction of the scrambling.
pub const LOW_DISCREPANCY_CHUNKS: u32 = 6;

/// The scrambling seeds of one low-discrepancy chunk: the chunk's seed (its index shuffle)
/// and one Owen-scrambling seed per dimension.
#[derive(Clone, Copy, Debug, Default)]
struct ChunkSeeds {
    chunk: u64,
    dims: [u32; 4],
}

impl ChunkSeeds {
    #[inline]
    fn new(key: u64, chunk: u32) -> ChunkSeeds {
        let seed = chunk_seed(key, chunk);
        // Each coordinate needs an independent scramble: seeds that are functions of one
        // another (e.g. affine) make the scrambled point non-uniform in 4-D and bias estimates.
        ChunkSeeds {
            chunk: seed,
            dims: std::array::from_fn(|d| mix64(seed ^ ((d as u64 + 1) << 56)) as u32),
        }
    }
}

#[inline]
fn chunk_seed(key: u64, chunk: u32) -> u64 {
    mix64(key ^ (chunk as u64).wrapping_mul(0xd1b5_4a32_d192_ed03))
}

/// The seeds of a key's low-discrepancy chunks, which depend on the key alone: computed once
/// and shared by all the samples of a pixel (or of the eye sensor), they spare each sample
/// five hashes per chunk. [`SampleStream::seeded`] gives the same numbers as
/// [`SampleStream::new`].
#[derive(Clone, Copy, Debug)]
pub struct StreamSeeds {
    key: u64,
    chunks: [ChunkSeeds; LOW_DISCREPANCY_CHUNKS as usize],
    /// The hashed chunks' seeds, from chunk [`LOW_DISCREPANCY_CHUNKS`] on: a path of the
    /// default depth (8) draws up to 15 chunks, most of them hashed.
    deep: [u64; DEEP_CHUNKS],
}

/// How many hashed chunks' seeds [`StreamSeeds`] keeps (later ones are hashed when entered).
const DEEP_CHUNKS: usize = 10;

impl StreamSeeds {
    pub fn new(key: u64) -> StreamSeeds {
        StreamSeeds {
            key,
            chunks: std::array::from_fn(|c| ChunkSeeds::new(key, c as u32)),
            deep: std::array::from_fn(|c| chunk_seed(key, LOW_DISCREPANCY_CHUNKS + c as u32)),
        }
    }
}

/// Where a stream's chunk seeds come from.
#[derive(Clone, Copy, Debug)]
enum Seeds<'a> {
    /// Hashed from the key when a chunk is entered.
    Key(u64),
    /// Computed once for all the samples of the key.
    Shared(&'a StreamSeeds),
}

/// The random numbers of one sample (one camera path, one sensor path).
#[derive(Clone, Copy, Debug)]
pub struct SampleStream<'a> {
    seeds: Seeds<'a>,
    index: u32,
    /// `index.reverse_bits()`, computed once per sample.
    rev_index: u32,
    dim: u32,
    chunk: u32,
    /// The scrambled values of the current chunk's four dimensions.
    values: [f32; 4],
}

impl<'a> SampleStream<'a> {
    pub fn new(key: u64, index: u32) -> Self {
        Self::start(Seeds::Key(key), index)
    }

    /// [`SampleStream::new`] for `seeds`' key, with its chunk seeds computed already.
    #[inline]
    pub fn seeded(seeds: &'a StreamSeeds, index: u32) -> Self {
        Self::start(Seeds::Shared(seeds), index)
    }

    #[inline]
    fn start(seeds: Seeds<'a>, index: u32) -> Self {
        let mut s = SampleStream {
            seeds,
            index,
            rev_index: index.reverse_bits(),
            dim: 0,
            chunk: u32::MAX,
            values: [0.0; 4],
        };
        s.enter_chunk(0);
        s
    }

    /// Computes the chunk's four values at once: shuffle the index, take the Sobol point,
    /// Owen-scramble each coordinate with its own seed.
    #[inline]
    fn enter_chunk(&mut self, chunk: u32) {
        self.chunk = chunk;
        if chunk >= LOW_DISCREPANCY_CHUNKS {
            let seed = match self.seeds {
                Seeds::Key(key) => chunk_seed(key, chunk),
                Seeds::Shared(s) => match s.deep.get((chunk - LOW_DISCREPANCY_CHUNKS) as usize) {
                    Some(&seed) => seed,
                    None => chunk_seed(s.key, chunk),
                },
            };
            let a = mix64(seed ^ self.index as u64);
            let b = mix64(a);
            self.values = [a as u32, (a >> 32) as u32, b as u32, (b >> 32) as u32].map(unit);
            return;
        }
        let seeds = match self.seeds {
            Seeds::Key(key) => ChunkSeeds::new(key, chunk),
            Seeds::Shared(s) => s.chunks[chunk as usize],
        };
        // Shuffle the index (nested uniform scramble = reverse, Laine-Karras, reverse) and look
        // the point up, both in the reversed domain; then Owen-scramble each coordinate.
        let rev_shuffled = laine_karras(self.rev_index, seeds.chunk as u32);
        self.values = scramble4(rev_shuffled, &seeds.dims);
    }

    /// Skips to the start of the next 4-D chunk (keeps 2-D requests on aligned pairs).
    #[inline]
    pub fn align(&mut self, to: u32) {
        self.dim = self.dim.next_multiple_of(to);
    }

    /// The next value in [0, 1).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let chunk = self.dim / 4;
        if chunk != self.chunk {
            self.enter_chunk(chunk);
        }
        let v = self.values[(self.dim % 4) as usize];
        self.dim += 1;
        v
    }

    /// The next chunk's four values (what four calls of [`SampleStream::next_1d`] after
    /// [`SampleStream::start_group`] give), at once.
    #[inline]
    pub fn next_4d(&mut self) -> [f32; 4] {
        self.align(4);
        let chunk = self.dim / 4;
        if chunk != self.chunk {
            self.enter_chunk(chunk);
        }
        self.dim += 4;
        self.values
    }

    /// The next 2-D point; always drawn from dimensions (0,1) or (2,3) of a chunk.
    #[inline]
    pub fn next_2d(&mut self) -> [f32; 2] {
        self.align(2);
        [self.next_1d(), self.next_1d()]
    }

    /// Starts a new group of dimensions at a chunk boundary (e.g. one per path vertex), so
    /// that each bounce uses the same, well-stratified dimension pairs.
    #[inline]
    pub fn start_group(&mut self) {
        self.align(4);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_a_pure_function_of_key_index_and_dimension() {
        let draw = |key, idx| {
            let mut s = SampleStream::new(key, idx);
            (0..40).map(|_| s.next_1d().to_bits()).collect::<Vec<_>>()
        };
        let a = draw(hash_key(&[1, 3, 17, 5]), 9);
        // Visit other keys and indices in between, in reverse order: no hidden state.
        for k in (0..50).rev() {
            let _ = draw(hash_key(&[1, 3, k, 5]), k as u32);
        }
        assert_eq!(a, draw(hash_key(&[1, 3, 17, 5]), 9));
        assert_ne!(a, draw(hash_key(&[1, 3, 5, 17]), 9));
    }

    #[test]
    fn seeded_streams_draw_what_new_streams_draw() {
        for k in 0..20u64 {
            let key = hash_key(&[k, 7]);
            let seeds = StreamSeeds::new(key);
            for i in [0u32, 1, 2, 15, 16, 1000, u32::MAX] {
                let mut a = SampleStream::new(key, i);
                let mut b = SampleStream::seeded(&seeds, i);
                // Past the low-discrepancy chunks and the hashed ones whose seeds are kept.
                for d in 0..(4 * (LOW_DISCREPANCY_CHUNKS + DEEP_CHUNKS as u32) + 12) {
                    if d % 5 == 0 {
                        a.start_group();
                        b.start_group();
                    }
                    assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits(), "{k} {i} {d}");
                }
            }
        }
    }

    #[test]
    fn four_at_once_are_four_in_turn() {
        let key = hash_key(&[9, 9]);
        for i in 0..50 {
            let mut a = SampleStream::new(key, i);
            let mut b = SampleStream::new(key, i);
            a.next_1d();
            b.next_1d();
            for _ in 0..(LOW_DISCREPANCY_CHUNKS + 3) {
                a.start_group();
                let one = [a.next_1d(), a.next_1d(), a.next_1d(), a.next_1d()];
                assert_eq!(one.map(f32::to_bits), b.next_4d().map(f32::to_bits));
            }
        }
    }

    #[test]
    fn reversed_tables_equal_the_bit_loop() {
        for i in [0u32, 1, 2, 3, 255, 256, 0x1234_5678, u32::MAX, 0x8000_0001] {
            for d in 0..4 {
                assert_eq!(
                    rev_sobol4(i.reverse_bits())[d],
                    sobol(i, d).reverse_bits(),
                    "index {i} dim {d}"
                );
            }
        }
    }

    #[test]
    fn reversed_domain_equals_the_textbook_scramble() {
        // values = nested_uniform_scramble(sobol(nested_uniform_scramble(i, s0), d), s_d)
        let key = hash_key(&[3, 1, 4]);
        for i in [0u32, 1, 5, 77, 1023] {
            let mut st = SampleStream::new(key, i);
            let got: Vec<f32> = (0..4).map(|_| st.next_1d()).collect();
            let seed = mix64(key);
            let shuffled = nested_uniform_scramble(i, seed as u32);
            let want: Vec<f32> = (0..4)
                .map(|d| {
                    let v = nested_uniform_scramble(
                        sobol(shuffled, d),
                        mix64(seed ^ ((d as u64 + 1) << 56)) as u32,
                    );
                    (v >> 8) as f32 * (1.0 / 16_777_216.0)
                })
                .collect();
            assert_eq!(got, want, "index {i}");
        }
    }

    #[test]
    fn first_dimensions_match_sobol() {
        // Unscrambled Sobol dimension 1 (direction numbers 0.1, 0.11, 0.101 in binary) for
        // indices 1..4: v0, v1, v0^v1, v2.
        let v: Vec<f64> = (1..5).map(|i| sobol(i, 1) as f64 / 2f64.powi(32)).collect();
        assert_eq!(v, vec![0.5, 0.75, 0.25, 0.625]);
    }

    #[test]
    fn power_of_two_prefix_is_stratified_in_2d() {
        // 16 samples of one pixel: each of the 4x4 cells of every elementary 2-D interval
        // shape holds exactly one point (a (0,4,2)-net).
        let key = hash_key(&[42, 0, 7, 9]);
        let pts: Vec<[f32; 2]> = (0..16)
            .map(|i| {
                let mut s = SampleStream::new(key, i);
                s.next_2d()
            })
            .collect();
        for (bx, by) in [(1u32, 16u32), (2, 8), (4, 4), (8, 2), (16, 1)] {
            let mut cells = vec![0; 16];
            for p in &pts {
                let cx = (p[0] * bx as f32) as u32;
                let cy = (p[1] * by as f32) as u32;
                cells[(cy * bx + cx) as usize] += 1;
            }
            assert!(cells.iter().all(|&c| c == 1), "{bx}x{by}: {cells:?}");
        }
    }

    #[test]
    fn mean_is_unbiased() {
        let mut sum = 0.0f64;
        let n = 4096;
        for p in 0..64u64 {
            let key = hash_key(&[p]);
            for i in 0..n / 64 {
                let mut s = SampleStream::new(key, i);
                s.next_1d();
                sum += s.next_1d() as f64;
            }
        }
        assert!((sum / n as f64 - 0.5).abs() < 0.01);
    }
}
