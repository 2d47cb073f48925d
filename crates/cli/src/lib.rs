//! The `eyeadapt` command line: argument parsing, exit codes and progress display. All work is
//! done by the library crates; each subcommand lives in its own module.
//!
//! Exit codes: 0 done; 2 bad input or usage; 75 transient failure worth a retry; 130/143
//! stopped by SIGINT/SIGTERM with every finished frame committed; 1 other.

/// `--estimators/--cat/--degree…` into library settings; the table after a render.
mod adapt_cli;
/// What the user typed (clap).
mod args;
/// `eyeadapt bench`.
mod cmd_bench;
/// `eyeadapt bench --bvh-triangles N`.
mod cmd_bench_bvh;
/// `eyeadapt paper`.
mod cmd_paper;
/// `eyeadapt plan`.
mod cmd_plan;
/// `eyeadapt render`.
mod cmd_render;
/// `eyeadapt report`.
mod cmd_report;
/// `eyeadapt sequence` and `merge`.
mod cmd_sequence;
/// SIGINT/SIGTERM during `sequence`: stop after the frame in flight, or at once.
mod interrupt;

use clap::Parser;
use eyeadapt_sequencer::Failure;
use std::process::ExitCode;

pub use crate::args::{Cli, Command};

/// Parses the command line, runs the command and maps failures to exit codes.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f @ Failure::Stopped { .. }) => {
            eprintln!("eyeadapt: {f}");
            ExitCode::from(f.exit_code())
        }
        Err(f) => {
            eprintln!("eyeadapt: error: {f}");
            ExitCode::from(f.exit_code())
        }
    }
}

fn run(cli: Cli) -> Result<(), Failure> {
    // Before anything is read or written: a misspelt value must not pass for `auto` unseen.
    eyeadapt_tracer::simd_setting().map_err(Failure::Input)?;
    if let Some(t) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global()
            .map_err(|e| Failure::Other(format!("cannot start {t} threads: {e}")))?;
    }
    match cli.command {
        Command::Render(a) => cmd_render::run(*a),
        Command::Bench(a) if a.bvh_triangles.is_some() => cmd_bench_bvh::run(a),
        Command::Bench(a) => cmd_bench::run(a),
        Command::Sequence(a) => cmd_sequence::run(*a),
        Command::Plan(a) => cmd_plan::run(*a),
        Command::Merge(a) => cmd_sequence::merge(a),
        Command::Report(a) => cmd_report::run(a),
        Command::Paper(a) => cmd_paper::run(a),
        Command::Scenes => {
            for (name, what) in eyeadapt_scene::builtin_scenes() {
                println!("builtin:{name:<28} {what}");
            }
            Ok(())
        }
    }
}
