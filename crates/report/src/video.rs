//! `--video`: H.264 movies with `ffmpeg`: the raw previews (`raw.mp4`), each estimator's
//! adapted previews, and a labelled side-by-side `raw | wcam | eye` movie. With `--overlay`
//! every movie gets a strip under the picture naming each frame's number and time.
//!
//! ffmpeg's `drawtext` needs a font file at run time; instead the labels are drawn here with a
//! built-in 5×7 bitmap font into a PNG strip that ffmpeg stacks above the three panels, so
//! the movie looks the same on every machine.
use crate::palette::PALETTE;
use eyeadapt_color::srgb_decode;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::manifest::Manifest;
use eyeadapt_sequencer::output::{temp_path, write_png};
use eyeadapt_sequencer::pipeline::frame_name;
use std::path::{Path, PathBuf};
use std::process::Command;

/// What happened to `--video`.
#[derive(Clone, Debug, PartialEq)]
pub enum VideoOutcome {
    NotRequested,
    /// Nothing was encoded, and why (e.g. no ffmpeg on PATH).
    Skipped(String),
    /// The movies written, and problems with the ones that were not.
    Written {
        files: Vec<PathBuf>,
        problems: Vec<String>,
    },
}

/// 5×7 glyphs, one byte per row (bit 4 = leftmost column).
fn glyph(c: char) -> [u8; 7] {
    match c.to_ascii_lowercase() {
        'a' => [0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F],
        'b' => [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E],
        'c' => [0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E],
        'd' => [0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F],
        'e' => [0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E],
        'f' => [0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08],
        'g' => [0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E],
        'h' => [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11],
        'i' => [0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E],
        'j' => [0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0C],
        'k' => [0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12],
        'l' => [0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'm' => [0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11],
        'n' => [0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11],
        'o' => [0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E],
        'p' => [0x00, 0x00, 0x1E, 0x11, 0x1E, 0x10, 0x10],
        'q' => [0x00, 0x00, 0x0D, 0x13, 0x0F, 0x01, 0x01],
        'r' => [0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10],
        's' => [0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E],
        't' => [0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06],
        'u' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D],
        'v' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04],
        'w' => [0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A],
        'x' => [0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11],
        'y' => [0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E],
        'z' => [0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F],
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        '_' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F],
        '+' => [0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00],
        '-' => [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00],
        ':' => [0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C],
        ' ' => [0; 7],
        _ => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04],
    }
}

/// A `width × height` linear-RGB strip: each label centred in its panel of `panel_w` pixels,
/// in its estimator's colour (the report's palette; anything else, e.g. `raw`, dark grey) on
/// white, so a movie names its panels in the colours of the plots.
pub fn label_strip(labels: &[&str], panel_w: usize) -> (Vec<[f32; 3]>, usize, usize) {
    let longest = labels
        .iter()
        .map(|l| l.chars().count())
        .max()
        .unwrap_or(1)
        .max(1);
    // Glyph cell 6×8 at `scale`; as large as fits, at least 1, at most 4.
    let scale = ((panel_w.saturating_sub(4)) / (6 * longest)).clamp(1, 4);
    let height = 8 * scale + 2 * scale.max(2);
    let width = panel_w * labels.len();
    let mut px = vec![[1.0f32; 3]; width * height];
    for (k, label) in labels.iter().enumerate() {
        let ink = label_colour(label);
        let text_w = label.chars().count() * 6 * scale;
        let x0 = k * panel_w + panel_w.saturating_sub(text_w) / 2;
        let y0 = (height - 7 * scale) / 2;
        for (i, c) in label.chars().enumerate() {
            for (row, bits) in glyph(c).iter().enumerate() {
                for col in 0..5 {
                    if bits & (0x10 >> col) == 0 {
                        continue;
                    }
                    for dy in 0..scale {
                        for dx in 0..scale {
                            let x = x0 + (i * 6 + col) * scale + dx;
                            let y = y0 + row * scale + dy;
                            if x < (k + 1) * panel_w && y < height {
                                px[y * width + x] = ink;
                            }
                        }
                    }
                }
            }
        }
    }
    (px, width, height)
}

/// A label's colour in linear RGB: its estimator's, or dark grey for any other label.
fn label_colour(label: &str) -> [f32; 3] {
    match PALETTE.iter().find(|(n, _)| *n == label) {
        Some((_, c)) => [c.0, c.1, c.2].map(|v| srgb_decode(f64::from(v) / 255.0) as f32),
        None => [0.03; 3],
    }
}

/// Whether `ffmpeg` runs.
pub fn ffmpeg_available(ffmpeg: &Path) -> bool {
    Command::new(ffmpeg)
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The PNG input of one estimator's (or `raw`'s) frames: ffmpeg arguments, and a temporary
/// directory to delete afterwards when the frame numbers have gaps (then the frames are
/// hard-linked, or copied, under consecutive numbers).
fn png_input(
    dir: &Path,
    m: &Manifest,
    name: &str,
    fps: f64,
) -> Result<(Vec<String>, Option<PathBuf>), String> {
    let frames: Vec<u32> = m.frames.keys().copied().collect();
    for f in &frames {
        let rel = format!("frames/{name}/{}", frame_name(*f, "png"));
        if !m.frames[f].files.iter().any(|e| e.path == rel) {
            return Err(format!("{name}: frame {f} has no PNG preview ({rel})"));
        }
    }
    let consecutive = frames.windows(2).all(|w| w[1] == w[0] + 1);
    let rate = ["-framerate".to_string(), format!("{fps}")];
    if consecutive {
        let pattern = dir.join("frames").join(name).join("frame_%06d.png");
        let mut args = rate.to_vec();
        args.extend([
            "-start_number".into(),
            frames[0].to_string(),
            "-i".into(),
            pattern.display().to_string(),
        ]);
        return Ok((args, None));
    }
    let tmp = dir
        .join("video")
        .join(format!(".frames-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).map_err(|e| format!("cannot create {}: {e}", tmp.display()))?;
    for (k, f) in frames.iter().enumerate() {
        let src = dir.join("frames").join(name).join(frame_name(*f, "png"));
        let dst = tmp.join(frame_name(k as u32, "png"));
        let _ = std::fs::remove_file(&dst);
        if std::fs::hard_link(&src, &dst).is_err() {
            std::fs::copy(&src, &dst).map_err(|e| format!("cannot copy {}: {e}", src.display()))?;
        }
    }
    let mut args = rate.to_vec();
    args.extend([
        "-start_number".into(),
        "0".into(),
        "-i".into(),
        tmp.join("frame_%06d.png").display().to_string(),
    ]);
    Ok((args, Some(tmp)))
}

/// Runs ffmpeg writing `out` atomically; returns the reason on failure.
fn encode(
    ffmpeg: &Path,
    inputs: Vec<String>,
    filter: &[String],
    fps: f64,
    n: usize,
    out: &Path,
) -> Result<(), String> {
    let tmp = temp_path(out);
    let mut cmd = Command::new(ffmpeg);
    cmd.args(["-y", "-hide_banner", "-loglevel", "error", "-nostdin"])
        .args(inputs)
        .args(filter)
        .args(["-c:v", "libx264", "-pix_fmt", "yuv420p", "-r"])
        .arg(format!("{fps}"))
        .args(["-frames:v", &n.to_string(), "-f", "mp4"])
        .arg(&tmp);
    let result = match cmd.output() {
        Ok(o) if o.status.success() => std::fs::rename(&tmp, out)
            .map_err(|e| format!("cannot rename into {}: {e}", out.display())),
        Ok(o) => Err(format!(
            "ffmpeg failed for {} ({}): {}",
            out.display(),
            o.status,
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        Err(e) => Err(format!("cannot run {}: {e}", ffmpeg.display())),
    };
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The `--overlay` strip of every frame, `width` wide, as an image-sequence input: ffmpeg
/// arguments and the temporary directory holding the PNGs.
fn overlay_input(dir: &Path, m: &Manifest, width: usize) -> Result<(Vec<String>, PathBuf), String> {
    let tmp = dir
        .join("video")
        .join(format!(".overlay-{width}-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).map_err(|e| format!("cannot create {}: {e}", tmp.display()))?;
    for (k, (f, e)) in m.frames.iter().enumerate() {
        let long = format!("frame {f}  {:.3} s", e.time_s);
        // Narrow movies get the short form rather than clipped text.
        let text = if 6 * long.len() + 4 <= width {
            long
        } else {
            format!("{f} {:.2}s", e.time_s)
        };
        let (px, w, h) = label_strip(&[text.as_str()], width);
        write_png(&tmp.join(frame_name(k as u32, "png")), &px, w, h, 0.0)
            .map_err(|e| e.to_string())?;
    }
    let args = [
        "-framerate".to_string(),
        format!("{}", m.fps),
        "-start_number".into(),
        "0".into(),
        "-i".into(),
        tmp.join("frame_%06d.png").display().to_string(),
    ];
    Ok((args.to_vec(), tmp))
}

/// The width of the raw previews.
fn preview_width(dir: &Path, m: &Manifest) -> Result<usize, String> {
    let first = m.frames.keys().next().copied().unwrap_or(0);
    let png = dir.join("frames/raw").join(frame_name(first, "png"));
    image::image_dimensions(&png)
        .map(|(w, _)| w as usize)
        .map_err(|e| format!("cannot read {}: {e}", png.display()))
}

/// Encodes `video/raw.mp4`, `video/<estimator>.mp4` for every estimator of the manifest and
/// `video/raw_wcam_eye.mp4`; with `overlay`, each with the frame/time strip under it.
pub fn videos(
    dir: &Path,
    m: &Manifest,
    ffmpeg: &Path,
    overlay: bool,
) -> Result<VideoOutcome, Failure> {
    if !ffmpeg_available(ffmpeg) {
        return Ok(VideoOutcome::Skipped(format!(
            "video skipped: {} was not found on PATH (install ffmpeg, e.g. `apt-get install ffmpeg`, and run `eyeadapt report --video {}` again)",
            ffmpeg.display(),
            dir.display()
        )));
    }
    let out_dir = dir.join("video");
    std::fs::create_dir_all(&out_dir)
        .map_err(|e| Failure::io("cannot create directory", &out_dir, &e))?;
    let fps = m.fps;
    let n = m.frames.len();
    let even = "pad=ceil(iw/2)*2:ceil(ih/2)*2".to_string();
    let mut files = Vec::new();
    let mut problems = Vec::new();
    let mut temps = Vec::new();
    // One strip sequence per width: the single panels', and the side by side's.
    let strip = |width: usize, temps: &mut Vec<PathBuf>| -> Result<Option<Vec<String>>, String> {
        if !overlay {
            return Ok(None);
        }
        let (args, tmp) = overlay_input(dir, m, width)?;
        temps.push(tmp);
        Ok(Some(args))
    };
    let single = preview_width(dir, m).and_then(|w| strip(w, &mut temps));
    let panels_list = std::iter::once("raw").chain(m.estimators.iter().map(String::as_str));
    for est in panels_list {
        let out = out_dir.join(format!("{est}.mp4"));
        let r = single.clone().and_then(|strip_args| {
            let (mut args, tmp) = png_input(dir, m, est, fps)?;
            temps.extend(tmp);
            let filter = match strip_args {
                Some(strip_args) => {
                    args.extend(strip_args);
                    vec![
                        "-filter_complex".into(),
                        format!("[0:v][1:v]vstack=inputs=2,{even}[out]"),
                        "-map".into(),
                        "[out]".into(),
                    ]
                }
                None => vec!["-vf".into(), even.clone()],
            };
            encode(ffmpeg, args, &filter, fps, n, &out)
        });
        match r {
            Ok(()) => files.push(out),
            Err(e) => problems.push(e),
        }
    }
    // Side by side, labelled.
    let out = out_dir.join("raw_wcam_eye.mp4");
    let panels = ["raw", "wcam", "eye"];
    let side = (|| -> Result<(), String> {
        let mut inputs = Vec::new();
        for p in panels {
            let (args, tmp) = png_input(dir, m, p, fps)?;
            temps.extend(tmp);
            inputs.extend(args);
        }
        let w = preview_width(dir, m)?;
        let (px, lw, lh) = label_strip(&panels, w);
        let labels = out_dir.join(format!(".labels-{}.png", std::process::id()));
        write_png(&labels, &px, lw, lh, 0.0).map_err(|e| e.to_string())?;
        temps.push(labels.clone());
        inputs.extend([
            "-loop".into(),
            "1".into(),
            "-i".into(),
            labels.display().to_string(),
        ]);
        let filter = match strip(3 * w, &mut temps)? {
            Some(strip_args) => {
                inputs.extend(strip_args);
                format!(
                    "[0:v][1:v][2:v]hstack=inputs=3[row];[3:v][row][4:v]vstack=inputs=3:shortest=1,{even}[out]"
                )
            }
            None => format!(
                "[0:v][1:v][2:v]hstack=inputs=3[row];[3:v][row]vstack=inputs=2:shortest=1,{even}[out]"
            ),
        };
        encode(
            ffmpeg,
            inputs,
            &[
                "-filter_complex".into(),
                filter,
                "-map".into(),
                "[out]".into(),
            ],
            fps,
            n,
            &out,
        )
    })();
    match side {
        Ok(()) => files.push(out),
        Err(e) => problems.push(format!("raw_wcam_eye.mp4: {e}")),
    }
    for t in temps {
        let _ = if t.is_dir() {
            std::fs::remove_dir_all(&t)
        } else {
            std::fs::remove_file(&t)
        };
    }
    Ok(VideoOutcome::Written { files, problems })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn label_strip_draws_centred_text_in_the_estimators_colours() {
        let (px, w, h) = label_strip(&["raw", "eye", "wcam"], 96);
        assert_eq!(w, 288);
        let inked = |x0: usize, x1: usize, ink: [f32; 3]| {
            (0..h).any(|y| (x0..x1).any(|x| px[y * w + x] == ink))
        };
        assert!(inked(20, 76, [0.03; 3]), "raw in dark grey");
        assert!(inked(116, 172, [0.0; 3]), "eye in black, as in the plots");
        let wcam = label_colour("wcam");
        assert!(
            wcam[0] > wcam[1] && inked(212, 268, wcam),
            "wcam in its red"
        );
        let blank =
            |x0: usize, x1: usize| (0..h).all(|y| (x0..x1).all(|x| px[y * w + x] == [1.0; 3]));
        assert!(blank(0, 10) && blank(96, 106), "margins stay white");
        // Every glyph used by the estimator names exists.
        for c in "abcdefghijklmnopqrstuvwxyz0123456789_+-:. ".chars() {
            assert!(c == ' ' || glyph(c) != [0; 7], "{c}");
        }
    }
}
