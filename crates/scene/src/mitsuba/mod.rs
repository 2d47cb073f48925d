//! Mitsuba 3 XML scenes: the subset eyeadapt can render the same way (`docs/mitsuba.md`).
//!
//! Loading runs in two stages like the TOML loader: `xml.rs` turns the document into a tree
//! of plugin objects with typed, located properties (substituting `$parameters`), then
//! `build.rs` interprets the plugins it knows and reports everything else — unknown plugin
//! types, textures, unknown parameters of known plugins — as errors with `file:line:col`,
//! all at once.
//!
//! ```no_run
//! use std::path::Path;
//! let scene = eyeadapt_scene::load_mitsuba(Path::new("scenes/cornell-box/cornell.xml"), &[("spp", "256")])?;
//! # Ok::<(), eyeadapt_scene::SceneError>(())
//! ```
mod build;
mod ply;
mod presets;
mod serialized;
mod source;
mod spectrum;
mod xml;

use crate::Scene;
use crate::diagnostic::{Diagnostic, SceneError, Severity};
use source::Sources;
use std::path::Path;

pub use build::vertical_fov as mitsuba_vertical_fov;

/// Loads a Mitsuba 3 XML scene. `overrides` set `$name` parameters and take precedence over
/// the file's `<default name=… value=…>`s (like `mitsuba -D name=value`).
pub fn load_mitsuba(path: &Path, overrides: &[(&str, &str)]) -> Result<Scene, SceneError> {
    let text = crate::read_input_text(path).map_err(|e| SceneError {
        diagnostics: vec![Diagnostic {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: 0,
            col: 0,
            message: format!("cannot read scene file: {e}"),
        }],
    })?;
    load_mitsuba_str(&text, path, overrides)
}

/// Loads Mitsuba XML from text; `path` names it in messages and anchors relative file names.
pub fn load_mitsuba_str(
    text: &str,
    path: &Path,
    overrides: &[(&str, &str)],
) -> Result<Scene, SceneError> {
    let mut parser = xml::Parser::new(Sources::new(path, text), overrides);
    let doc = parser.parse(text);
    let mut diags = std::mem::take(&mut parser.diags);
    let sources = parser.sources;
    let scene = doc.as_ref().map(|doc| {
        let mut b = build::Builder::new(&sources);
        b.build(doc);
        diags.append(&mut b.diags);
        b.scene
    });
    // In file order, whichever stage found them.
    diags.sort_by_key(|d| (d.file != path, d.file.clone(), d.line, d.col));
    let (errors, warnings): (Vec<_>, Vec<_>) = diags
        .into_iter()
        .partition(|d| d.severity == Severity::Error);
    match scene {
        Some(scene) if errors.is_empty() => Ok(Scene { warnings, ..scene }),
        _ => Err(SceneError {
            diagnostics: errors.into_iter().chain(warnings).collect(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_xml_reports_its_position() {
        let e = load_mitsuba_str(
            "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n</scene>\n",
            Path::new("bad.xml"),
            &[],
        )
        .unwrap_err();
        let d = &e.diagnostics[0];
        assert_eq!(d.line, 3, "{e}");
        assert!(d.message.contains("malformed XML"), "{e}");
    }

    #[test]
    fn old_scene_versions_are_rejected() {
        let e = load_mitsuba_str(
            "<scene version=\"0.5.0\"><emitter type=\"constant\"/></scene>",
            Path::new("old.xml"),
            &[],
        )
        .unwrap_err();
        assert!(e.to_string().contains("version=\"0.5.0\""), "{e}");
    }
}
