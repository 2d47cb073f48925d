//! Wavefront OBJ through `tobj`: positions, normals, texture coordinates (`vt`, v flipped to
//! Mitsuba's image-down convention as its `flip_tex_coords` does), vertex colours, and MTL `Kd`
//! (diffuse reflectance), `map_Kd` (its texture) and `Ke` (emission).
use crate::{Bsdf, Material, MaterialId, Mesh, Param, Rgb};
use glam::{Vec2, Vec3};
use std::cell::RefCell;
use std::path::Path;

/// The triangles and materials of one OBJ file.
#[derive(Clone, Debug)]
pub struct LoadedObj {
    pub meshes: Vec<Mesh>,
    /// Per mesh: the MTL material, or `None` for the error material.
    pub materials: Vec<Option<Material>>,
    /// Per mesh: the material's `map_Kd` file (relative to the OBJ's directory, as written), to
    /// replace its constant reflectance.
    pub diffuse_maps: Vec<Option<String>>,
    pub warnings: Vec<String>,
}

/// Loads triangles of every model. With `override_material` the MTL is not needed at all.
pub(crate) fn load_obj(
    path: &Path,
    override_material: Option<MaterialId>,
) -> Result<LoadedObj, String> {
    let file =
        crate::open_input(path).map_err(|e| format!("cannot read OBJ {}: {e}", path.display()))?;
    // The text is only read again to point at the offending line of a failed load.
    let text = || crate::read_input(path).unwrap_or_default();
    // `mtllib` names resolve next to the OBJ, as tobj::load_obj resolves them.
    let dir = path.parent().unwrap_or(Path::new("."));
    let note = RefCell::new(None);
    // A missing MTL costs only its materials (a warning); one that cannot be read (a FIFO, a
    // device, no permission) is an error.
    let unreadable = RefCell::new(None);
    let mut reader = std::io::BufReader::new(file);
    let loaded = tobj::load_obj_buf(&mut reader, &tobj::GPU_LOAD_OPTIONS, |mtl| {
        let mtl_path = dir.join(mtl);
        let bytes = crate::read_input(&mtl_path).map_err(|e| {
            if e.kind() != std::io::ErrorKind::NotFound {
                *unreadable.borrow_mut() = Some(format!(
                    "OBJ {}: cannot read material library {}: {e}",
                    path.display(),
                    mtl_path.display()
                ));
            }
            tobj::LoadError::OpenFileFailed
        })?;
        load_mtl_checked(&bytes, &mtl_path, &note)
    });
    if let Some(e) = unreadable.take() {
        return Err(e);
    }
    let (models, mtls) = loaded.map_err(|e| {
        format!(
            "cannot load OBJ {}: {e}",
            at_line(path, &text(), Problem::Load(&e))
        )
    })?;
    let mtls = mtls.map_err(|e| note.take().unwrap_or_else(|| e.to_string()));
    convert(path, models, mtls, override_material).map_err(|e| e.located(path, &text()))
}

/// `tobj::load_mtl_buf`, after looking for what makes tobj 4.0.5 panic instead of failing: a
/// colour line (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than three numbers unwraps a short Vec.
/// Such a line fails like any malformed MTL, and `note` gets its `file:line` for the warning.
fn load_mtl_checked(
    bytes: &[u8],
    mtl_path: &Path,
    note: &RefCell<Option<String>>,
) -> tobj::MTLLoadResult {
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = String::from_utf8_lossy(raw);
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next()
            && words.count() < 3
        {
            *note.borrow_mut() = Some(format!(
                "{}:{}: `{key}` needs three numbers",
                mtl_path.display(),
                i + 1
            ));
            return Err(tobj::LoadError::MaterialParseError);
        }
    }
    tobj::load_mtl_buf(&mut &bytes[..])
}

/// The same validation as a scene's `type = "obj"` shape, on an OBJ (and optionally its MTL)
/// held in memory; every `mtllib` resolves to `mtl`. `name` only labels messages. For fuzzing
/// and tests: the scene loader itself reads files with [`crate::load_scene`].
pub fn load_obj_bytes(obj: &[u8], mtl: Option<&[u8]>, name: &Path) -> Result<LoadedObj, String> {
    let note = RefCell::new(None);
    let (models, mtls) =
        tobj::load_obj_buf(&mut &obj[..], &tobj::GPU_LOAD_OPTIONS, |p| match mtl {
            Some(bytes) => load_mtl_checked(bytes, p, &note),
            None => Err(tobj::LoadError::OpenFileFailed),
        })
        .map_err(|e| {
            format!(
                "cannot load OBJ {}: {e}",
                at_line(name, obj, Problem::Load(&e))
            )
        })?;
    let mtls = mtls.map_err(|e| note.take().unwrap_or_else(|| e.to_string()));
    convert(name, models, mtls, None).map_err(|e| e.located(name, obj))
}

/// A problem `convert` found, before the OBJ line it comes from is looked up.
enum ConvertError {
    NonFiniteVertex(String),
    Other(String),
}

impl ConvertError {
    fn located(self, path: &Path, text: &[u8]) -> String {
        match self {
            ConvertError::NonFiniteVertex(model) => format!(
                "OBJ {}: model \"{model}\" has a non-finite vertex",
                at_line(path, text, Problem::NonFiniteVertex)
            ),
            ConvertError::Other(m) => m,
        }
    }
}

impl From<String> for ConvertError {
    fn from(m: String) -> Self {
        ConvertError::Other(m)
    }
}

#[derive(Clone, Copy)]
enum Problem<'a> {
    Load(&'a tobj::LoadError),
    NonFiniteVertex,
}

/// `path:LINE` for the first line of the OBJ text that explains `problem`, else `path`.
/// (tobj reports what went wrong but not where.)
fn at_line(path: &Path, text: &[u8], problem: Problem) -> String {
    match find_line(text, problem) {
        Some(line) => format!("{}:{line}", path.display()),
        None => path.display().to_string(),
    }
}

fn find_line(text: &[u8], problem: Problem) -> Option<usize> {
    use tobj::LoadError as E;
    let lines = || text.split(|&b| b == b'\n').enumerate();
    let mut total = [0isize; 3]; // v, vt, vn
    for (_, l) in lines() {
        let l = String::from_utf8_lossy(l);
        match l.split_whitespace().next() {
            Some("v") => total[0] += 1,
            Some("vt") => total[1] += 1,
            Some("vn") => total[2] += 1,
            _ => {}
        }
    }
    let mut seen = [0isize; 3];
    for (i, raw) in lines() {
        let Ok(l) = std::str::from_utf8(raw) else {
            if matches!(problem, Problem::Load(E::ReadError)) {
                return Some(i + 1);
            }
            continue;
        };
        let mut words = l.split_whitespace();
        let key = words.next();
        let floats: Vec<Option<f32>> = words.clone().map(|w| w.parse().ok()).collect();
        let bad_floats = |n: usize| floats.len() < n || floats[..n].iter().any(Option::is_none);
        let hit = match (key, problem) {
            (Some("v"), Problem::Load(E::PositionParseError)) => bad_floats(3),
            (Some("v"), Problem::NonFiniteVertex) => floats
                .iter()
                .take(3)
                .any(|f| f.is_some_and(|x| !x.is_finite())),
            (Some("vt"), Problem::Load(E::TexcoordParseError)) => bad_floats(2),
            (Some("vn"), Problem::Load(E::NormalParseError)) => bad_floats(3),
            (
                Some("f"),
                Problem::Load(
                    E::FaceParseError
                    | E::FaceVertexOutOfBounds
                    | E::FaceTexCoordOutOfBounds
                    | E::FaceNormalOutOfBounds,
                ),
            ) => words.any(|w| {
                w.split('/').enumerate().any(|(k, c)| {
                    if c.is_empty() && k > 0 {
                        return false;
                    }
                    match c.parse::<isize>() {
                        Err(_) => true,
                        Ok(x) => k > 2 || x == 0 || x > total[k] || x < -seen[k],
                    }
                })
            }),
            _ => false,
        };
        if hit {
            return Some(i + 1);
        }
        match key {
            Some("v") => seen[0] += 1,
            Some("vt") => seen[1] += 1,
            Some("vn") => seen[2] += 1,
            _ => {}
        }
    }
    None
}

fn convert(
    path: &Path,
    models: Vec<tobj::Model>,
    mtls: Result<Vec<tobj::Material>, String>,
    override_material: Option<MaterialId>,
) -> Result<LoadedObj, ConvertError> {
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
        diffuse_maps: Vec::new(),
        warnings,
    };
    let mut warned_unknown = false;
    for model in models {
        let m = &model.mesh;
        let mesh = mesh_of(path, &model)?;
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
        let map = match (&material, m.material_id.and_then(|i| mtls.get(i))) {
            (Some(_), Some(mtl)) => mtl.diffuse_texture.clone(),
            _ => None,
        };
        out.meshes.push(mesh);
        out.materials.push(material);
        out.diffuse_maps.push(map);
    }
    if out.meshes.iter().all(|m| m.indices.is_empty()) {
        return Err(format!("OBJ {} contains no triangles", path.display()).into());
    }
    Ok(out)
}

/// A tobj model as a [`Mesh`]: finite positions, texture coordinates and colours, indices
/// that exist; normals, UVs (flipped to the image's top-left origin) and colours kept only
/// when every vertex has them.
fn mesh_of(path: &Path, model: &tobj::Model) -> Result<Mesh, ConvertError> {
    let m = &model.mesh;
    let malformed = |what: &str| -> ConvertError {
        format!("OBJ {}: model \"{}\" {what}", path.display(), model.name).into()
    };
    if !m.positions.len().is_multiple_of(3) || !m.indices.len().is_multiple_of(3) {
        return Err(malformed("is malformed"));
    }
    let positions: Vec<Vec3> = m
        .positions
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect();
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(ConvertError::NonFiniteVertex(model.name.clone()));
    }
    let n = positions.len() as u32;
    let indices: Vec<[u32; 3]> = m
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    if indices.iter().flatten().any(|&i| i >= n) {
        return Err(malformed("indexes a vertex that does not exist"));
    }
    let normals: Vec<Vec3> = if m.normals.len() == m.positions.len() {
        m.normals
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]).normalize_or_zero())
            .collect()
    } else {
        Vec::new()
    };
    let uvs: Vec<Vec2> = if m.texcoords.len() / 2 == positions.len() {
        m.texcoords
            .chunks_exact(2)
            .map(|t| Vec2::new(t[0], 1.0 - t[1]))
            .collect()
    } else {
        Vec::new()
    };
    let colors: Vec<Rgb> = if m.vertex_color.len() == m.positions.len() {
        m.vertex_color
            .chunks_exact(3)
            .map(|c| Rgb::new(c[0], c[1], c[2]))
            .collect()
    } else {
        Vec::new()
    };
    if !uvs.iter().all(|t| t.is_finite()) || !colors.iter().all(|c| c.is_finite()) {
        return Err(malformed(
            "has a non-finite texture coordinate or vertex colour",
        ));
    }
    Ok(Mesh {
        name: format!("{}#{}", path.display(), model.name),
        positions,
        indices,
        normals,
        uvs,
        colors,
    })
}

/// An MTL material as a diffuse [`Material`]. `Kd` above 1 is clamped (a sloppy MTL cannot make
/// a surface create energy); NaN, infinite, negative or absurdly large (above
/// [`crate::MAX_COLOUR`]) `Kd`/`Ke` are errors, as in TOML scenes.
fn from_mtl(path: &Path, mtl: &tobj::Material) -> Result<Material, String> {
    let colour = |key: &str, v: Option<[f32; 3]>, default: Rgb| -> Result<Rgb, String> {
        let Some(a) = v else { return Ok(default) };
        let Err(problem) = crate::check_colour(Rgb::from_array(a)) else {
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
            reflectance: Param::Const(kd.min(Rgb::ONE)),
        },
        emission: ke,
    })
}
