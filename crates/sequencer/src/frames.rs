//! Frame selection for render farms: frame specs, start/end/step ranges and chunks.
//!
//! A *frame spec* is the string farm managers hand a worker (`--frames`). Items are separated by
//! commas, and whitespace around items and around the range punctuation is ignored:
//!
//! | item | frames | used by |
//! |---|---|---|
//! | `7` | 7 | everyone |
//! | `0-99` | 0, 1, …, 99 (inclusive) | Flamenco, OpenCue, OpenJD, Deadline |
//! | `1-100:2` | 1, 3, …, 99 (step 2, the end is kept only if the step lands on it) | OpenCue, OpenJD |
//! | `1..10`, `1..10:2` | as `1-10`, `1-10:2` | Blender `-f`, Flamenco's generated commands |
//! | `1,5,7-9` | 1, 5, 7, 8, 9 | everyone |
//!
//! The result is a [`FrameSet`]: sorted and without duplicates, whatever order the items came in.
//! Frames are `u32` (no negative frames, no Blender `+N`/`-N` relative frames: those need the
//! scene's range, which the sequencer resolves before calling here).
//!
//! ```
//! use eyeadapt_sequencer::FrameSet;
//! let set: FrameSet = "1, 5, 7-9, 20..24:2".parse().unwrap();
//! assert_eq!(set.as_slice(), &[1, 5, 7, 8, 9, 20, 22, 24]);
//! let err = "1-x".parse::<FrameSet>().unwrap_err();
//! assert_eq!(err.to_string(), r#"frame spec "1-x": invalid number "x" at column 3"#);
//! ```
//!
//! *Chunks* split a job's frame list for Slurm array tasks: chunk `i` of size `N` holds
//! `list[i·N .. min((i+1)·N, len)]`, so the last chunk is clamped rather than running past the
//! job's end (the OpenCue `#FRAME_END#` trap described in farm.md).

use std::fmt;
use std::str::FromStr;

/// Most frames one spec may select. A typo such as `0-4000000000` should fail at once with a
/// clear message instead of allocating 16 GB; ten million frames is over four days of 24 fps
/// footage, far beyond any job this renderer runs.
pub const MAX_FRAMES: u64 = 10_000_000;

/// A sorted, duplicate-free list of frame numbers.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FrameSet {
    frames: Vec<u32>,
}

impl FrameSet {
    /// Builds a set from any frame numbers; they are sorted and de-duplicated.
    pub fn from_frames(frames: impl IntoIterator<Item = u32>) -> FrameSet {
        let mut frames: Vec<u32> = frames.into_iter().collect();
        frames.sort_unstable();
        frames.dedup();
        FrameSet { frames }
    }

    /// The frames `start, start+step, …` up to and including `end` when the step lands on it,
    /// as Blender's `-s/-e/-j` and Deadline's `<STARTFRAME> <ENDFRAME>` describe a range.
    ///
    /// Errors name the range as the equivalent spec `start-end:step`.
    pub fn from_start_end_step(
        start: u32,
        end: u32,
        step: u32,
    ) -> Result<FrameSet, FrameSpecError> {
        let spec = format!("{start}-{end}:{step}");
        let step_at = spec.len() - step.to_string().len();
        let mut collector = Collector::new(&spec);
        collector.push_range(0, start, end, step, step_at)?;
        Ok(FrameSet {
            frames: collector.frames,
        })
    }

    pub fn as_slice(&self) -> &[u32] {
        &self.frames
    }

    pub fn into_vec(self) -> Vec<u32> {
        self.frames
    }

    pub fn len(&self) -> usize {
        self.frames.len()
    }

    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    pub fn contains(&self, frame: u32) -> bool {
        self.frames.binary_search(&frame).is_ok()
    }

    pub fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        self.frames.iter().copied()
    }

    pub fn first(&self) -> Option<u32> {
        self.frames.first().copied()
    }

    pub fn last(&self) -> Option<u32> {
        self.frames.last().copied()
    }

    /// This set narrowed to a selection that must lie inside it (a job's frames and
    /// `--frames`); `Err` holds the selected frames this set lacks.
    pub fn narrow(&self, selection: &FrameSet) -> Result<FrameSet, FrameSet> {
        let outside = selection.minus(self);
        if outside.is_empty() {
            Ok(self.intersect(selection))
        } else {
            Err(outside)
        }
    }

    /// The frames of this set that `other` lacks.
    pub fn minus(&self, other: &FrameSet) -> FrameSet {
        FrameSet {
            frames: self.iter().filter(|f| !other.contains(*f)).collect(),
        }
    }

    /// Number of chunks of `chunk_size` frames needed to cover the set.
    pub fn chunk_count(&self, chunk_size: usize) -> Result<usize, ChunkError> {
        if chunk_size == 0 {
            return Err(ChunkError::ZeroChunkSize);
        }
        Ok(self.len().div_ceil(chunk_size))
    }

    /// Chunk `index` of the sorted set: frames `[index·N, min((index+1)·N, len))`.
    pub fn chunk(&self, chunk_size: usize, index: usize) -> Result<FrameSet, ChunkError> {
        let chunks = self.chunk_count(chunk_size)?;
        if index >= chunks {
            return Err(ChunkError::IndexOutOfRange { index, chunks });
        }
        let start = index * chunk_size;
        let end = (start + chunk_size).min(self.len());
        Ok(FrameSet {
            frames: self.frames[start..end].to_vec(),
        })
    }

    /// The frames present in both sets: a job's frames narrowed by a `--frames` selection.
    pub fn intersect(&self, other: &FrameSet) -> FrameSet {
        // Both lists are sorted, so one merge pass suffices.
        let (a, b) = (&self.frames, &other.frames);
        let (mut i, mut j) = (0, 0);
        let mut frames = Vec::with_capacity(a.len().min(b.len()));
        while i < a.len() && j < b.len() {
            match a[i].cmp(&b[j]) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => {
                    frames.push(a[i]);
                    i += 1;
                    j += 1;
                }
            }
        }
        FrameSet { frames }
    }
}

impl FromStr for FrameSet {
    type Err = FrameSpecError;

    fn from_str(spec: &str) -> Result<FrameSet, FrameSpecError> {
        let mut collector = Collector::new(spec);
        let mut item_start = 0;
        for item in spec.split(',') {
            collector.parse_item(item, item_start)?;
            item_start += item.len() + 1;
        }
        Ok(FrameSet::from_frames(collector.frames))
    }
}

/// Prints the set as a spec that parses back to the same set, with consecutive runs collapsed
/// (`0-99,120,200-210`), so logs stay short for long jobs.
impl fmt::Display for FrameSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut rest = self.frames.as_slice();
        let mut first = true;
        while let Some(&start) = rest.first() {
            let run = rest
                .iter()
                .enumerate()
                .take_while(|&(k, &frame)| frame as u64 == start as u64 + k as u64)
                .count();
            if !first {
                f.write_str(",")?;
            }
            first = false;
            match run {
                1 => write!(f, "{start}")?,
                _ => write!(f, "{start}-{}", rest[run - 1])?,
            }
            rest = &rest[run..];
        }
        Ok(())
    }
}

/// Frames gathered from a spec's items, with the spec kept for error messages.
struct Collector<'a> {
    spec: &'a str,
    /// Frames so far *before* de-duplication: the size cap is checked against this, so memory
    /// is bounded before anything is allocated.
    total: u64,
    frames: Vec<u32>,
}

impl<'a> Collector<'a> {
    fn new(spec: &'a str) -> Collector<'a> {
        Collector {
            spec,
            total: 0,
            frames: Vec::new(),
        }
    }

    /// Parses one comma-separated item, which starts at byte `offset` of the spec.
    fn parse_item(&mut self, item: &str, offset: usize) -> Result<(), FrameSpecError> {
        let spec = self.spec;
        if item.trim().is_empty() {
            // Point at the comma (or the end) where an item was expected.
            let at = offset + item.len() - item.trim_start().len();
            return Err(FrameSpecError::new(spec, at, FrameSpecErrorKind::EmptyItem));
        }
        // Split off the step first so that `1..10:2` and `1-10:2` share the range code below.
        let (range, step) = match item.split_once(':') {
            Some((range, step)) => (range, Some((step, offset + range.len() + 1))),
            None => (item, None),
        };
        // `..` is checked before `-` because Blender's form never contains a dash.
        let bounds = range
            .split_once("..")
            .map(|(a, b)| (a, b, 2))
            .or_else(|| range.split_once('-').map(|(a, b)| (a, b, 1)));
        match bounds {
            None => {
                let frame = parse_number(spec, range, offset, "frame")?;
                if let Some((_, at)) = step {
                    let kind = FrameSpecErrorKind::StepWithoutRange;
                    return Err(FrameSpecError::new(spec, at - 1, kind));
                }
                self.push_range(offset, frame, frame, 1, offset)
            }
            Some((a, b, sep_len)) => {
                let start = parse_number(spec, a, offset, "range start")?;
                let end_offset = offset + a.len() + sep_len;
                let end = parse_number(spec, b, end_offset, "range end")?;
                let (step, step_at) = match step {
                    Some((text, at)) => (parse_number(spec, text, at, "step")?, at),
                    None => (1, offset),
                };
                self.push_range(offset, start, end, step, step_at)
            }
        }
    }

    /// Appends `start..=end` by `step` after checking the range and the size cap; `item_at`
    /// and `step_at` are byte offsets for error columns.
    fn push_range(
        &mut self,
        item_at: usize,
        start: u32,
        end: u32,
        step: u32,
        step_at: usize,
    ) -> Result<(), FrameSpecError> {
        let spec = self.spec;
        // Columns point at the first non-blank character of the item or step.
        let item_at = first_non_space(spec, item_at);
        let step_at = first_non_space(spec, step_at);
        if start > end {
            let kind = FrameSpecErrorKind::Reversed { start, end };
            return Err(FrameSpecError::new(spec, item_at, kind));
        }
        if step == 0 {
            let kind = FrameSpecErrorKind::ZeroStep;
            return Err(FrameSpecError::new(spec, step_at, kind));
        }
        let count = (end - start) as u64 / step as u64 + 1;
        self.total += count;
        if self.total > MAX_FRAMES {
            let kind = FrameSpecErrorKind::TooMany { total: self.total };
            return Err(FrameSpecError::new(spec, item_at, kind));
        }
        // u64 arithmetic: `start + k·step` may pass u32::MAX only after the last frame.
        let frames = (0..count).map(|k| (start as u64 + k * step as u64) as u32);
        self.frames.extend(frames);
        Ok(())
    }
}

fn first_non_space(spec: &str, byte: usize) -> usize {
    let rest = &spec[byte..];
    byte + rest.len() - rest.trim_start().len()
}

/// Parses a decimal `u32`; `text` starts at byte `offset` of `spec`, `what` names it in errors.
fn parse_number(
    spec: &str,
    text: &str,
    offset: usize,
    what: &'static str,
) -> Result<u32, FrameSpecError> {
    let trimmed = text.trim();
    let at = offset + text.len() - text.trim_start().len();
    if trimmed.is_empty() {
        return Err(FrameSpecError::new(
            spec,
            at,
            FrameSpecErrorKind::Missing(what),
        ));
    }
    // Only plain digits: `str::parse::<u32>` would also accept a leading `+`, which no farm
    // manager emits and which would hide typos.
    if !trimmed.bytes().all(|b| b.is_ascii_digit()) {
        let kind = FrameSpecErrorKind::InvalidNumber(trimmed.to_string());
        return Err(FrameSpecError::new(spec, at, kind));
    }
    trimmed.parse::<u32>().map_err(|_| {
        let kind = FrameSpecErrorKind::TooLarge(trimmed.to_string());
        FrameSpecError::new(spec, at, kind)
    })
}

/// A frame spec that could not be parsed, with the 1-based character column of the culprit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameSpecError {
    pub spec: String,
    pub column: usize,
    pub kind: FrameSpecErrorKind,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FrameSpecErrorKind {
    /// Nothing between two commas, or before the first / after the last.
    EmptyItem,
    /// A range with a missing bound or step, e.g. `5-` (the payload names which part).
    Missing(&'static str),
    InvalidNumber(String),
    /// More than `u32::MAX`.
    TooLarge(String),
    Reversed {
        start: u32,
        end: u32,
    },
    ZeroStep,
    /// `7:2`: a step only makes sense on a range.
    StepWithoutRange,
    /// The items so far select more than [`MAX_FRAMES`] (counted before de-duplication).
    TooMany {
        total: u64,
    },
}

impl FrameSpecError {
    fn new(spec: &str, byte: usize, kind: FrameSpecErrorKind) -> FrameSpecError {
        // Columns count characters, not bytes, so they match what a terminal shows.
        let column = spec[..byte.min(spec.len())].chars().count() + 1;
        FrameSpecError {
            spec: spec.to_string(),
            column,
            kind,
        }
    }
}

impl fmt::Display for FrameSpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let col = self.column;
        write!(f, "frame spec {:?}: ", self.spec)?;
        match &self.kind {
            FrameSpecErrorKind::EmptyItem => write!(f, "empty item at column {col}"),
            FrameSpecErrorKind::Missing(what) => write!(f, "missing {what} at column {col}"),
            FrameSpecErrorKind::InvalidNumber(text) => {
                write!(f, "invalid number {text:?} at column {col}")
            }
            FrameSpecErrorKind::TooLarge(text) => write!(
                f,
                "number {text} at column {col} is too large (largest frame is {})",
                u32::MAX
            ),
            FrameSpecErrorKind::Reversed { start, end } => write!(
                f,
                "reversed range {start}-{end} at column {col} (the start must not exceed the end)"
            ),
            FrameSpecErrorKind::ZeroStep => {
                write!(f, "step 0 at column {col} (must be at least 1)")
            }
            FrameSpecErrorKind::StepWithoutRange => {
                write!(f, "step at column {col} needs a range such as 1-10:2")
            }
            FrameSpecErrorKind::TooMany { total } => write!(
                f,
                "the items up to column {col} select {total} frames, more than the limit of {MAX_FRAMES}"
            ),
        }
    }
}

impl std::error::Error for FrameSpecError {}

/// Parses a chunk index given as text, typically `$SLURM_ARRAY_TASK_ID`. Surrounding
/// whitespace is ignored; anything but a non-negative decimal integer is an error.
pub fn parse_chunk_index(text: &str) -> Result<usize, ChunkError> {
    let trimmed = text.trim();
    let invalid = || ChunkError::InvalidIndex(text.to_string());
    if trimmed.is_empty() || !trimmed.bytes().all(|b| b.is_ascii_digit()) {
        return Err(invalid());
    }
    trimmed.parse().map_err(|_| invalid())
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ChunkError {
    ZeroChunkSize,
    IndexOutOfRange {
        index: usize,
        chunks: usize,
    },
    /// The text given as a chunk index (kept verbatim for the message).
    InvalidIndex(String),
}

impl fmt::Display for ChunkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ChunkError::ZeroChunkSize => write!(f, "chunk size must be at least 1"),
            ChunkError::IndexOutOfRange { index, chunks } => {
                let valid = match chunks {
                    0 => "there are no frames to split".to_string(),
                    1 => "the only valid index is 0".to_string(),
                    n => format!("valid indices are 0-{}", n - 1),
                };
                write!(
                    f,
                    "chunk index {index} is out of range: the job has {chunks} chunks ({valid})"
                )
            }
            ChunkError::InvalidIndex(text) => {
                write!(f, "chunk index {text:?} is not a non-negative integer")
            }
        }
    }
}

impl std::error::Error for ChunkError {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    fn parse(spec: &str) -> Vec<u32> {
        match spec.parse::<FrameSet>() {
            Ok(set) => set.into_vec(),
            Err(e) => panic!("{spec:?} should parse: {e}"),
        }
    }

    fn chunk(frames: &[u32], size: usize, index: usize) -> Result<Vec<u32>, ChunkError> {
        FrameSet::from_frames(frames.iter().copied())
            .chunk(size, index)
            .map(FrameSet::into_vec)
    }

    fn chunk_count(frames: usize, size: usize) -> Result<usize, ChunkError> {
        FrameSet::from_frames(0..frames as u32).chunk_count(size)
    }

    #[test]
    fn narrow_names_the_frames_outside() {
        let job = FrameSet::from_frames(0..10);
        let sel: FrameSet = "2-4,8".parse().unwrap();
        assert_eq!(job.narrow(&sel).unwrap().as_slice(), &[2, 3, 4, 8]);
        let wide: FrameSet = "8-12".parse().unwrap();
        assert_eq!(job.narrow(&wide).unwrap_err().as_slice(), &[10, 11, 12]);
        assert_eq!(job.first(), Some(0));
        assert_eq!(job.last(), Some(9));
    }

    fn error(spec: &str) -> String {
        match spec.parse::<FrameSet>() {
            Ok(set) => panic!("{spec:?} should fail, parsed as {set}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn single_frames_ranges_and_lists() {
        assert_eq!(parse("7"), [7]);
        assert_eq!(parse("0-4"), [0, 1, 2, 3, 4]);
        assert_eq!(parse("3-3"), [3]);
        assert_eq!(parse("1,5,7-9"), [1, 5, 7, 8, 9]);
        assert_eq!(parse("0-99").len(), 100);
    }

    #[test]
    fn steps_keep_the_end_only_when_landed_on() {
        assert_eq!(parse("1-9:2"), [1, 3, 5, 7, 9]);
        assert_eq!(parse("1-10:2"), [1, 3, 5, 7, 9]);
        assert_eq!(parse("1-100:2").len(), 50);
        assert_eq!(parse("5-6:10"), [5]);
    }

    #[test]
    fn blender_double_dot_ranges() {
        assert_eq!(parse("1..4"), [1, 2, 3, 4]);
        assert_eq!(parse("1..10:3"), [1, 4, 7, 10]);
        assert_eq!(parse("1..3,5-6"), [1, 2, 3, 5, 6]);
    }

    #[test]
    fn sorted_and_deduplicated_whatever_the_order() {
        assert_eq!(parse("9,1-3,2,9,0"), [0, 1, 2, 3, 9]);
    }

    #[test]
    fn whitespace_around_items_and_punctuation() {
        assert_eq!(parse(" 1 , 5 ,\t7 - 9 "), [1, 5, 7, 8, 9]);
        assert_eq!(parse("1 .. 5 : 2"), [1, 3, 5]);
    }

    #[test]
    fn extreme_frame_numbers_do_not_overflow() {
        let max = u32::MAX;
        assert_eq!(parse(&format!("{max}")), [max]);
        assert_eq!(
            parse(&format!("{}-{max}", max - 2)),
            [max - 2, max - 1, max]
        );
        assert_eq!(parse(&format!("{}-{max}:{max}", max - 2)), [max - 2]);
    }

    #[test]
    fn invalid_numbers_point_at_their_column() {
        assert_eq!(
            error("1-x"),
            r#"frame spec "1-x": invalid number "x" at column 3"#
        );
        assert_eq!(
            error("1,5,a"),
            r#"frame spec "1,5,a": invalid number "a" at column 5"#
        );
        assert_eq!(
            error("1-2-3"),
            r#"frame spec "1-2-3": invalid number "2-3" at column 3"#
        );
        assert_eq!(
            error("1...5"),
            r#"frame spec "1...5": invalid number ".5" at column 4"#
        );
        assert_eq!(
            error("+5"),
            r#"frame spec "+5": invalid number "+5" at column 1"#
        );
        assert_eq!(
            error("1 2"),
            r#"frame spec "1 2": invalid number "1 2" at column 1"#
        );
        assert_eq!(
            error("1-2:x"),
            r#"frame spec "1-2:x": invalid number "x" at column 5"#
        );
        // Columns count characters, so a multi-byte character before the culprit counts once.
        assert_eq!(
            error("é"),
            r#"frame spec "é": invalid number "é" at column 1"#
        );
        assert_eq!(
            error("1,é"),
            r#"frame spec "1,é": invalid number "é" at column 3"#
        );
    }

    #[test]
    fn negative_frames_and_missing_bounds() {
        assert_eq!(
            error("-5"),
            r#"frame spec "-5": missing range start at column 1"#
        );
        assert_eq!(
            error("5-"),
            r#"frame spec "5-": missing range end at column 3"#
        );
        assert_eq!(
            error("1-5:"),
            r#"frame spec "1-5:": missing step at column 5"#
        );
    }

    #[test]
    fn empty_items() {
        assert_eq!(error(""), r#"frame spec "": empty item at column 1"#);
        assert_eq!(error("  "), r#"frame spec "  ": empty item at column 3"#);
        assert_eq!(
            error("1,,2"),
            r#"frame spec "1,,2": empty item at column 3"#
        );
        assert_eq!(
            error("1, ,2"),
            r#"frame spec "1, ,2": empty item at column 4"#
        );
        assert_eq!(error("1,"), r#"frame spec "1,": empty item at column 3"#);
        assert_eq!(error(",1"), r#"frame spec ",1": empty item at column 1"#);
    }

    #[test]
    fn reversed_ranges_and_zero_steps() {
        assert_eq!(
            error("1, 9-7"),
            r#"frame spec "1, 9-7": reversed range 9-7 at column 4 (the start must not exceed the end)"#
        );
        assert_eq!(
            error("1..10:0"),
            r#"frame spec "1..10:0": step 0 at column 7 (must be at least 1)"#
        );
        assert_eq!(
            error("1-10: 0"),
            r#"frame spec "1-10: 0": step 0 at column 7 (must be at least 1)"#
        );
        assert_eq!(
            error("7:2"),
            r#"frame spec "7:2": step at column 2 needs a range such as 1-10:2"#
        );
    }

    #[test]
    fn overflow_and_absurd_sizes() {
        assert_eq!(
            error("4294967296"),
            r#"frame spec "4294967296": number 4294967296 at column 1 is too large (largest frame is 4294967295)"#
        );
        assert_eq!(
            error("0-4000000000"),
            r#"frame spec "0-4000000000": the items up to column 1 select 4000000001 frames, more than the limit of 10000000"#
        );
        // The limit is on the sum over items, checked item by item.
        assert_eq!(
            error("0-5999999, 0-5999999"),
            r#"frame spec "0-5999999, 0-5999999": the items up to column 12 select 12000000 frames, more than the limit of 10000000"#
        );
        assert_eq!(
            parse(&format!("0-{}", MAX_FRAMES - 1)).len(),
            MAX_FRAMES as usize
        );
        assert_eq!(parse("0-19999999:2").len(), MAX_FRAMES as usize);
    }

    #[test]
    fn error_fields_are_public_for_callers() {
        let e = "1-x".parse::<FrameSet>().unwrap_err();
        assert_eq!(e.column, 3);
        assert_eq!(e.kind, FrameSpecErrorKind::InvalidNumber("x".into()));
    }

    #[test]
    fn start_end_step() {
        let set = FrameSet::from_start_end_step(1, 10, 3).unwrap();
        assert_eq!(set.as_slice(), &[1, 4, 7, 10]);
        assert_eq!(
            FrameSet::from_start_end_step(5, 5, 1).unwrap().as_slice(),
            &[5]
        );
        assert_eq!(
            FrameSet::from_start_end_step(5, 1, 1)
                .unwrap_err()
                .to_string(),
            r#"frame spec "5-1:1": reversed range 5-1 at column 1 (the start must not exceed the end)"#
        );
        assert_eq!(
            FrameSet::from_start_end_step(1, 5, 0).unwrap_err().kind,
            FrameSpecErrorKind::ZeroStep
        );
        assert!(matches!(
            FrameSet::from_start_end_step(0, u32::MAX, 1)
                .unwrap_err()
                .kind,
            FrameSpecErrorKind::TooMany { .. }
        ));
    }

    #[test]
    fn display_collapses_runs_and_round_trips() {
        let set = FrameSet::from_frames([0, 1, 2, 3, 7, 9, 10, u32::MAX - 1, u32::MAX]);
        assert_eq!(set.to_string(), "0-3,7,9-10,4294967294-4294967295");
        assert_eq!(set.to_string().parse::<FrameSet>().unwrap(), set);
        assert_eq!(FrameSet::default().to_string(), "");
    }

    #[test]
    fn intersection_with_a_selection() {
        let job: FrameSet = "0-20:2".parse().unwrap();
        let selection: FrameSet = "3-9,20-30".parse().unwrap();
        assert_eq!(job.intersect(&selection).as_slice(), &[4, 6, 8, 20]);
        assert_eq!(selection.intersect(&job), job.intersect(&selection));
        assert!(job.intersect(&"1-19:2".parse().unwrap()).is_empty());
        assert!(job.contains(4) && !job.contains(5));
    }

    #[test]
    fn chunks_clamp_the_last_one() {
        let frames: Vec<u32> = (1..=72).collect();
        assert_eq!(chunk_count(frames.len(), 10), Ok(8));
        assert_eq!(chunk(&frames, 10, 0).unwrap(), &frames[0..10]);
        // OpenCue would ask for 71-80 here; the job ends at 72.
        assert_eq!(chunk(&frames, 10, 7).unwrap(), &[71, 72]);
        assert_eq!(chunk(&frames, 72, 0).unwrap(), frames.as_slice());
        assert_eq!(chunk(&frames, 1000, 0).unwrap(), frames.as_slice());
    }

    #[test]
    fn chunk_errors_name_the_number_of_chunks() {
        let frames: Vec<u32> = (0..72).collect();
        assert_eq!(
            chunk(&frames, 10, 8).unwrap_err().to_string(),
            "chunk index 8 is out of range: the job has 8 chunks (valid indices are 0-7)"
        );
        assert_eq!(
            chunk(&frames, 100, 1).unwrap_err().to_string(),
            "chunk index 1 is out of range: the job has 1 chunks (the only valid index is 0)"
        );
        assert_eq!(
            chunk(&[], 10, 0).unwrap_err().to_string(),
            "chunk index 0 is out of range: the job has 0 chunks (there are no frames to split)"
        );
        assert_eq!(chunk(&frames, 0, 0), Err(ChunkError::ZeroChunkSize));
        assert_eq!(chunk_count(0, 10), Ok(0));
    }

    #[test]
    fn chunk_index_from_slurm_text() {
        assert_eq!(parse_chunk_index("0"), Ok(0));
        assert_eq!(parse_chunk_index("17\n"), Ok(17));
        for bad in [
            "",
            " ",
            "-1",
            "+1",
            "1.0",
            "abc",
            "1 2",
            "99999999999999999999999",
        ] {
            assert_eq!(
                parse_chunk_index(bad).unwrap_err().to_string(),
                format!("chunk index {bad:?} is not a non-negative integer")
            );
        }
    }

    /// splitmix64: a tiny deterministic generator, so the property loops below are reproducible.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }
        fn below(&mut self, n: u64) -> u32 {
            (self.next() % n) as u32
        }
    }

    /// A random valid spec and the frames it must select, built independently of the parser.
    fn random_spec(rng: &mut Rng) -> (String, BTreeSet<u32>) {
        let mut items = Vec::new();
        let mut expected = BTreeSet::new();
        for _ in 0..1 + rng.below(6) {
            let start = rng.below(300);
            let end = start + rng.below(60);
            let step = 1 + rng.below(7);
            let sep = ["-", "..", " - ", " .. "][rng.below(4) as usize];
            let item = match rng.below(4) {
                0 => {
                    expected.insert(start);
                    format!("{start}")
                }
                1 => {
                    expected.extend(start..=end);
                    format!("{start}{sep}{end}")
                }
                _ => {
                    expected.extend((start..=end).step_by(step as usize));
                    format!("{start}{sep}{end}:{step}")
                }
            };
            items.push(item);
        }
        let comma = [",", ", ", " ,\t"][rng.below(3) as usize];
        (items.join(comma), expected)
    }

    #[test]
    fn property_random_specs_parse_to_the_reference_set() {
        let mut rng = Rng(1);
        for _ in 0..2000 {
            let (spec, expected) = random_spec(&mut rng);
            let set = spec.parse::<FrameSet>().unwrap_or_else(|e| panic!("{e}"));
            assert!(set.as_slice().iter().eq(expected.iter()), "{spec}");
            assert_eq!(set.to_string().parse::<FrameSet>().unwrap(), set, "{spec}");
        }
    }

    #[test]
    fn property_chunks_partition_the_list() {
        let mut rng = Rng(2);
        for _ in 0..2000 {
            let (spec, _) = random_spec(&mut rng);
            let frames = spec.parse::<FrameSet>().unwrap().into_vec();
            let size = 1 + rng.below(40) as usize;
            let count = chunk_count(frames.len(), size).unwrap();
            let mut joined = Vec::new();
            for i in 0..count {
                let part = chunk(&frames, size, i).unwrap();
                assert!(
                    !part.is_empty() && part.len() <= size,
                    "{spec} size {size} chunk {i}"
                );
                // Chunks are contiguous and in order, so concatenation reproduces the list
                // exactly: no frame lost, none rendered twice.
                joined.extend_from_slice(&part);
            }
            assert_eq!(joined, frames, "{spec} size {size}");
            assert!(chunk(&frames, size, count).is_err());
        }
    }

    #[test]
    fn property_intersection_matches_set_semantics() {
        let mut rng = Rng(3);
        for _ in 0..1000 {
            let (a_spec, a_ref) = random_spec(&mut rng);
            let (b_spec, b_ref) = random_spec(&mut rng);
            let a: FrameSet = a_spec.parse().unwrap();
            let b: FrameSet = b_spec.parse().unwrap();
            let both: Vec<u32> = a_ref.intersection(&b_ref).copied().collect();
            assert_eq!(
                a.intersect(&b).as_slice(),
                both.as_slice(),
                "{a_spec} ∩ {b_spec}"
            );
        }
    }
}
