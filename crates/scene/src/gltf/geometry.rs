//! glTF mesh primitives as object-space [`Mesh`]es.
//!
//! Each primitive of a glTF mesh becomes one eyeadapt mesh (a primitive has one material);
//! nodes that use the mesh become instances of it, so a mesh placed a thousand times is stored
//! once. Triangle lists, strips and fans are read; points and lines have no area and are
//! skipped with a warning. UVs are kept as they are: glTF's (0, 0) is the top-left corner of
//! an image with v growing downwards, which is eyeadapt's (and Mitsuba's) convention too.
use super::read::{GltfFile, at};
use crate::{Diagnostic, Mesh, Rgb, Severity};
use glam::{Vec2, Vec3};
use gltf::mesh::Mode;

/// Largest vertex or index count of one primitive (u32 indices, and a sanity bound far above
/// any real mesh).
const MAX_ELEMENTS: usize = 1 << 30;

/// The primitive as a mesh, or `Ok(None)` for primitives without area (points, lines).
pub fn primitive_mesh(
    f: &GltfFile,
    mesh: &gltf::Mesh,
    prim: &gltf::Primitive,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Option<Mesh>, Diagnostic> {
    let here = format!("/meshes/{}/primitives/{}", mesh.index(), prim.index());
    let mode = prim.mode();
    if matches!(
        mode,
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
    ) {
        let mut w = at(
            &f.path,
            &format!("{here}/mode"),
            "points and lines have no area; skipped",
        );
        w.severity = Severity::Warning;
        warnings.push(w);
        return Ok(None);
    }
    let reader = prim.reader(|b| f.buffers.get(b.index()).map(|d| &d.0[..]));
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| {
            at(
                &f.path,
                &format!("{here}/attributes"),
                "no POSITION attribute",
            )
        })?
        .map(Vec3::from_array)
        .collect();
    let n = positions.len();
    if n > MAX_ELEMENTS {
        return Err(at(
            &f.path,
            &format!("{here}/attributes/POSITION"),
            "too many vertices",
        ));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(at(
            &f.path,
            &format!("{here}/attributes/POSITION"),
            format!("vertex {i} is not finite"),
        ));
    }
    let flat: Vec<u32> = match reader.read_indices() {
        Some(ix) => ix.into_u32().collect(),
        None => (0..n as u32).collect(),
    };
    if let Some(bad) = flat.iter().find(|&&i| i as usize >= n) {
        return Err(at(
            &f.path,
            &format!("{here}/indices"),
            format!("index {bad} is past the {n} vertices"),
        ));
    }
    let indices = triangles(&flat, mode);
    let same_count = |what: &str, len: usize| {
        if len == n {
            Ok(())
        } else {
            Err(at(
                &f.path,
                &format!("{here}/attributes/{what}"),
                format!("{len} values for {n} vertices"),
            ))
        }
    };
    let normals: Vec<Vec3> = match reader.read_normals() {
        Some(it) => it.map(Vec3::from_array).collect(),
        None => Vec::new(),
    };
    if !normals.is_empty() {
        same_count("NORMAL", normals.len())?;
    }
    let uvs: Vec<Vec2> = match reader.read_tex_coords(0) {
        Some(it) => it.into_f32().map(Vec2::from_array).collect(),
        None => Vec::new(),
    };
    if !uvs.is_empty() {
        same_count("TEXCOORD_0", uvs.len())?;
    }
    let colors: Vec<Rgb> = match reader.read_colors(0) {
        // glTF vertex colours are linear (§3.7.2.1); alpha is dropped.
        Some(it) => it.into_rgb_f32().map(Rgb::from_array).collect(),
        None => Vec::new(),
    };
    if !colors.is_empty() {
        same_count("COLOR_0", colors.len())?;
    }
    let name = match (mesh.name(), mesh.primitives().len()) {
        (Some(m), 1) => m.to_string(),
        (Some(m), _) => format!("{m}#{}", prim.index()),
        (None, _) => format!("meshes/{}/primitives/{}", mesh.index(), prim.index()),
    };
    Ok(Some(Mesh {
        name,
        positions,
        indices,
        normals,
        uvs,
        colors,
        face_colors: Vec::new(),
    }))
}

/// Triangles of a list, strip or fan (glTF §3.7.2.1 gives the strip and fan orders).
fn triangles(ix: &[u32], mode: Mode) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..ix.len().saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [ix[i], ix[i + 1], ix[i + 2]]
                } else {
                    [ix[i + 1], ix[i], ix[i + 2]]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..ix.len().saturating_sub(1))
            .map(|i| [ix[i], ix[i + 1], ix[0]])
            .collect(),
        _ => ix.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_the_winding() {
        let ix = [0, 1, 2, 3, 4];
        assert_eq!(
            triangles(&ix, Mode::TriangleStrip),
            vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]
        );
        assert_eq!(
            triangles(&ix, Mode::TriangleFan),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert_eq!(triangles(&ix, Mode::Triangles), vec![[0, 1, 2]]);
    }
}
