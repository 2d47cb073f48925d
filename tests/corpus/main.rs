//! The malformed-input corpus (`tests/corpus/`, format in its README): every case must exit
//! with code 2, print its expected location and message parts, and leave an output directory
//! that already held good results byte-for-byte unchanged. One test per kind of input:
//!
//! | directory | case | command | test |
//! |---|---|---|---|
//! | `scene/` | `NAME.toml` | `eyeadapt render CASE` into a directory holding a good render | `inputs.rs` |
//! | `obj/` | `NAME.obj` (+ `NAME.mtl`) | `render` of a scene whose only shape is the OBJ | `inputs.rs` |
//! | `xml/` | `NAME.xml` | `eyeadapt render CASE` (Mitsuba 3 XML) into the good render | `inputs.rs` |
//! | `gltf/` | `NAME.gltf` | `eyeadapt render CASE` (glTF 2.0) into the good render | `inputs.rs` |
//! | `job/` | `NAME.toml` | `eyeadapt sequence CASE` into a directory holding a good sequence | `sequences.rs` |
//! | `frames/` | `NAME.spec` | `eyeadapt sequence --frames SPEC` into the same directory | `sequences.rs` |
//! | `merge/` | `NAME/` (a chunk output) | `eyeadapt merge GOOD_CHUNK CASE --frames 0-3` into a good merge | `sequences.rs` |
//! | `report/` | `NAME.csv` / `NAME.manifest` | `eyeadapt report` of a good sequence with that CSV / manifest patch | `report.rs` |
//! | `fuzz-regressions/` | inputs the fuzzers once crashed on | the fuzz targets' checks | `fuzz.rs` |
//!
//! `harness.rs` holds what they share; `samples.rs` (non-finite samples) and `manifests.rs`
//! (hostile manifests) are the checks beside the corpus files.
#[path = "../common/mod.rs"]
mod common;

mod fuzz;
mod harness;
mod inputs;
mod manifests;
mod report;
mod samples;
mod sequences;
