//! Wavefront OBJ through `tobj`, with MTL `Kd` (diffuse reflectance) and `Ke` (emission).
use crate::{Bsdf, Material, MaterialId, Mesh, Rgb};
use glam::Vec3;
use std::path::Path;

pub(crate) struct LoadedObj {
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
                Some(mtl) => Some(from_mtl(path, mtl)),
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

fn from_mtl(path: &Path, mtl: &tobj::Material) -> Material {
    let kd = mtl.diffuse.map_or(Rgb::splat(0.8), Rgb::from_array);
    let ke = mtl.emissive.map_or(Rgb::ZERO, Rgb::from_array);
    Material {
        name: format!("{}:{}", path.display(), mtl.name),
        // Clamp so that a sloppy MTL cannot make a surface create energy.
        bsdf: Bsdf::Diffuse {
            reflectance: kd.clamp(Rgb::ZERO, Rgb::ONE),
        },
        emission: ke.max(Rgb::ZERO),
    }
}
