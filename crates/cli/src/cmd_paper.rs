//! `eyeadapt paper`: the paper's test cases and its claims, checked (library:
//! `eyeadapt_paper`).
use crate::args::PaperArgs;
use eyeadapt_paper::PaperOptions;
use eyeadapt_sequencer::Failure;
use std::path::PathBuf;
use std::time::Instant;

pub fn run(a: PaperArgs) -> Result<(), Failure> {
    let start = Instant::now();
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(if a.quick { "out/paper-quick" } else { "paper" }));
    let work = a
        .work
        .clone()
        .or_else(|| (a.out.is_none() && !a.quick).then(|| PathBuf::from("out/paper-work")));
    let o = PaperOptions {
        quick: a.quick,
        results: a.results.clone(),
        work,
        seed: a.seed,
        cases: a.cases.clone(),
        eye_samples: a.eye_samples,
        verbose: true,
        ..PaperOptions::new(out)
    };
    let r = eyeadapt_paper::run(&o)?;
    for c in &r.cases {
        for (i, v) in c.verdicts.iter().enumerate() {
            println!(
                "case {} {:<13}: {} — {}{}",
                c.info.number,
                v.outcome.label(),
                v.claim,
                v.test(),
                c.study
                    .as_ref()
                    .map_or(String::new(), |st| format!(" [{}]", st.robustness(i)))
            );
        }
        if let Some(s) = &c.sheet {
            println!("Saved: '{}'", o.out.join(s).display());
        }
    }
    println!("Saved: '{}'", r.results_path.display());
    eprintln!("paper: done in {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}
