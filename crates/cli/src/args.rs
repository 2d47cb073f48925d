//! What the user typed (stage one of argument handling); commands validate further.
//!
//! The doc comments here are clap's `--help` text, printed as written: `<name>` in them is a
//! placeholder for the user, not HTML.
#![allow(rustdoc::invalid_html_tags)]
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "eyeadapt",
    version,
    about = "Path-traced sequences with eye-centred chromatic adaptation"
)]
pub struct Cli {
    /// Worker threads, 1 to 1024 (default: all cores). Results are identical for any value.
    #[arg(long, global = true, value_parser = parse_threads)]
    pub threads: Option<usize>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render one still: DIR/raw.exr (beauty + AOVs) and DIR/preview.png.
    Render(Box<RenderArgs>),
    /// Benchmark the tracer on the Cornell box and print samples/s.
    Bench(BenchArgs),
    /// Render a camera-path sequence (the overnight job); with no JOB, the built-in demo.
    Sequence(Box<SequenceArgs>),
    /// Print the frame and chunk counts of a job for farm submitters: quoted shell assignments
    /// (safe to `eval` in sh and bash), or JSON with --format json.
    Plan(Box<PlanArgs>),
    /// Join chunk output directories into one sequence (verifies every file; refuses gaps,
    /// conflicts and damaged chunks).
    Merge(MergeArgs),
    /// List the built-in scenes (usable as `builtin:NAME` wherever a scene path is).
    Scenes,
    /// Temporal-coherence report of a sequence directory: coherence.csv, plots, report.html.
    Report(ReportArgs),
    /// Render the paper's six test cases and check its claims: RESULTS.md + contact sheets.
    Paper(PaperArgs),
}

#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Sequence output directory (holds manifest.json and adaptation.csv).
    pub dir: PathBuf,
    /// Also encode video/raw.mp4, video/<estimator>.mp4 and video/raw_wcam_eye.mp4 with ffmpeg.
    #[arg(long)]
    pub video: bool,
    /// With --video: a strip under every movie naming each frame's number and time.
    #[arg(long, requires = "video")]
    pub overlay: bool,
    /// Gaussian σ in seconds of the hf_rms low-pass (estimators.md §7.2).
    #[arg(long, default_value_t = eyeadapt_color::DEFAULT_SIGMA_S)]
    pub sigma_s: f64,
}

#[derive(Args, Debug)]
pub struct PaperArgs {
    /// Small images and few samples (about a minute on 2 cores).
    #[arg(long)]
    pub quick: bool,
    /// Directory for RESULTS.md and the contact sheets (default: paper, or out/paper-quick
    /// with --quick).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write RESULTS.md here instead of OUT/RESULTS.md.
    #[arg(long)]
    pub results: Option<PathBuf>,
    /// Directory for the per-case job files, CSVs and raw EXRs (default: out/paper-work, or
    /// OUT/work when --out is given).
    #[arg(long)]
    pub work: Option<PathBuf>,
    /// Only these cases (comma list of 1-6).
    #[arg(long, value_delimiter = ',')]
    pub cases: Vec<u32>,
    /// Random seed; the same seed gives the same RESULTS.md, byte for byte.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Exactly this many eye-sensor paths per frame (default: the job files' fixed 16384).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=67_108_864))]
    pub eye_samples: Option<u32>,
}

#[derive(Args, Debug, Clone)]
pub struct SequenceArgs {
    /// Job file (TOML). Without it: the built-in demo job (configs/demo.toml).
    pub job: Option<PathBuf>,
    /// Output directory (default: out/<job name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Frames to render: 0-99, 1-100:2, 1,5,7-9, 1..10 (Blender).
    #[arg(long, conflicts_with_all = ["start", "end"])]
    pub frames: Option<String>,
    /// First frame (with --end, like Blender's -s/-e, Deadline's <STARTFRAME>, OpenCue's
    /// #FRAME_START#).
    #[arg(long, requires = "end")]
    pub start: Option<u32>,
    /// Last frame, inclusive; clamped to the job's last frame.
    #[arg(long, requires = "start")]
    pub end: Option<u32>,
    /// Step between frames with --start/--end.
    #[arg(long, default_value_t = 1, requires = "start")]
    pub step: u32,
    /// Frames per chunk (Slurm array tasks); chunk i holds frames [i*N, (i+1)*N).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub chunk_size: Option<u64>,
    /// Which chunk to render; defaults to $SLURM_ARRAY_TASK_ID.
    #[arg(long, requires = "chunk_size")]
    pub chunk_index: Option<String>,
    /// Discard an output directory's records of a different job and start over.
    #[arg(long)]
    pub force: bool,
    /// On resume, re-hash committed files instead of checking their sizes.
    #[arg(long)]
    pub verify: bool,
    /// Progress lines for farm managers: plain (Fra:/Saved:/Progress:) or openjd.
    #[arg(long, default_value = "plain", value_parser = ["plain", "openjd"])]
    pub log_format: String,
    /// Never draw a progress bar, even on a terminal.
    #[arg(long)]
    pub no_progress_bar: bool,
    /// Skip the coherence report at the end of a complete sequence.
    #[arg(long)]
    pub no_report: bool,
    #[command(flatten)]
    pub sampling: SamplingArgs,
    /// Exactly this many eye-sensor paths per frame (default: adaptive, 4096-16384).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=67_108_864))]
    pub eye_samples: Option<u32>,
}

#[derive(Args, Debug)]
pub struct PlanArgs {
    #[command(flatten)]
    pub seq: SequenceArgs,
    /// Output: `sh` (EYEADAPT_NAME='value' lines for `eval`) or `json` (one object).
    #[arg(long, default_value = "sh", value_parser = ["sh", "json"])]
    pub format: String,
}

#[derive(Args, Debug)]
pub struct MergeArgs {
    /// Chunk output directories.
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Merged output directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Frames the merge must cover (default: the job's own frames, whatever each chunk
    /// selected); frames of the inputs outside it are left out.
    #[arg(long)]
    pub frames: Option<String>,
}

/// Sampling options shared by `render` and `sequence`.
#[derive(Args, Debug, Clone, Default)]
pub struct SamplingArgs {
    /// Samples per pixel.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16_777_216))]
    pub spp: Option<u32>,
    /// Image width in pixels.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub width: Option<u32>,
    /// Image height in pixels.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub height: Option<u32>,
    /// Longest path in segments, Mitsuba's `max_depth` (1 = emitters only, 2 = direct light,
    /// -1 = unlimited).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_max_depth)]
    pub max_depth: Option<i32>,
    /// Path length at which Russian roulette starts (Mitsuba's `rr_depth`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub rr_depth: Option<u32>,
    /// Random seed; the same seed gives the same bits.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Path guiding, learned per frame from the frame's own samples: `off` (the default) or
    /// `on` (docs/benchmarks/guiding.md says where it pays).
    #[arg(long, value_parser = ["off", "on"])]
    pub guiding: Option<String>,
}

impl SamplingArgs {
    pub fn sampling(&self) -> eyeadapt_sequencer::pipeline::Sampling {
        eyeadapt_sequencer::pipeline::Sampling {
            width: self.width,
            height: self.height,
            spp: self.spp,
            max_depth: self.max_depth,
            rr_depth: self.rr_depth,
            seed: self.seed,
            guiding: self.guiding.as_deref().map(|g| match g {
                "on" => eyeadapt_tracer::Guiding::On,
                _ => eyeadapt_tracer::Guiding::Off,
            }),
        }
    }
}

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=1024).contains(&n) => Ok(n),
        _ => Err(format!("\"{s}\" is not a thread count between 1 and 1024")),
    }
}

fn parse_exposure(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v.abs() <= 30.0 => Ok(v),
        _ => Err(format!(
            "\"{s}\" is not a finite number of stops in [-30, 30]"
        )),
    }
}

fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((name, value)) if !name.is_empty() && !name.contains('$') => {
            Ok((name.to_string(), value.to_string()))
        }
        _ => Err(format!("\"{s}\" is not NAME=VALUE")),
    }
}

fn parse_max_depth(s: &str) -> Result<i32, String> {
    let v: i32 = s
        .parse()
        .map_err(|_| format!("\"{s}\" is not an integer"))?;
    if v == -1 || (1..=1024).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} must be -1 (unlimited) or between 1 and 1024"))
    }
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (.toml, or .xml in Mitsuba 3's format) or builtin:NAME.
    pub scene: String,
    /// A `$NAME` parameter of a Mitsuba XML scene, as `mitsuba -D NAME=VALUE` gives it
    /// (repeatable; it wins over the file's `<default>`).
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    #[command(flatten)]
    pub sampling: SamplingArgs,
    /// Output directory.
    #[arg(long, default_value = "out/render")]
    pub out: PathBuf,
    /// Preview exposure in stops, -30 to 30 (PNG only; the EXR is never scaled).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = parse_exposure)]
    pub exposure: f32,
    /// Also write render statistics as JSON to this file.
    #[arg(long)]
    pub stats_json: Option<PathBuf>,
    #[command(flatten)]
    pub adapt: AdaptArgs,
}

/// Estimators and chromatic adaptation.
#[derive(Args, Debug, Clone, Default)]
pub struct AdaptArgs {
    /// Adaptation estimators: `all` or a comma list of eye, eye_fov, wcam, ncns, dominant,
    /// grey_world, white_patch, shades_of_grey, grey_edge. Writes adapted_<name>.png and
    /// adaptation.csv.
    #[arg(long)]
    pub estimators: Option<String>,
    /// Chromatic adaptation transform: cat02 (default), cat16, bradford, vonkries.
    #[arg(long, requires = "estimators")]
    pub cat: Option<String>,
    /// Degree of adaptation D in [0, 1] (default 1: full adaptation, as in the paper).
    #[arg(long, conflicts_with = "adapt_luminance", requires = "estimators")]
    pub degree: Option<f64>,
    /// Compute D from the adapting luminance L_A in cd/m² (CIECAM02).
    #[arg(long, requires = "estimators")]
    pub adapt_luminance: Option<f64>,
    /// Surround for D from L_A: average, dim or dark.
    #[arg(long, requires = "adapt_luminance")]
    pub surround: Option<String>,
    /// Exactly this many eye-sensor paths per frame (default: adaptive, 4096-16384).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=67_108_864), requires = "estimators")]
    pub eye_samples: Option<u32>,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scene to benchmark.
    #[arg(long, default_value = "builtin:cornell-box")]
    pub scene: String,
    /// Samples per pixel.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=16_777_216))]
    pub spp: u32,
    /// Image size (square), 1 to 32768.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub size: u32,
    /// Mitsuba's max_depth (-1 = unlimited, else 1 to 1024).
    #[arg(long, default_value_t = 8, allow_negative_numbers = true, value_parser = parse_max_depth)]
    pub max_depth: i32,
    /// Timed repetitions (the median is reported), 1 to 1000.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub runs: u32,
    /// Instead of rendering: build the BVH of a generated mesh of about this many triangles
    /// (a displaced terrain) and report build time, memory and ray throughput.
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=100_000_000))]
    pub bvh_triangles: Option<u32>,
    /// With --bvh-triangles: the obvhs preset (default: the renderer's own choice for the size).
    #[arg(long, value_parser = ["fastest", "very_fast", "fast", "medium", "slow", "very_slow"])]
    pub bvh_preset: Option<String>,
}
