//! Reading `adaptation.csv` back (a small reader for the file [`eyeadapt_sequencer::adapt::csv_row`]
//! writes: no quoting, `;` inside the flags cell) and writing the report's derived rows in
//! the same schema.
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::{CSV_HEADER, num};
use eyeadapt_sequencer::manifest::{Manifest, checksum};
use eyeadapt_sequencer::pipeline::frame_name;
use std::collections::{BTreeSet, HashMap};
use std::fmt::Write;
use std::path::Path;

/// One parsed row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub frame: u32,
    pub estimator: String,
    /// The cells as written (for copying `time_s`, `n_samples` and the camera columns).
    pub cells: Vec<String>,
    /// XYZ normalised to Y = 1 (NaN when undefined).
    pub xyz: [f64; 3],
    pub uv: Option<[f64; 2]>,
    pub std_err: Option<[f64; 2]>,
    pub valid: bool,
    /// The line as read, without its newline.
    pub line: String,
}

/// Column indices of the header.
pub mod col {
    pub const FRAME: usize = 0;
    pub const TIME: usize = 1;
    pub const ESTIMATOR: usize = 2;
    pub const X: usize = 3;
    pub const U: usize = 8;
    pub const STD_ERR_U: usize = 14;
    pub const N_SAMPLES: usize = 16;
    pub const VALID: usize = 17;
    pub const CAM_X: usize = 20;
}

/// What [`parse`] found.
#[derive(Debug, Default)]
pub struct Table {
    /// Rows of the sequence's own estimators, in file order.
    pub rows: Vec<Row>,
    /// Rows a previous report derived (estimator contains `+`); dropped.
    pub dropped_derived: usize,
    /// Rows of frames absent from the manifest (e.g. a frame in flight when a run was killed).
    pub dropped_uncommitted: usize,
    /// Second and later rows for the same (frame, estimator).
    pub dropped_duplicates: usize,
}

fn number(cell: &str) -> f64 {
    // Empty cells and "NaN" are undefined.
    cell.trim().parse::<f64>().unwrap_or(f64::NAN)
}

/// Parses `adaptation.csv` text, keeping rows of `committed` frames only.
pub fn parse(text: &str, source: &Path, committed: &BTreeSet<u32>) -> Result<Table, Failure> {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    if header.trim_end() != CSV_HEADER {
        return Err(Failure::Input(format!(
            "{}: unexpected header (expected the eyeadapt adaptation.csv columns {CSV_HEADER})",
            source.display()
        )));
    }
    let n_cols = CSV_HEADER.split(',').count();
    let mut table = Table::default();
    let mut seen = BTreeSet::new();
    for (i, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let cells: Vec<String> = line.split(',').map(str::to_string).collect();
        let bad = |what: &str| {
            Failure::Input(format!("{}:{}: {what}: {line:?}", source.display(), i + 2))
        };
        if cells.len() != n_cols {
            return Err(bad(&format!(
                "{} cells where the header has {n_cols}",
                cells.len()
            )));
        }
        let frame: u32 = cells[col::FRAME]
            .parse()
            .map_err(|_| bad("the frame is not a whole number"))?;
        let estimator = cells[col::ESTIMATOR].clone();
        if estimator.is_empty() {
            return Err(bad("no estimator name"));
        }
        if estimator.contains('+') {
            table.dropped_derived += 1;
            continue;
        }
        if !committed.contains(&frame) {
            table.dropped_uncommitted += 1;
            continue;
        }
        if !seen.insert((frame, estimator.clone())) {
            table.dropped_duplicates += 1;
            continue;
        }
        let xyz = [0, 1, 2].map(|k| number(&cells[col::X + k]));
        let uv = [number(&cells[col::U]), number(&cells[col::U + 1])];
        let se = [
            number(&cells[col::STD_ERR_U]),
            number(&cells[col::STD_ERR_U + 1]),
        ];
        let valid = cells[col::VALID].trim() == "1" && uv.iter().all(|v| v.is_finite());
        table.rows.push(Row {
            frame,
            estimator,
            xyz,
            uv: valid.then_some(uv),
            std_err: se.iter().all(|v| v.is_finite()).then_some(se),
            valid,
            cells,
            line: line.to_string(),
        });
    }
    Ok(table)
}

/// Checks the table against the sequence's record: the rows of every committed frame must be
/// exactly that frame's `rows/frame_NNNNNN.csv` (whose size and checksum the manifest holds),
/// so a CSV whose rows were cut, edited or added for a committed frame is refused, naming the
/// frames, instead of giving other metrics. `source` is the CSV, for messages.
pub fn check_committed(
    tab: &Table,
    dir: &Path,
    m: &Manifest,
    source: &Path,
) -> Result<(), Failure> {
    let mut have: HashMap<u32, Vec<&str>> = HashMap::new();
    for r in &tab.rows {
        have.entry(r.frame).or_default().push(&r.line);
    }
    let mut differ = Vec::new();
    for (f, e) in &m.frames {
        let rel = format!("rows/{}", frame_name(*f, "csv"));
        let Some(entry) = e.files.iter().find(|fe| fe.path == rel) else {
            continue;
        };
        let p = dir.join(&rel);
        let bytes = eyeadapt_scene::read_input(&p)
            .map_err(|e| Failure::input_io("cannot read committed rows", &p, &e))?;
        if bytes.len() as u64 != entry.bytes || checksum(&bytes) != entry.sha256_128 {
            return Err(Failure::Input(format!(
                "{}: frame {f}'s rows are not the ones committed (size or checksum differs from \
                 manifest.json)",
                p.display()
            )));
        }
        let text = String::from_utf8_lossy(&bytes);
        let mut want: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
        let mut got = have.remove(f).unwrap_or_default();
        want.sort_unstable();
        got.sort_unstable();
        if want != got {
            differ.push(*f);
        }
    }
    if differ.is_empty() {
        return Ok(());
    }
    let list: Vec<String> = differ.iter().take(10).map(u32::to_string).collect();
    Err(Failure::Input(format!(
        "{}: the rows of {} committed frame(s) ({}{}) differ from their record in rows/ \
         (checksummed in manifest.json): the file was cut or edited. Running the job's \
         `eyeadapt sequence` on this directory again rebuilds it from rows/",
        source.display(),
        differ.len(),
        list.join(", "),
        if differ.len() > 10 { ", …" } else { "" }
    )))
}

/// One derived row (with its newline), in [`CSV_HEADER`]'s columns: the filtered white
/// (`xyz`, Y = 1) with its chromaticities, CCT and linear sRGB; no standard errors; `abs_Y`
/// NaN (a filtered white has no absolute scale); frame, time, sample count and camera
/// position copied from the source row `src` (or from `frame`/`time` when the source has no
/// row for that frame).
pub fn derived_row(
    frame: u32,
    time: f64,
    estimator: &str,
    xyz: glam::DVec3,
    valid: bool,
    flags: &[&str],
    src: Option<&Row>,
) -> String {
    let mut s = String::with_capacity(256);
    let _ = write!(s, "{frame},");
    match src {
        Some(r) => s.push_str(&r.cells[col::TIME]),
        None => num(&mut s, time),
    }
    let _ = write!(s, ",{estimator},");
    eyeadapt_sequencer::adapt::white_columns(&mut s, xyz, valid);
    // std_err_u, std_err_v: empty.
    s.push(',');
    s.push(',');
    match src {
        Some(r) => s.push_str(&r.cells[col::N_SAMPLES]),
        None => s.push('0'),
    }
    let _ = write!(s, ",{},{},", u8::from(valid), flags.join(";"));
    s.push_str("NaN");
    for k in 0..3 {
        s.push(',');
        match src {
            Some(r) => s.push_str(&r.cells[col::CAM_X + k]),
            None => s.push_str("NaN"),
        }
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_rows_parse_back_with_the_same_white() {
        let xyz = eyeadapt_color::D65_XYZ;
        let line = derived_row(3, 0.125, "eye+fairchild", xyz, true, &["clamped"], None);
        let text = format!("{CSV_HEADER}\n{line}");
        let t = parse(&text, Path::new("x.csv"), &[3].into()).unwrap();
        assert_eq!(t.rows.len(), 0);
        assert_eq!(t.dropped_derived, 1);
        let plain = line.replace("eye+fairchild", "eye");
        let t = parse(
            &format!("{CSV_HEADER}\n{plain}{plain}"),
            Path::new("x.csv"),
            &[3].into(),
        )
        .unwrap();
        assert_eq!(t.dropped_duplicates, 1);
        let r = &t.rows[0];
        assert_eq!(r.xyz, xyz.to_array());
        assert!(r.valid && r.std_err.is_none());
        let uv = eyeadapt_color::xyz_to_uv(xyz).unwrap();
        assert_eq!(r.uv, Some([uv.x, uv.y]));
        assert_eq!(
            line.trim_end().split(',').count(),
            CSV_HEADER.split(',').count()
        );
    }

    #[test]
    fn bad_lines_name_file_and_line() {
        let e = parse(
            &format!("{CSV_HEADER}\n1,2,3\n"),
            Path::new("a.csv"),
            &[1].into(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("a.csv:2"), "{e}");
        assert!(parse("x,y\n", Path::new("a.csv"), &[1].into()).is_err());
    }
}
