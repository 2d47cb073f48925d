//! Wavefront OBJ through `tobj`, with MTL `Kd` (diffuse reflectance) and `Ke` (emission).
use crate::{Bsdf, Material, MaterialId, Mesh, Rgb};
use glam::Vec3;
use std::path::Path;

/// The triangles and materials of one OBJ file.
#[derive(Clone, Debug)]
pub struct LoadedObj {
    pub meshes: Vec<Mesh>,
    /// Per mesh: the MTL material, or `None` for the error material.
    pub materials: Vec<Option<Material>>,
    pub warnings: Vec<String>,
}

/// Loads triangles of every model. With `override_material` the MTL is not needed at all.
pub(crate) fn load_obj(
    path: &Path,
    override_material: Option<MaterialId>,
) -> Result<LoadedObj, String> {
    if !path.is_file() {
        return Err(format!(
            "OBJ file {} does not exist or is not a file",
            path.display()
        ));
    }
    let (models, mtls) = tobj::load_obj(path, &tobj::GPU_LOAD_OPTIONS)
        .map_err(|e| format!("cannot load OBJ {}: {e}", path.display()))?;
    convert(path, models, mtls, override_material)
}

/// The same validation as a scene's `type = "obj"` shape, on an OBJ (and optionally its MTL)
/// held in memory; every `mtllib` resolves to `mtl`. `name` only labels messages. For fuzzing
/// and tests: the scene loader itself reads files with [`crate::load_scene`].
pub fn load_obj_bytes(obj: &[u8], mtl: Option<&[u8]>, name: &Path) -> Result<LoadedObj, String> {
    let (models, mtls) =
        tobj::load_obj_buf(&mut &obj[..], &tobj::GPU_LOAD_OPTIONS, |_| match mtl {
            Some(bytes) => tobj::load_mtl_buf(&mut &bytes[..]),
            None => Err(tobj::LoadError::OpenFileFailed),
        })
        .map_err(|e| format!("cannot load OBJ {}: {e}", name.display()))?;
    convert(name, models, mtls, None)
}

fn convert(
    path: &Path,
    models: Vec<tobj::Model>,
    mtls: Result<Vec<tobj::Material>, tobj::LoadError>,
    override_material: Option<MaterialId>,
) -> Result<LoadedObj, String> {
    let mut warnings = Vec::new();
    let mtls = match mtls {
        Ok(m) => m,
        Err(e) => {
            if override_material.is_none() {
                warnings.push(format!(
                    "{}: material library not loaded ({e}); its triangles render with the error material (magenta)",
                    path.display()
                ));
            }
            Vec::new()
        }
    };
    let mut out = LoadedObj {
        meshes: Vec::new(),
        materials: Vec::new(),
        warnings,
    };
    let mut warned_unknown = false;
    for model in models {
        let m = &model.mesh;
        if m.positions.len() % 3 != 0 || m.indices.len() % 3 != 0 {
            return Err(format!(
                "OBJ {}: model \"{}\" is malformed",
                path.display(),
                model.name
            ));
        }
        let positions: Vec<Vec3> = m
            .positions
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        if positions.iter().any(|p| !p.is_finite()) {
            return Err(format!(
                "OBJ {}: model \"{}\" has a non-finite vertex",
                path.display(),
                model.name
            ));
        }
        let n = positions.len() as u32;
        let indices: Vec<[u32; 3]> = m
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        if indices.iter().flatten().any(|&i| i >= n) {
            return Err(format!(
                "OBJ {}: model \"{}\" indexes a vertex that does not exist",
                path.display(),
                model.name
            ));
        }
        let normals: Vec<Vec3> = if m.normals.len() == m.positions.len() {
            m.normals
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2]).normalize_or_zero())
                .collect()
        } else {
            Vec::new()
        };
        let material = if override_material.is_some() {
            None
        } else {
            match m.material_id.and_then(|i| mtls.get(i)) {
                Some(mtl) => Some(from_mtl(path, mtl)?),
                None => {
                    if !mtls.is_empty() && !warned_unknown {
                        out.warnings.push(format!(
                            "{}: model \"{}\" has no known material (missing or unknown usemtl); rendering it with the error material (magenta)",
                            path.display(),
                            model.name
                        ));
                        warned_unknown = true;
                    }
                    None
                }
            }
        };
        out.meshes.push(Mesh {
            name: format!("{}#{}", path.display(), model.name),
            positions,
            indices,
            normals,
            material: override_material,
        });
        out.materials.push(material);
    }
    if out.meshes.iter().all(|m| m.indices.is_empty()) {
        return Err(format!("OBJ {} contains no triangles", path.display()));
    }
    Ok(out)
}

/// An MTL material as a diffuse [`Material`]. `Kd` above 1 is clamped (a sloppy MTL cannot make
/// a surface create energy); NaN, infinite or negative `Kd`/`Ke` are errors, as in TOML scenes.
fn from_mtl(path: &Path, mtl: &tobj::Material) -> Result<Material, String> {
    let colour = |key: &str, v: Option<[f32; 3]>, default: Rgb| -> Result<Rgb, String> {
        let Some(a) = v else { return Ok(default) };
        let problem = if a.iter().any(|c| !c.is_finite()) {
            "has a non-finite component"
        } else if a.iter().any(|&c| c < 0.0) {
            "has a negative component"
        } else {
            return Ok(Rgb::from_array(a));
        };
        Err(format!(
            "OBJ {}: MTL material \"{}\": {key} {a:?} {problem}",
            path.display(),
            mtl.name
        ))
    };
    let kd = colour("Kd", mtl.diffuse, Rgb::splat(0.8))?;
    let ke = colour("Ke", mtl.emissive, Rgb::ZERO)?;
    Ok(Material {
        name: format!("{}:{}", path.display(), mtl.name),
        bsdf: Bsdf::Diffuse {
            reflectance: kd.min(Rgb::ONE),
        },
        emission: ke,
    })
}
