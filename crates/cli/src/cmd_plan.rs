//! `eyeadapt plan JOB`: the frame and chunk counts of a job for farm submitters, as POSIX
//! shell assignments (every value single-quoted, so `eval "$(eyeadapt plan job.toml)"` assigns
//! exactly the values whatever the job's name holds) or, with `--format json`, one JSON object.
use crate::args::PlanArgs;
use crate::cmd_sequence::{job_of, selection};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::sequence::{plan_chunks, plan_frames};

pub fn run(a: PlanArgs) -> Result<(), Failure> {
    let job = job_of(&a.seq)?;
    let (_, all) = plan_frames(&job, selection(&a.seq, &job)?.as_ref(), None)?;
    let chunks = match a.seq.chunk_size {
        Some(n) => plan_chunks(&all, n as usize)?,
        None => 1,
    };
    let plan = Plan {
        job_name: job.name.clone(),
        frames: all.len(),
        chunks,
        first: all.first().unwrap_or_default(),
        last: all.last().unwrap_or_default(),
        job_hash: job.hash.clone(),
    };
    print!(
        "{}",
        if a.format == "json" {
            plan.json()
        } else {
            plan.shell()
        }
    );
    Ok(())
}

struct Plan {
    job_name: String,
    frames: usize,
    chunks: usize,
    first: u32,
    last: u32,
    job_hash: String,
}

impl Plan {
    fn fields(&self) -> [(&'static str, String); 6] {
        [
            ("JOB_NAME", self.job_name.clone()),
            ("FRAMES", self.frames.to_string()),
            ("CHUNKS", self.chunks.to_string()),
            ("FIRST", self.first.to_string()),
            ("LAST", self.last.to_string()),
            ("JOB_HASH", self.job_hash.clone()),
        ]
    }

    /// `EYEADAPT_NAME='value'` lines.
    fn shell(&self) -> String {
        self.fields()
            .iter()
            .map(|(k, v)| format!("EYEADAPT_{k}={}\n", sh_quote(v)))
            .collect()
    }

    /// One JSON object: names in lower case, counts as numbers.
    fn json(&self) -> String {
        let mut o = serde_json::Map::new();
        o.insert("job_name".into(), self.job_name.clone().into());
        o.insert("frames".into(), self.frames.into());
        o.insert("chunks".into(), self.chunks.into());
        o.insert("first".into(), self.first.into());
        o.insert("last".into(), self.last.into());
        o.insert("job_hash".into(), self.job_hash.clone().into());
        format!("{}\n", serde_json::Value::Object(o))
    }
}

/// `s` as one POSIX shell word: single quotes, each `'` written as `'\''`. Inside single
/// quotes nothing is special (no `$`, backquote, backslash or glob), in sh and bash alike.
fn sh_quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', "'\\''"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting_leaves_nothing_for_the_shell_to_expand() {
        assert_eq!(sh_quote("plain"), "'plain'");
        assert_eq!(sh_quote(""), "''");
        assert_eq!(sh_quote("it's"), "'it'\\''s'");
        assert_eq!(sh_quote("$(rm -rf x) `y` *"), "'$(rm -rf x) `y` *'");
    }
}
