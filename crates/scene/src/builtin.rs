//! Built-in scenes, usable wherever a scene path is (`builtin:NAME`), from any directory.
//! Scene files without external meshes are embedded in the binary; procedural scenes are
//! generated in code.
use crate::{Scene, SceneError, load_scene_str};
use std::path::Path;

/// (name, one-line description) of every built-in scene.
pub fn builtin_scenes() -> Vec<(&'static str, &'static str)> {
    EMBEDDED.iter().map(|(n, d, _)| (*n, *d)).collect()
}

const EMBEDDED: &[(&str, &str, &str)] = &[
    (
        "cornell-box",
        "the classic Cornell box: white, red and green walls, one warm quad light",
        include_str!("../../../scenes/cornell-box/scene.toml"),
    ),
    (
        "three-rooms",
        "the paper's walkthrough: rooms lit white, orange, blue; glossy bench; 5 s camera path",
        include_str!("../../../scenes/three-rooms/scene.toml"),
    ),
];

/// Loads `builtin:NAME`.
pub fn load_builtin(name: &str) -> Result<Scene, SceneError> {
    match EMBEDDED.iter().find(|(n, _, _)| *n == name) {
        Some((n, _, text)) => load_scene_str(text, Path::new(&format!("builtin:{n}"))),
        None => Err(SceneError {
            diagnostics: vec![crate::Diagnostic {
                severity: crate::Severity::Error,
                file: format!("builtin:{name}").into(),
                line: 0,
                col: 0,
                message: format!(
                    "no built-in scene named \"{name}\" (available: {})",
                    builtin_scenes()
                        .iter()
                        .map(|(n, _)| *n)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }],
        }),
    }
}

/// Loads a scene given as `builtin:NAME` or as a file path.
pub fn resolve_scene(spec: &str) -> Result<Scene, SceneError> {
    match spec.strip_prefix("builtin:") {
        Some(name) => load_builtin(name),
        None => crate::load_scene_file(Path::new(spec)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_scene_loads_without_warnings() {
        for (name, _) in builtin_scenes() {
            let s = load_builtin(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(s.warnings.is_empty(), "{name}: {:?}", s.warnings);
            assert!(s.camera.is_some());
        }
        assert!(
            load_builtin("nope")
                .unwrap_err()
                .to_string()
                .contains("cornell-box")
        );
    }
}
