//! `manifest.json`: the job's hash and every committed frame with its files' sizes and
//! checksums. It is the single source of truth for resume and merge, and it is rewritten
//! atomically after each frame. It holds no timestamps or timings, so an interrupted and
//! resumed run produces the same manifest bytes as an uninterrupted one.
use crate::error::Failure;
use crate::output::atomic_write_bytes;
use crate::settings::RunSettings;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::Path;

pub const MANIFEST: &str = "manifest.json";
pub const CSV: &str = "adaptation.csv";

/// The manifest format this version writes. Format 1 recorded in `job_frames` the run's
/// selection (the job's frames narrowed by `--frames`); format 2 records there the job's own
/// frames, whatever each chunk selected, so that chunks chosen in any way merge. Both read.
pub const FORMAT: u32 = 2;

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FileEntry {
    /// Path relative to the output directory.
    pub path: String,
    pub bytes: u64,
    /// First 128 bits of SHA-256, hex.
    pub sha256_128: String,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FrameEntry {
    pub time_s: f64,
    pub files: Vec<FileEntry>,
    /// Samples dropped as NaN/Inf in the image.
    pub invalid_samples: u64,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub format: u32,
    pub tool: String,
    pub job_name: String,
    pub job_source: String,
    pub job_hash: String,
    /// Frames this directory is meant to hold (the selection or chunk), as a frame spec.
    pub planned: String,
    /// The job's own frames (its `frames` key, else the whole camera path), as a frame spec:
    /// what `merge` must cover unless told `--frames`. (Format 1: the run's selection.)
    pub job_frames: String,
    pub estimators: Vec<String>,
    pub fps: f64,
    /// The resolved job settings (resolution, spp, depths, seed, CAT, D, eye samples,
    /// temporal filters…), for reports.
    pub settings: RunSettings,
    pub frames: BTreeMap<u32, FrameEntry>,
}

/// The first 12 characters of a hash, for messages (whatever the hash's length).
pub fn short_hash(h: &str) -> String {
    h.chars().take(12).collect()
}

/// A manifest's file paths must stay inside its directory: relative, no `..`, no root.
fn check_paths(m: &Manifest, file: &Path) -> Result<(), Failure> {
    for (f, e) in &m.frames {
        for fe in &e.files {
            let p = Path::new(&fe.path);
            let inside = p
                .components()
                .all(|c| matches!(c, std::path::Component::Normal(_)));
            if !inside || fe.path.is_empty() {
                return Err(Failure::Input(format!(
                    "{}: frame {f}: file path \"{}\" leaves the output directory",
                    file.display(),
                    fe.path
                )));
            }
        }
    }
    Ok(())
}

pub fn checksum(bytes: &[u8]) -> String {
    crate::job::hex(&Sha256::digest(bytes)[..16])
}

/// Why the file `fe` names under `dir` is not what the manifest says (missing, another size,
/// another checksum), or `None` when it is.
pub fn file_problem(dir: &Path, fe: &FileEntry) -> Option<String> {
    let p = dir.join(&fe.path);
    let bytes = match std::fs::read(&p) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Some("is missing".into());
        }
        Err(e) => return Some(format!("cannot be read: {e}")),
    };
    if bytes.len() as u64 != fe.bytes {
        return Some(format!(
            "has {} bytes, the manifest says {}",
            bytes.len(),
            fe.bytes
        ));
    }
    let sum = checksum(&bytes);
    (sum != fe.sha256_128)
        .then(|| format!("has checksum {sum}, the manifest says {}", fe.sha256_128))
}

pub fn file_entry(dir: &Path, rel: &str) -> Result<FileEntry, Failure> {
    let p = dir.join(rel);
    let bytes = std::fs::read(&p).map_err(|e| Failure::io("cannot read back", &p, &e))?;
    Ok(FileEntry {
        path: rel.to_string(),
        bytes: bytes.len() as u64,
        sha256_128: checksum(&bytes),
    })
}

impl Manifest {
    pub fn load(dir: &Path) -> Result<Option<Manifest>, Failure> {
        let p = dir.join(MANIFEST);
        match std::fs::read(&p) {
            Ok(b) => {
                let m: Manifest = serde_json::from_slice(&b).map_err(|e| {
                    Failure::Input(format!(
                        "{}: not a valid eyeadapt manifest: {e}",
                        p.display()
                    ))
                })?;
                if !(1..=FORMAT).contains(&m.format) {
                    return Err(Failure::Input(format!(
                        "{}: manifest format {} is not one this eyeadapt reads (1 to {FORMAT})",
                        p.display(),
                        m.format
                    )));
                }
                check_paths(&m, &p)?;
                Ok(Some(m))
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(Failure::io("cannot read", &p, &e)),
        }
    }

    pub fn save(&self, dir: &Path) -> Result<(), Failure> {
        let mut text = serde_json::to_string_pretty(self)
            .map_err(|e| Failure::Other(format!("cannot encode manifest: {e}")))?;
        text.push('\n');
        atomic_write_bytes(&dir.join(MANIFEST), text.as_bytes())
    }

    /// True when the frame's files exist with the recorded sizes (and, with `verify`, the
    /// recorded checksums).
    pub fn frame_intact(&self, dir: &Path, f: u32, verify: bool) -> bool {
        let Some(e) = self.frames.get(&f) else {
            return false;
        };
        e.files.iter().all(|fe| {
            if verify {
                file_problem(dir, fe).is_none()
            } else {
                std::fs::metadata(dir.join(&fe.path)).is_ok_and(|m| m.len() == fe.bytes)
            }
        })
    }
}
