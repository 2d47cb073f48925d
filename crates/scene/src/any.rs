//! One entry point for every scene format: Mitsuba 3 XML and glTF 2.0 by extension, TOML
//! otherwise.
use crate::{Scene, SceneError, gltf, load_mitsuba, load_scene};
use std::path::Path;

/// Loads `path` as Mitsuba 3 XML when its extension is `.xml`, as glTF 2.0 when it is
/// `.gltf` or `.glb` (any case), otherwise as an eyeadapt TOML scene.
pub fn load_scene_file(path: &Path) -> Result<Scene, SceneError> {
    if is_mitsuba_path(path) {
        load_mitsuba(path, &[])
    } else if gltf::is_gltf_path(path) {
        gltf::load_gltf(path)
    } else {
        load_scene(path)
    }
}

/// True for paths that [`load_scene_file`] reads as Mitsuba XML.
pub fn is_mitsuba_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dispatches_on_the_extension() {
        assert!(is_mitsuba_path(Path::new("a/b/scene.XML")));
        assert!(!is_mitsuba_path(Path::new("scene.toml")));
        assert!(!is_mitsuba_path(Path::new("xml")));
        let e = load_scene_file(Path::new("/nonexistent/scene.xml")).unwrap_err();
        assert!(e.to_string().contains("cannot read scene file"));
    }
}
