//! The `eyeadapt` binary: everything lives in `crates/cli`; this file only hands over.
fn main() -> std::process::ExitCode {
    eyeadapt_cli::main()
}
