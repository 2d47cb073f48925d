//! `eyeadapt merge DIR... --out DIR [--frames SPEC]`: join chunk outputs into one sequence.
//!
//! The chunks may have chosen their frames in any way (`--chunk-index`, `--start/--end`,
//! `--frames`, the job file's own `frames`): every manifest records the job's own frames, and
//! the merge must cover those, or the `--frames` selection when one is given (frames of the
//! inputs outside it are left out).
//!
//! Refuses (exit 2, naming the frames or directories): directories without a manifest,
//! different job hashes or job frames, the same frame rendered differently in two places,
//! gaps, and damaged chunks: before anything is written, every file of every merged frame is
//! checked against its chunk's manifest (present, same size, same checksum), and a bad one is
//! named with its chunk, frame and file.
//!
//! Then the merge is staged and committed: every file is hard-linked (else copied) into
//! `--out` under a temporary name next to its place, then all are renamed into place, then
//! `adaptation.csv` and last `manifest.json` are written (atomically). A failure while staging
//! removes the staged files and leaves `--out` as it was; the manifest, written last, is the
//! commit point.
use crate::error::Failure;
use crate::frames::FrameSet;
use crate::manifest::{FileEntry, FrameEntry, Manifest, file_entry, file_problem};
use crate::output::temp_path;
use crate::sequence::{lock_dir, sync_csv};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Default)]
pub struct MergeSummary {
    pub frames: usize,
    pub sources: usize,
    pub duplicates: usize,
    /// Frames of the inputs outside the `--frames` selection, not merged.
    pub left_out: usize,
    /// The frames merged, as a spec.
    pub selection: String,
}

/// A frame's entry and the input it is taken from.
type Owners = BTreeMap<u32, (usize, FrameEntry)>;

/// Merges the chunk directories `dirs` into `out`; `frames` narrows what must be covered
/// (default: the job's own frames).
pub fn merge(
    dirs: &[PathBuf],
    out: &Path,
    frames: Option<&FrameSet>,
) -> Result<MergeSummary, Failure> {
    let manifests = load_inputs(dirs, out)?;
    let (d0, m0) = &manifests[0];
    let job = m0
        .job_frames
        .parse::<FrameSet>()
        .map_err(|e| Failure::Input(format!("{}: manifest job_frames: {e}", d0.display())))?;
    let wanted = match frames {
        Some(sel) => job.narrow(sel).map_err(|outside| {
            Failure::Input(format!(
                "merge --frames selects {} frame(s) outside the job's frames {job} (first: {})",
                outside.len(),
                outside.first().unwrap_or_default()
            ))
        })?,
        None => job,
    };
    let (mut owner, duplicates) = union(&manifests)?;
    let before = owner.len();
    owner.retain(|f, _| wanted.contains(*f));
    let missing = wanted.minus(&FrameSet::from_frames(owner.keys().copied()));
    if !missing.is_empty() {
        let (what, hint) = match frames {
            Some(_) => (format!("the selection {wanted} (merge --frames)"), ""),
            None => (
                "the job's selection".to_string(),
                "; to merge part of the job, name it with merge --frames SPEC",
            ),
        };
        return Err(Failure::Input(format!(
            "gap: {} frame(s) of {what} are in no input: {missing}{hint}",
            missing.len(),
        )));
    }
    verify_inputs(&manifests, &owner)?;

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
    let merged = Manifest {
        format: crate::manifest::FORMAT,
        planned: wanted.to_string(),
        frames: owner.iter().map(|(f, (_, e))| (*f, e.clone())).collect(),
        ..m0.clone()
    };
    let staged = stage(&manifests, &owner, out)?;
    commit(&staged)?;
    sync_csv(out, &merged)?;
    merged.save(out)?;
    Ok(MergeSummary {
        frames: owner.len(),
        sources: manifests.len(),
        duplicates,
        left_out: before - owner.len(),
        selection: wanted.to_string(),
    })
}

/// Every input's manifest, checked to come from one job with the same frames.
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
            let old = [(d0, m0), (d, m)]
                .into_iter()
                .find(|(_, m)| m.format < 2)
                .map_or(String::new(), |(d, _)| {
                    format!(
                        " ({} was written by an older eyeadapt, which recorded the chunk's own \
                         selection there: rerun that chunk's command to update its manifest; \
                         finished frames are not rendered again)",
                        d.display()
                    )
                });
            return Err(Failure::Input(format!(
                "{} belongs to a job of frames {} but {} to one of frames {}: merge chunks of one job{old}",
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

/// Every file of every merged frame is in its chunk with the size and checksum its manifest
/// records; the first that is not is named with its chunk, frame and file.
fn verify_inputs(manifests: &[(PathBuf, Manifest)], owner: &Owners) -> Result<(), Failure> {
    for (f, (i, e)) in owner {
        let dir = &manifests[*i].0;
        for fe in &e.files {
            if let Some(why) = file_problem(dir, fe) {
                return Err(Failure::Input(format!(
                    "damaged chunk {}: frame {f}: {} {why}; rerun that chunk's command to \
                     render the frame again, then merge",
                    dir.display(),
                    fe.path
                )));
            }
        }
    }
    Ok(())
}

/// A file staged under its temporary name, and where it goes.
struct Staged {
    tmp: PathBuf,
    to: PathBuf,
}

/// Hard-links (else copies) every merged file into `out` under its temporary name; files
/// already in place with the recorded contents are kept. On failure every staged file is
/// removed again.
fn stage(
    manifests: &[(PathBuf, Manifest)],
    owner: &Owners,
    out: &Path,
) -> Result<Vec<Staged>, Failure> {
    let mut staged = Vec::new();
    let result = (|| {
        for (i, e) in owner.values() {
            for fe in &e.files {
                if let Some(s) = stage_file(&manifests[*i].0, fe, out)? {
                    staged.push(s);
                }
            }
        }
        Ok(())
    })();
    match result {
        Ok(()) => Ok(staged),
        Err(e) => {
            for s in &staged {
                let _ = std::fs::remove_file(&s.tmp);
            }
            Err(e)
        }
    }
}

fn stage_file(src: &Path, fe: &FileEntry, out: &Path) -> Result<Option<Staged>, Failure> {
    let from = src.join(&fe.path);
    let to = out.join(&fe.path);
    if to.exists() && file_entry(out, &fe.path).is_ok_and(|x| x == *fe) {
        return Ok(None);
    }
    if let Some(dir) = to.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| Failure::io("cannot create directory", dir, &e))?;
    }
    let tmp = temp_path(&to);
    let _ = std::fs::remove_file(&tmp);
    if std::fs::hard_link(&from, &tmp).is_err() {
        let copy = std::fs::copy(&from, &tmp).and_then(|_| std::fs::File::open(&tmp)?.sync_all());
        if let Err(e) = copy {
            let _ = std::fs::remove_file(&tmp);
            return Err(Failure::io("cannot copy", &from, &e));
        }
        // The copy is what gets committed: it must be what the manifest says, too.
        if let Some(why) = file_problem(out, &tmp_entry(fe, &tmp, out)) {
            let _ = std::fs::remove_file(&tmp);
            return Err(Failure::Transient(format!(
                "the copy of {} {why}",
                from.display()
            )));
        }
    }
    Ok(Some(Staged { tmp, to }))
}

/// `fe` for the staged copy at `tmp` (a path inside `out`).
fn tmp_entry(fe: &FileEntry, tmp: &Path, out: &Path) -> FileEntry {
    FileEntry {
        path: tmp
            .strip_prefix(out)
            .unwrap_or(tmp)
            .to_string_lossy()
            .into_owned(),
        ..fe.clone()
    }
}

/// Renames every staged file into place.
fn commit(staged: &[Staged]) -> Result<(), Failure> {
    for (k, s) in staged.iter().enumerate() {
        if let Err(e) = std::fs::rename(&s.tmp, &s.to) {
            for rest in &staged[k..] {
                let _ = std::fs::remove_file(&rest.tmp);
            }
            return Err(Failure::io("cannot rename into place", &s.to, &e));
        }
    }
    Ok(())
}
