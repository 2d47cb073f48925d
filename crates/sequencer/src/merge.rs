//! `eyeadapt merge DIR... --out DIR`: join chunk outputs into one sequence directory.
//!
//! Refuses (exit 2, naming the frames or directories): directories without a manifest,
//! different job hashes, the same frame rendered differently in two places, and gaps in the
//! job's frame selection. Files are hard-linked when possible, else copied (atomically).
use crate::error::Failure;
use crate::frames::FrameSet;
use crate::manifest::{FrameEntry, Manifest};
use crate::output::atomic_write;
use crate::sequence::{lock_dir, sync_csv};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Default)]
pub struct MergeSummary {
    pub frames: usize,
    pub sources: usize,
    pub duplicates: usize,
}

/// A frame's entry and the input it is taken from.
type Owners = BTreeMap<u32, (usize, FrameEntry)>;

pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<MergeSummary, Failure> {
    let manifests = load_inputs(dirs, out)?;
    let (d0, m0) = &manifests[0];
    let (owner, duplicates) = union(&manifests)?;
    let wanted = m0
        .job_frames
        .parse::<FrameSet>()
        .map_err(|e| Failure::Input(format!("{}: manifest job_frames: {e}", d0.display())))?;
    let missing = wanted.minus(&FrameSet::from_frames(owner.keys().copied()));
    if !missing.is_empty() {
        return Err(Failure::Input(format!(
            "gap: {} frame(s) of the job's selection are in no input: {}",
            missing.len(),
            missing
        )));
    }
    crate::still::prepare_out_dir(out)?;
    let _lock = lock_dir(out)?;
    crate::output::remove_stale_temps(out)?;
    if let Some(existing) = Manifest::load(out)?
        && existing.job_hash != m0.job_hash
    {
        return Err(Failure::Input(format!(
            "{} already holds a different job (\"{}\"); choose an empty --out",
            out.display(),
            existing.job_name
        )));
    }
    let mut merged = Manifest {
        planned: m0.job_frames.clone(),
        frames: BTreeMap::new(),
        ..m0.clone()
    };
    for (f, (i, e)) in &owner {
        let src = &manifests[*i].0;
        for fe in &e.files {
            let from = src.join(&fe.path);
            let to = out.join(&fe.path);
            if to.exists() && crate::manifest::file_entry(out, &fe.path).is_ok_and(|x| x == *fe) {
                continue;
            }
            atomic_write(&to, |tmp| {
                std::fs::hard_link(&from, tmp)
                    .or_else(|_| std::fs::copy(&from, tmp).map(|_| ()))
                    .map_err(|e| Failure::io("cannot copy", &from, &e))
            })?;
        }
        merged.frames.insert(*f, e.clone());
    }
    merged.save(out)?;
    sync_csv(out, &merged)?;
    Ok(MergeSummary {
        frames: owner.len(),
        sources: manifests.len(),
        duplicates,
    })
}

/// Every input's manifest, checked to come from one job and one selection.
fn load_inputs(dirs: &[PathBuf], out: &Path) -> Result<Vec<(PathBuf, Manifest)>, Failure> {
    if dirs.is_empty() {
        return Err(Failure::Input(
            "merge needs at least one input directory".into(),
        ));
    }
    let out_canon = out.canonicalize().ok();
    let mut manifests = Vec::new();
    for d in dirs {
        if out_canon.is_some() && d.canonicalize().ok() == out_canon {
            return Err(Failure::Input(format!(
                "{}: an input directory cannot also be the --out directory",
                d.display()
            )));
        }
        match Manifest::load(d)? {
            Some(m) => manifests.push((d.clone(), m)),
            None => {
                return Err(Failure::Input(format!(
                    "{}: no manifest.json (not an eyeadapt sequence output)",
                    d.display()
                )));
            }
        }
    }
    let (d0, m0) = &manifests[0];
    for (d, m) in &manifests[1..] {
        if m.job_hash != m0.job_hash {
            return Err(Failure::Input(format!(
                "{} (job \"{}\", hash {}…) and {} (job \"{}\", hash {}…) come from different jobs or settings",
                d0.display(),
                m0.job_name,
                crate::manifest::short_hash(&m0.job_hash),
                d.display(),
                m.job_name,
                crate::manifest::short_hash(&m.job_hash)
            )));
        }
        if m.job_frames != m0.job_frames {
            return Err(Failure::Input(format!(
                "{} selects frames {} but {} selects {}: merge chunks of one selection",
                d0.display(),
                m0.job_frames,
                d.display(),
                m.job_frames
            )));
        }
    }
    Ok(manifests)
}

/// The union of the inputs' frames, and how many were in several inputs with the same files;
/// a frame whose files differ between inputs is a conflict.
fn union(manifests: &[(PathBuf, Manifest)]) -> Result<(Owners, usize), Failure> {
    // Union of frames, checking overlaps.
    let mut owner = Owners::new();
    let mut conflicts = Vec::new();
    let mut duplicates = 0;
    for (i, (_, m)) in manifests.iter().enumerate() {
        for (f, e) in &m.frames {
            match owner.get(f) {
                Some((_, prev)) if prev.files == e.files => duplicates += 1,
                Some((j, _)) => conflicts.push(format!(
                    "frame {f} ({} vs {})",
                    manifests[*j].0.display(),
                    manifests[i].0.display()
                )),
                None => {
                    owner.insert(*f, (i, e.clone()));
                }
            }
        }
    }
    if !conflicts.is_empty() {
        return Err(Failure::Input(format!(
            "{} frame(s) exist in several inputs with different content: {}",
            conflicts.len(),
            conflicts.join(", ")
        )));
    }
    Ok((owner, duplicates))
}
