//! Ctrl-C and SIGTERM during `eyeadapt sequence`.
//!
//! The first signal asks the run to stop after the frame in flight is committed (the sequence
//! checks an `eyeadapt_sequencer::stop::StopRequest` before each frame). A second one, or the first while the report
//! is written, stops at once: that is safe at any moment because every file is written under
//! a temporary name and renamed, and the next run cleans up and resumes. Either way the last
//! line says how many frames are committed and that rerunning the same command resumes.
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::stop::StopRequest;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use std::sync::Arc;

pub fn signal_name(signal: i32) -> &'static str {
    match signal {
        SIGINT => "SIGINT",
        SIGTERM => "SIGTERM",
        _ => "a signal",
    }
}

/// How many of the run's frames are safe, and what to do next.
pub fn committed_message(committed: usize, planned: usize) -> String {
    format!("{committed} of {planned} frames committed; rerun the same command to resume")
}

/// Starts the thread that turns SIGINT/SIGTERM into `stop` requests; `planned` is the run's
/// frame count, for the message of a stop at once.
pub fn watch(stop: Arc<StopRequest>, planned: usize) -> Result<(), Failure> {
    let mut signals = Signals::new([SIGINT, SIGTERM])
        .map_err(|e| Failure::Other(format!("cannot install signal handlers: {e}")))?;
    std::thread::spawn(move || {
        for signal in signals.forever() {
            let name = signal_name(signal);
            if stop.requested().is_some() || stop.reporting() {
                eprintln!(
                    "eyeadapt: {name}: stopped at once; {}",
                    committed_message(stop.committed(), planned)
                );
                std::process::exit(128 + signal);
            }
            stop.request(signal);
            eprintln!(
                "eyeadapt: {name}: stopping after the frame in flight is committed ({name} again stops at once)"
            );
        }
    });
    Ok(())
}
