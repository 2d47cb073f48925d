//! Built-in scenes, usable wherever a scene path is (`builtin:NAME`), from any directory.
//! Their scene files are embedded in the binary, with the images they name (the interior's
//! sky and floor, written by its `gen.py`).
use crate::{ImageCache, Scene, SceneError, load_scene_str_with, scene_dir};
use std::path::Path;

/// (name, one-line description) of every built-in scene.
pub fn builtin_scenes() -> Vec<(&'static str, &'static str)> {
    EMBEDDED.iter().map(|(n, d, _)| (*n, *d)).collect()
}

/// Files a built-in scene names, by the name it uses: (scene, file name, bytes).
const EMBEDDED_FILES: &[(&str, &str, &[u8])] = &[
    (
        "interior",
        "sky.png",
        include_bytes!("../../../scenes/interior/sky.png"),
    ),
    (
        "interior",
        "planks.png",
        include_bytes!("../../../scenes/interior/planks.png"),
    ),
];

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
    (
        "cornell-orange",
        "paper case 1 (Fig. 5): all-white Cornell box, one 2700 K (orange) light",
        include_str!("../../../scenes/cornell-orange/scene.toml"),
    ),
    (
        "white-world-orange-light",
        "paper case 2 (Fig. 6): closed room of one grey reflectance, 2700 K light",
        include_str!("../../../scenes/one-reflectance/white-world-orange-light.toml"),
    ),
    (
        "orange-world-white-light",
        "paper case 2 (Fig. 7): closed room of one orange reflectance, white light",
        include_str!("../../../scenes/one-reflectance/orange-world-white-light.toml"),
    ),
    (
        "cornell-green-floor",
        "paper case 3 (Fig. 8): Cornell box, green floor, white light, 24-patch colour checker",
        include_str!("../../../scenes/cornell-green-floor/scene.toml"),
    ),
    (
        "statue-red-spot",
        "paper case 4 (Fig. 9): white statue lit by a red spot and a white ceiling light",
        include_str!("../../../scenes/statue-red-spot/scene.toml"),
    ),
    (
        "two-rooms",
        "paper case 5 (Fig. 10-12): room 1 lit by four orange lights, room 2 by four blue",
        include_str!("../../../scenes/two-rooms/scene.toml"),
    ),
    (
        "interior",
        "a sunlit room (sky and sun through glass panes, plank floor, a glass ball) and a lamp-lit one; 5 s walk",
        include_str!("../../../scenes/interior/scene.toml"),
    ),
];

/// Loads `builtin:NAME`.
pub fn load_builtin(name: &str) -> Result<Scene, SceneError> {
    match EMBEDDED.iter().find(|(n, _, _)| *n == name) {
        Some((n, _, text)) => {
            let path = format!("builtin:{n}");
            let path = Path::new(&path);
            let dir = scene_dir(path);
            let files = EMBEDDED_FILES
                .iter()
                .filter(|(scene, _, _)| scene == n)
                .map(|(_, file, bytes)| (dir.join(file), *bytes));
            load_scene_str_with(text, path, ImageCache::with_embedded(files))
        }
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

    #[test]
    fn the_interior_reads_its_embedded_images_as_the_files_on_disk() {
        let built = load_builtin("interior").unwrap();
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/interior");
        let disk = crate::load_scene_file(&dir.join("scene.toml")).unwrap();
        let (a, b) = (
            built.environment_map.as_ref().unwrap(),
            disk.environment_map.as_ref().unwrap(),
        );
        assert_eq!((a.image.width, a.image.height), (256, 128));
        assert_eq!(a.image, b.image);
        assert_eq!(a.scale, b.scale);
        let images = |s: &Scene| -> Vec<crate::Image> {
            s.textures
                .iter()
                .filter_map(|t| match t {
                    crate::Texture::Bitmap(b) => Some(b.image.as_ref().clone()),
                    _ => None,
                })
                .collect()
        };
        assert_eq!(images(&built).len(), 2);
        assert_eq!(images(&built), images(&disk));
    }
}
