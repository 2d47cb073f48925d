//! Mitsuba's `serialized` meshes (format versions 3 and 4, what Mitsuba 0.6 and 3 write for
//! scenes): a little-endian file of one or more zlib streams, each preceded by the header
//! (`0x041C`, version), with a table of their offsets at the end. A stream holds a flag word,
//! (version 4) the shape's name, the vertex and triangle counts, then positions, optional
//! normals, UVs and colours (single or double precision) and `u32` triangle indices.
use crate::Mesh;
use glam::{Vec2, Vec3};
use std::io::Read;
use std::path::Path;

const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const FACE_NORMALS: u32 = 0x0010;
const DOUBLE_PRECISION: u32 = 0x2000;

/// One shape of a serialized file.
#[derive(Debug)]
pub(crate) struct SerializedMesh {
    pub mesh: Mesh,
    /// The file asks for flat shading (its normals, if any, are not used).
    pub face_normals: bool,
}

pub(crate) fn load_serialized(path: &Path, shape_index: usize) -> Result<SerializedMesh, String> {
    let bytes = crate::read_input(path)
        .map_err(|e| format!("cannot read serialized mesh {}: {e}", path.display()))?;
    parse_serialized(&bytes, shape_index)
        .map_err(|e| format!("serialized mesh {}: {e}", path.display()))
}

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(b.get(at..at + 8)?.try_into().ok()?))
}

/// Where shape `index`'s header starts.
fn shape_offset(b: &[u8], version: u16, index: usize) -> Result<usize, String> {
    if index == 0 {
        return Ok(0);
    }
    let truncated = || "the offset table at the end of the file is truncated".to_string();
    let count =
        u32_at(b, b.len().checked_sub(4).ok_or_else(truncated)?).ok_or_else(truncated)? as usize;
    if index >= count {
        return Err(format!(
            "shape_index {index} is out of range: the file holds {count} shapes (0..={})",
            count.saturating_sub(1)
        ));
    }
    let offset = if version >= 4 {
        let at = b
            .len()
            .checked_sub(8 * (count - index) + 4)
            .ok_or_else(truncated)?;
        u64_at(b, at).ok_or_else(truncated)? as usize
    } else {
        let at = b
            .len()
            .checked_sub(4 * (count - index + 1))
            .ok_or_else(truncated)?;
        u32_at(b, at).ok_or_else(truncated)? as usize
    };
    if offset + 4 > b.len() {
        return Err(format!(
            "shape {index}'s offset {offset} is past the end of the file"
        ));
    }
    Ok(offset)
}

pub(crate) fn parse_serialized(b: &[u8], shape_index: usize) -> Result<SerializedMesh, String> {
    let (magic, version) = match (u16_at(b, 0), u16_at(b, 2)) {
        (Some(m), Some(v)) => (m, v),
        _ => return Err("too short for a serialized mesh".into()),
    };
    if magic != MAGIC {
        return Err(format!(
            "not a serialized mesh (it starts with {magic:#06x}, expected {MAGIC:#06x})"
        ));
    }
    if !matches!(version, 3 | 4) {
        return Err(format!(
            "format version {version} is not supported (versions 3 and 4 are)"
        ));
    }
    let start = shape_offset(b, version, shape_index)?;
    let mut z = flate2::read::ZlibDecoder::new(&b[start + 4..]);
    read_stream(&mut z, version).map_err(|e| format!("shape {shape_index}: {e}"))
}

/// Reads exactly `n` bytes (never reserving more than what arrives: counts come from the file).
fn take(z: &mut impl Read, n: usize) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let got = z
        .take(n as u64)
        .read_to_end(&mut out)
        .map_err(|e| format!("corrupt zlib data: {e}"))?;
    if got != n {
        return Err("the mesh data ends early".into());
    }
    Ok(out)
}

fn floats(z: &mut impl Read, n: usize, double: bool) -> Result<Vec<f32>, String> {
    let size = if double { 8 } else { 4 };
    let bytes = take(z, n.checked_mul(size).ok_or("absurd vertex count")?)?;
    Ok(if double {
        bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")) as f32)
            .collect()
    } else {
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect()
    })
}

fn read_stream(z: &mut impl Read, version: u16) -> Result<SerializedMesh, String> {
    let flags = u32::from_le_bytes(take(z, 4)?.try_into().expect("4 bytes"));
    let mut name = Vec::new();
    if version == 4 {
        loop {
            let c = take(z, 1)?[0];
            if c == 0 {
                break;
            }
            name.push(c);
        }
    }
    let vertices = u64::from_le_bytes(take(z, 8)?.try_into().expect("8 bytes"));
    let triangles = u64::from_le_bytes(take(z, 8)?.try_into().expect("8 bytes"));
    let (nv, nt) = (usize::try_from(vertices), usize::try_from(triangles));
    let (Ok(nv), Ok(nt)) = (nv, nt) else {
        return Err("absurd vertex or triangle count".into());
    };
    if nv > u32::MAX as usize {
        return Err(format!(
            "{nv} vertices: more than 32-bit indices can address"
        ));
    }
    let double = flags & DOUBLE_PRECISION != 0;
    let vec3s = |v: Vec<f32>| -> Vec<Vec3> { v.chunks_exact(3).map(Vec3::from_slice).collect() };
    let positions = vec3s(floats(z, 3 * nv, double)?);
    if positions.iter().any(|p| !p.is_finite()) {
        return Err("a vertex position is not finite".into());
    }
    let normals = if flags & HAS_NORMALS != 0 {
        vec3s(floats(z, 3 * nv, double)?)
            .into_iter()
            .map(|n| n.normalize_or_zero())
            .collect()
    } else {
        Vec::new()
    };
    let uvs = if flags & HAS_TEXCOORDS != 0 {
        floats(z, 2 * nv, double)?
            .chunks_exact(2)
            .map(Vec2::from_slice)
            .collect()
    } else {
        Vec::new()
    };
    let colors = if flags & HAS_COLORS != 0 {
        vec3s(floats(z, 3 * nv, double)?)
    } else {
        Vec::new()
    };
    let index_bytes = take(z, nt.checked_mul(12).ok_or("absurd triangle count")?)?;
    let indices: Vec<[u32; 3]> = index_bytes
        .chunks_exact(12)
        .map(|c| [0, 4, 8].map(|k| u32::from_le_bytes(c[k..k + 4].try_into().expect("4 bytes"))))
        .collect();
    if indices.iter().flatten().any(|&i| i as usize >= nv) {
        return Err("a triangle indexes a vertex that does not exist".into());
    }
    if indices.is_empty() {
        return Err("no triangles".into());
    }
    Ok(SerializedMesh {
        mesh: Mesh {
            name: String::from_utf8_lossy(&name).into_owned(),
            positions,
            indices,
            normals,
            uvs,
            colors,
            face_colors: Vec::new(),
        },
        face_normals: flags & FACE_NORMALS != 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// A version-4 stream: one triangle with UVs, named `name`.
    fn stream(name: &str, z: f32) -> Vec<u8> {
        let mut raw = Vec::new();
        raw.extend((HAS_TEXCOORDS | FACE_NORMALS).to_le_bytes());
        raw.extend(name.as_bytes());
        raw.push(0);
        raw.extend(3u64.to_le_bytes());
        raw.extend(1u64.to_le_bytes());
        for v in [0.0, 0.0, z, 1.0, 0.0, z, 0.0, 1.0, z] {
            raw.extend(f32::to_le_bytes(v));
        }
        for v in [0.0f32, 0.0, 1.0, 0.0, 0.0, 1.0] {
            raw.extend(v.to_le_bytes());
        }
        for i in [0u32, 1, 2] {
            raw.extend(i.to_le_bytes());
        }
        let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        e.write_all(&raw).unwrap();
        let mut out = MAGIC.to_le_bytes().to_vec();
        out.extend(4u16.to_le_bytes());
        out.extend(e.finish().unwrap());
        out
    }

    fn two_shapes() -> Vec<u8> {
        let mut file = stream("first", 0.0);
        let second = file.len() as u64;
        file.extend(stream("second", 5.0));
        file.extend(0u64.to_le_bytes());
        file.extend(second.to_le_bytes());
        file.extend(2u32.to_le_bytes());
        file
    }

    #[test]
    fn shape_index_picks_the_stream_through_the_offset_table() {
        let file = two_shapes();
        let a = parse_serialized(&file, 0).unwrap();
        assert_eq!(a.mesh.name, "first");
        assert!(a.face_normals);
        assert_eq!(a.mesh.uvs[1], Vec2::new(1.0, 0.0));
        let b = parse_serialized(&file, 1).unwrap();
        assert_eq!(b.mesh.name, "second");
        assert_eq!(b.mesh.positions[2], Vec3::new(0.0, 1.0, 5.0));
        assert_eq!(b.mesh.indices, vec![[0, 1, 2]]);
        let e = parse_serialized(&file, 2).unwrap_err();
        assert!(e.contains("out of range"), "{e}");
    }

    #[test]
    fn corrupt_truncated_and_foreign_files_are_errors() {
        let file = two_shapes();
        let mut corrupt = file.clone();
        corrupt[10] ^= 0xff;
        assert!(parse_serialized(&corrupt, 0).is_err());
        assert!(parse_serialized(&file[..20], 0).is_err());
        assert!(
            parse_serialized(b"ply\nformat", 0)
                .unwrap_err()
                .contains("not a serialized")
        );
        assert!(parse_serialized(&file[..3], 0).is_err());
    }
}
