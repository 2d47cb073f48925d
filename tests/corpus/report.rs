//! `report/`: a broken `adaptation.csv` (`NAME.csv`) or a patched `manifest.json`
//! (`NAME.manifest`, lines `FROM => TO`) in a copy of a good, already reported sequence:
//! `eyeadapt report` exits 2 with the location and message and changes nothing in the copy.
use super::harness::*;

#[test]
fn bad_report_inputs_exit_2_and_change_nothing() {
    let t = tempfile::tempdir().unwrap();
    let root = t.path();
    let seq_out = good_sequence(root, "seq-out");
    let before = snapshots(&[&seq_out]);
    let mut outcomes = Vec::new();
    // Report: a copy of the good sequence, reported once (so its report files exist), then
    // per case a fresh copy with a broken adaptation.csv (`NAME.csv`) or a patched
    // manifest.json (`NAME.manifest`: lines `FROM => TO`). The failed report must change
    // nothing in it.
    let report_good = root.join("report-good");
    copy_dir(&seq_out, &report_good);
    must(eyeadapt().arg("report").arg(&report_good));
    let mut report_cases = cases("report", "csv");
    report_cases.extend(cases("report", "manifest"));
    for (case, path, x) in report_cases {
        let dir = root.join("report-cases").join(path.file_name().unwrap());
        copy_dir(&report_good, &dir);
        if path.extension().is_some_and(|e| e == "csv") {
            std::fs::copy(&path, dir.join("adaptation.csv")).unwrap();
        } else {
            let mut m = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
            for l in std::fs::read_to_string(&path).unwrap().lines() {
                let (from, to) = l.split_once(" => ").unwrap();
                assert!(m.contains(from), "{case}: {from:?} not in the manifest");
                m = m.replace(from, to);
            }
            std::fs::write(dir.join("manifest.json"), m).unwrap();
        }
        let before = snapshot(&dir);
        let (code, err) = run(eyeadapt().arg("report").arg(&dir));
        let mut o = check(&case, code, &err, &x);
        let after = snapshot(&dir);
        let changed: Vec<&String> = before
            .keys()
            .chain(after.keys())
            .filter(|k| before.get(*k) != after.get(*k) && !k.ends_with(".eyeadapt.lock"))
            .collect();
        if !changed.is_empty() {
            o.problems
                .push(format!("the failed report changed {changed:?}"));
        }
        outcomes.push(o);
    }
    assert_unchanged(&[&seq_out], &before);
    finish(&outcomes, &[("report", 14)]);
}
