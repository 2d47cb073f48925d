//! Frame specs (`FrameSet::from_str` and friends); see `checks::frame_spec`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::frame_spec(data));
