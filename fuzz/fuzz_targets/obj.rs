//! The OBJ/MTL loading path (`eyeadapt_scene::load_obj_bytes`); see `checks::obj`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::obj(data));
