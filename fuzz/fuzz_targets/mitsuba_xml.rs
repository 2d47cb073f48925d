//! The Mitsuba 3 XML loader (`eyeadapt_scene::load_mitsuba_str`, with PLY meshes); see
//! `checks::mitsuba_xml`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::mitsuba_xml(data));
