//! The TOML scene loader (`eyeadapt_scene::load_scene_str`); see `checks::scene_toml`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::scene_toml(data));
