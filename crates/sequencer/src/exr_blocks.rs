//! An OpenEXR image written with its blocks compressed on the caller's rayon pool.
//!
//! The exr crate compresses blocks either one after another (`non_parallel`) or on a thread
//! pool it builds for each file; a frame is written from inside the render's own pool, next to
//! its PNGs, where a second pool would only compete with it. Here the blocks are compressed a
//! batch at a time with `par_iter` and written in increasing line order, so the file's bytes
//! are the same for any thread count (each block's compression depends on its own pixels
//! only). A batch holds two blocks a thread, and at most 32 MiB of them: their uncompressed
//! copies are the only memory this adds (a 256 × 256 tile of a frame's 17 channels is 4.5 MB).
use exr::block::UncompressedBlock;
use exr::block::writer::ChunksWriter;
use exr::error::UnitResult;
use exr::image::write::layers::{LayersWriter, WritableLayers};
use exr::prelude::*;
use rayon::prelude::*;
use std::io::{Seek, Write};

/// At most this many bytes of uncompressed blocks in flight (at least one block).
const BATCH_BYTES: usize = 32 << 20;

/// Writes `image` to `write` (the exr crate's `to_buffered`, with its blocks compressed in
/// parallel on the current rayon pool).
pub fn write_parallel<'i, L: WritableLayers<'i>>(
    image: &'i Image<L>,
    write: impl Write + Seek,
) -> UnitResult {
    let headers = image.layer_data.infer_headers(&image.attributes);
    let layers = image.layer_data.create_writer(&headers);
    exr::block::write(write, headers, true, move |meta, chunks| {
        let order: Vec<_> = meta.enumerate_ordered_header_block_indices().collect();
        let block_bytes = meta.headers.iter().map(|h| h.max_block_byte_size()).max();
        let batch = (BATCH_BYTES / block_bytes.unwrap_or(1).max(1))
            .clamp(1, 2 * rayon::current_num_threads().max(1));
        for run in order.chunks(batch) {
            let compressed: Vec<_> = run
                .par_iter()
                .map(|&(index_in_header, index)| {
                    let data = layers.extract_uncompressed_block(&meta.headers, index);
                    UncompressedBlock { index, data }
                        .compress_to_chunk(&meta.headers)
                        .map(|chunk| (index_in_header, chunk))
                })
                .collect();
            for c in compressed {
                let (index_in_header, chunk) = c?;
                chunks.write_chunk(index_in_header, chunk)?;
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 37 × 70 image of four channels in `blocks`: as scan lines, three blocks of 32, the
    /// last short; as 16 × 16 tiles, fifteen.
    fn image(blocks: Blocks) -> Image<Layer<AnyChannels<FlatSamples>>> {
        let (w, h) = (37, 70);
        let mut x = 0x9e37_79b9_u32;
        let mut noise = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1 << 24) as f32
        };
        let list: smallvec::SmallVec<[AnyChannel<FlatSamples>; 4]> = ["B", "G", "R", "Z"]
            .iter()
            .map(|n| {
                // A gradient with coarse noise: compressible, every block different.
                let v: Vec<f32> = (0..w * h)
                    .map(|i| (i / w + i % w) as f32 * 0.25 + (noise() * 4.0).floor() / 16.0)
                    .collect();
                AnyChannel::new(*n, FlatSamples::F32(v))
            })
            .collect();
        let encoding = Encoding {
            compression: Compression::PIZ,
            blocks,
            line_order: LineOrder::Increasing,
        };
        let layer = Layer::new(
            (w, h),
            LayerAttributes::named("frame"),
            encoding,
            AnyChannels::sort(list),
        );
        Image::from_layer(layer)
    }

    fn bytes_on(threads: usize, image: &Image<Layer<AnyChannels<FlatSamples>>>) -> Vec<u8> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = std::io::Cursor::new(Vec::new());
        pool.install(|| write_parallel(image, &mut out)).unwrap();
        out.into_inner()
    }

    #[test]
    fn the_bytes_are_the_exr_crates_sequential_ones_on_any_thread_count() {
        for blocks in [Blocks::ScanLines, Blocks::Tiles(Vec2(16, 16))] {
            let image = image(blocks);
            let mut sequential = std::io::Cursor::new(Vec::new());
            image
                .write()
                .non_parallel()
                .to_buffered(&mut sequential)
                .unwrap();
            let sequential = sequential.into_inner();
            for threads in [1, 2, 3, 8] {
                assert!(
                    bytes_on(threads, &image) == sequential,
                    "{blocks:?}, {threads} threads"
                );
            }
            // Several blocks, compressed, and read back as written.
            let back = read()
                .no_deep_data()
                .largest_resolution_level()
                .all_channels()
                .first_valid_layer()
                .all_attributes()
                .from_buffered(std::io::Cursor::new(&sequential))
                .unwrap();
            assert_eq!(back.layer_data.encoding.blocks, blocks);
            assert_eq!(back.layer_data.channel_data, image.layer_data.channel_data);
            assert!(sequential.len() < 37 * 70 * 4 * 4, "{blocks:?}");
        }
    }
}
