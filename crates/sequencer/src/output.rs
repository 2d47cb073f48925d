//! Files a render writes: the raw frame as OpenEXR (beauty + AOVs), sRGB PNG previews, and
//! the atomic write-then-rename every output goes through.
//!
//! EXR layout: one part, PIZ compression in 256 × 256 tiles (compressed in parallel,
//! `exr_blocks.rs`), increasing line order (so the bytes do not depend on compression-thread
//! timing), f32 channels `R G B`, `albedo.{R,G,B}`,
//! `wcam_achromatic.{R,G,B}`, `irradiance.{R,G,B}`, `N.{X,Y,Z}` (first-hit shading normal),
//! `Z` (first-hit distance, 0 where nothing was hit), `mask.emitter` and `mask.hit`
//! (fractions of the pixel's samples that saw an emitter / any surface).
//!
//! PNG preview tone curve: `sRGB_encode(clamp(rgb · 2^exposure, 0, 1))`, 8 bits, with the
//! IEC 61966-2-1 transfer function. No tone mapping, so colours below 1 are exact (the HSV
//! read-outs of the paper's figures are taken on these values); anything brighter clips.
use crate::error::Failure;
use exr::prelude::*;
// exr's prelude brings its own `Result`; ours is the standard one.
type Result<T, E = Failure> = std::result::Result<T, E>;
use eyeadapt_tracer::Frame;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The temporary name a file is written under before it is renamed into place.
pub fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// Deletes the temporary files (`.NAME.tmp-PID`) a killed run left in the output directory
/// `dir`, and nothing else: only in the directories this program writes (`dir` itself, `rows/`,
/// each directory of `frames/`, `plots/`, `video/`; none of them followed through a symbolic
/// link), and only names this program gives its temporaries there (`.frame_000012.png.tmp-77`,
/// `.manifest.json.tmp-77`…). A user's `.notes.tmp-1`, or anything in a directory of their
/// own, stays. Only called while holding the directory lock, so no live writer owns any of
/// them. Returns how many were removed.
pub fn remove_stale_temps(dir: &Path) -> Result<usize, Failure> {
    let mut dirs = vec![
        (dir.to_path_buf(), Owned::Top),
        (dir.join("rows"), Owned::Rows),
        (dir.join("plots"), Owned::Plots),
        (dir.join("video"), Owned::Video),
    ];
    for frames in real_subdirs(&dir.join("frames")) {
        dirs.push((frames, Owned::Frames));
    }
    let mut removed = 0;
    for (d, owned) in dirs {
        if !is_real_dir(&d) {
            continue;
        }
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            let is_file = e.file_type().is_ok_and(|t| t.is_file());
            if is_file && name.to_str().is_some_and(|n| owned.is_our_temp(n)) {
                let p = e.path();
                fs::remove_file(&p)
                    .map_err(|e| Failure::io("cannot remove stale temporary file", &p, &e))?;
                removed += 1;
            }
        }
    }
    Ok(removed)
}

/// The directories of an output directory this program writes into, by what it writes there.
#[derive(Clone, Copy)]
enum Owned {
    /// The manifest, the CSVs and the report page.
    Top,
    /// `rows/frame_NNNNNN.csv`.
    Rows,
    /// `frames/<raw or estimator>/frame_NNNNNN.{exr,png}`.
    Frames,
    /// `plots/*.svg`.
    Plots,
    /// `video/*.mp4`.
    Video,
}

impl Owned {
    /// True for `.FILE.tmp-PID` where FILE is a name this program writes in such a directory.
    fn is_our_temp(self, name: &str) -> bool {
        let Some((file, pid)) = name
            .strip_prefix('.')
            .and_then(|rest| rest.rsplit_once(".tmp-"))
        else {
            return false;
        };
        if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
            return false;
        }
        let frame_file = |exts: &[&str]| {
            file.strip_prefix("frame_")
                .and_then(|rest| rest.split_once('.'))
                .is_some_and(|(n, ext)| {
                    !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) && exts.contains(&ext)
                })
        };
        match self {
            Owned::Top => TOP_FILES.contains(&file),
            Owned::Rows => frame_file(&["csv"]),
            Owned::Frames => frame_file(&["exr", "png"]),
            Owned::Plots => file.len() > 4 && file.ends_with(".svg"),
            Owned::Video => file.len() > 4 && file.ends_with(".mp4"),
        }
    }
}

/// Files this program writes at the top of an output directory.
const TOP_FILES: [&str; 5] = [
    crate::manifest::MANIFEST,
    crate::manifest::CSV,
    "coherence.csv",
    "coherence_frames.csv",
    "report.html",
];

/// A directory itself, not a symbolic link to one.
fn is_real_dir(p: &Path) -> bool {
    fs::symlink_metadata(p).is_ok_and(|m| m.is_dir())
}

/// The subdirectories of `dir` that are directories themselves (not symbolic links).
fn real_subdirs(dir: &Path) -> Vec<PathBuf> {
    if !is_real_dir(dir) {
        return Vec::new();
    }
    let Ok(entries) = fs::read_dir(dir) else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| e.path())
        .collect()
}

/// Writes `path` atomically: `write` fills a temporary file in the same directory, which is
/// flushed to disk and renamed over `path`. A crash leaves either the old file or the new one.
pub fn atomic_write(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), Failure>,
) -> Result<(), Failure> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        fs::create_dir_all(dir).map_err(|e| Failure::io("cannot create directory", dir, &e))?;
    }
    let tmp = temp_path(path);
    let result = write(&tmp).and_then(|()| {
        let f = fs::File::open(&tmp).map_err(|e| Failure::io("cannot reopen", &tmp, &e))?;
        f.sync_all()
            .map_err(|e| Failure::io("cannot sync", &tmp, &e))?;
        fs::rename(&tmp, path).map_err(|e| Failure::io("cannot rename into place", path, &e))
    });
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Writes bytes atomically.
pub fn atomic_write_bytes(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    atomic_write(path, |tmp| {
        let mut f = fs::File::create(tmp).map_err(|e| Failure::io("cannot create", tmp, &e))?;
        f.write_all(bytes)
            .map_err(|e| Failure::io("cannot write", tmp, &e))
    })
}

fn exr_failure(path: &Path, e: exr::error::Error) -> Failure {
    match e {
        exr::error::Error::Io(io) => Failure::io("cannot write EXR", path, &io),
        other => Failure::Other(format!("cannot write EXR {}: {other}", path.display())),
    }
}

/// The named channels of a frame, in the order they are written.
fn channels(frame: &Frame) -> Vec<(String, Vec<f32>)> {
    let mut out = Vec::new();
    let rgb3 =
        |prefix: &str, v: &[[f32; 3]], names: [&str; 3], out: &mut Vec<(String, Vec<f32>)>| {
            for (c, n) in names.iter().enumerate() {
                out.push((format!("{prefix}{n}"), v.iter().map(|p| p[c]).collect()));
            }
        };
    rgb3("", &frame.rgb, ["R", "G", "B"], &mut out);
    rgb3("albedo.", &frame.albedo, ["R", "G", "B"], &mut out);
    rgb3(
        "wcam_achromatic.",
        &frame.achromatic,
        ["R", "G", "B"],
        &mut out,
    );
    rgb3("irradiance.", &frame.irradiance, ["R", "G", "B"], &mut out);
    rgb3("N.", &frame.normal, ["X", "Y", "Z"], &mut out);
    out.push(("Z".into(), frame.depth.clone()));
    out.push(("mask.emitter".into(), frame.emitter.clone()));
    out.push(("mask.hit".into(), frame.hit.clone()));
    out
}

/// Writes the raw frame with all AOVs (atomically).
pub fn write_exr(path: &Path, frame: &Frame) -> Result<(), Failure> {
    let list: smallvec::SmallVec<[AnyChannel<FlatSamples>; 4]> = channels(frame)
        .into_iter()
        .map(|(name, data)| AnyChannel::new(name.as_str(), FlatSamples::F32(data)))
        .collect();
    let layer = Layer::new(
        (frame.width, frame.height),
        LayerAttributes::named("frame"),
        Encoding {
            line_order: LineOrder::Increasing,
            ..Encoding::SMALL_FAST_LOSSLESS
        },
        AnyChannels::sort(list),
    );
    let image = Image::from_layer(layer);
    atomic_write(path, |tmp| {
        let file = fs::File::create(tmp).map_err(|e| Failure::io("cannot create", tmp, &e))?;
        crate::exr_blocks::write_parallel(&image, std::io::BufWriter::new(file))
            .map_err(|e| exr_failure(tmp, e))
    })
}

/// Reads a raw frame written by [`write_exr`] (missing AOV channels come back as zeros).
pub fn read_exr(path: &Path) -> Result<Frame, Failure> {
    let file = eyeadapt_scene::open_input(path)
        .map_err(|e| Failure::input_io("cannot read EXR frame", path, &e))?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::BufReader::new(file))
        .map_err(|e| match e {
            exr::error::Error::Io(io) => Failure::io("cannot read EXR", path, &io),
            other => Failure::Input(format!(
                "{}: not a readable EXR frame: {other}",
                path.display()
            )),
        })?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let get = |name: &str| -> Vec<f32> {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| c.sample_data.values_as_f32().collect())
            .unwrap_or_else(|| vec![0.0; w * h])
    };
    let rgb3 = |prefix: &str, names: [&str; 3]| -> Vec<[f32; 3]> {
        let [a, b, c] = names.map(|n| get(&format!("{prefix}{n}")));
        (0..w * h).map(|i| [a[i], b[i], c[i]]).collect()
    };
    Ok(Frame {
        width: w,
        height: h,
        rgb: rgb3("", ["R", "G", "B"]),
        albedo: rgb3("albedo.", ["R", "G", "B"]),
        achromatic: rgb3("wcam_achromatic.", ["R", "G", "B"]),
        irradiance: rgb3("irradiance.", ["R", "G", "B"]),
        normal: rgb3("N.", ["X", "Y", "Z"]),
        depth: get("Z"),
        emitter: get("mask.emitter"),
        hit: get("mask.hit"),
        stats: Default::default(),
    })
}

pub use crate::srgb8::srgb_encode;

/// 8-bit sRGB bytes of a linear image with the documented preview curve.
pub fn preview_bytes(rgb: &[[f32; 3]], exposure_ev: f32) -> Vec<u8> {
    let k = libm::powf(2f32, exposure_ev);
    crate::srgb8::srgb8_all(rgb.iter().flatten().map(|&c| {
        if c.is_finite() {
            (c * k).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }))
}

/// Writes an sRGB PNG preview of a linear image (atomically).
pub fn write_png(
    path: &Path,
    rgb: &[[f32; 3]],
    width: usize,
    height: usize,
    exposure_ev: f32,
) -> Result<(), Failure> {
    let bytes = preview_bytes(rgb, exposure_ev);
    let mut encoded = Vec::new();
    image::codecs::png::PngEncoder::new(&mut encoded)
        .write_image_checked(&bytes, width as u32, height as u32)
        .map_err(|e| Failure::Other(format!("cannot encode PNG {}: {e}", path.display())))?;
    atomic_write_bytes(path, &encoded)
}

trait WriteChecked {
    fn write_image_checked(self, bytes: &[u8], w: u32, h: u32) -> image::ImageResult<()>;
}

impl<W: Write> WriteChecked for image::codecs::png::PngEncoder<W> {
    fn write_image_checked(self, bytes: &[u8], w: u32, h: u32) -> image::ImageResult<()> {
        use image::ImageEncoder;
        self.write_image(bytes, w, h, image::ExtendedColorType::Rgb8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exr_round_trip_is_bit_exact_for_every_channel() {
        let dir = tempfile::tempdir().unwrap();
        let n = 6 * 4;
        let v3 = |k: f32| {
            (0..n)
                .map(|i| [i as f32 * k, -(i as f32) * k, 0.5 * k])
                .collect::<Vec<_>>()
        };
        let frame = Frame {
            width: 6,
            height: 4,
            rgb: v3(1.0),
            albedo: v3(0.1),
            achromatic: v3(0.2),
            irradiance: v3(3.0),
            normal: v3(0.01),
            depth: (0..n).map(|i| i as f32 * 0.3).collect(),
            emitter: (0..n).map(|i| (i % 2) as f32).collect(),
            hit: vec![1.0; n],
            stats: Default::default(),
        };
        let path = dir.path().join("f.exr");
        write_exr(&path, &frame).unwrap();
        let back = read_exr(&path).unwrap();
        assert_eq!(back, frame);
        // No temporary file is left behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn stale_temp_cleanup_removes_only_our_own_temporaries() {
        let d = tempfile::tempdir().unwrap();
        let dir = d.path();
        let ours = [
            ".manifest.json.tmp-12",
            ".adaptation.csv.tmp-3",
            "rows/.frame_000004.csv.tmp-99",
            "frames/raw/.frame_000004.exr.tmp-99",
            "frames/eye/.frame_000004.png.tmp-99",
            "plots/.chromaticity.svg.tmp-5",
        ];
        let theirs = [
            ".notes.tmp-1",
            ".manifest.json.tmp-",
            ".manifest.json.tmp-12x",
            "mine/.manifest.json.tmp-12",
            "rows/.frame_000004.png.tmp-99",
            "rows/.frame_x.csv.tmp-99",
            "frames/.frame_000004.png.tmp-99",
            "frames/raw/deeper/.frame_000004.png.tmp-99",
            "frames/raw/frame_000004.exr",
        ];
        for rel in ours.iter().chain(&theirs) {
            let p = dir.join(rel);
            fs::create_dir_all(p.parent().unwrap()).unwrap();
            fs::write(&p, "x").unwrap();
        }
        // A symbolic link out of the directory is not followed.
        let elsewhere = tempfile::tempdir().unwrap();
        let victim = elsewhere.path().join(".frame_000001.png.tmp-1");
        fs::write(&victim, "x").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(elsewhere.path(), dir.join("frames/linked")).unwrap();
        assert_eq!(remove_stale_temps(dir).unwrap(), ours.len());
        for rel in ours {
            assert!(!dir.join(rel).exists(), "{rel} stayed");
        }
        for rel in theirs {
            assert!(dir.join(rel).exists(), "{rel} was deleted");
        }
        assert!(victim.exists(), "followed a symbolic link");
    }

    #[test]
    fn preview_curve_is_srgb_with_clipping() {
        let b = preview_bytes(&[[0.0, 0.214_041_14, 1.5]], 0.0);
        assert_eq!(b, vec![0, 128, 255]);
        assert_eq!(preview_bytes(&[[0.25, f32::NAN, -1.0]], 1.0)[1..], [0, 0]);
    }
}
