//! Stanford PLY meshes, as Mitsuba's `ply` shape reads them: ASCII or binary little-endian;
//! vertex positions `x y z`, optional normals `nx ny nz`, texture coordinates (`u v`,
//! `texture_u texture_v` or `s t`) and colours (`r g b` or `red green blue`, 8-bit ones scaled
//! by 1/255), polygonal faces (`vertex_indices` or `vertex_index`, fan-triangulated). Other
//! properties and elements are skipped.
use glam::{Vec2, Vec3};
use std::path::Path;

#[derive(Debug)]
pub(crate) struct PlyMesh {
    pub positions: Vec<Vec3>,
    /// Empty unless every vertex has `nx ny nz`.
    pub normals: Vec<Vec3>,
    /// Empty unless the vertices have texture coordinates.
    pub uvs: Vec<Vec2>,
    /// Empty unless the vertices have colours.
    pub colors: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// One per triangle (a polygon's colour for each of its triangles); empty unless the
    /// faces have colours.
    pub face_colors: Vec<Vec3>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Scalar> {
        Some(match s {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

#[derive(Debug)]
enum Prop {
    Scalar(String, Scalar),
    /// (name, count type, item type)
    List(String, Scalar, Scalar),
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Prop>,
}

/// Sequential reader over the body, in either encoding.
enum Body<'a> {
    Ascii(std::str::SplitAsciiWhitespace<'a>),
    Binary(&'a [u8], usize),
}

impl Body<'_> {
    fn read(&mut self, ty: Scalar) -> Result<f64, String> {
        match self {
            Body::Ascii(tokens) => {
                let t = tokens
                    .next()
                    .ok_or("the file ends before all elements were read")?;
                t.parse::<f64>()
                    .map_err(|_| format!("\"{t}\" is not a number"))
            }
            Body::Binary(bytes, pos) => {
                let n = ty.size();
                let b = bytes
                    .get(*pos..*pos + n)
                    .ok_or("the file ends before all elements were read")?;
                *pos += n;
                Ok(match ty {
                    Scalar::I8 => b[0] as i8 as f64,
                    Scalar::U8 => b[0] as f64,
                    Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
                    Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
                    Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    Scalar::F64 => f64::from_le_bytes(b.try_into().expect("8 bytes")),
                })
            }
        }
    }
}

pub(crate) fn load_ply(path: &Path) -> Result<PlyMesh, String> {
    let bytes =
        crate::read_input(path).map_err(|e| format!("cannot read PLY {}: {e}", path.display()))?;
    parse_ply(&bytes).map_err(|e| format!("PLY {}: {e}", path.display()))
}

pub(crate) fn parse_ply(bytes: &[u8]) -> Result<PlyMesh, String> {
    let (header, body_start) = split_header(bytes)?;
    let (format, elements) = parse_header(header)?;
    let mut body = match format.as_str() {
        "ascii" => Body::Ascii(
            std::str::from_utf8(&bytes[body_start..])
                .map_err(|_| "the ASCII body is not text")?
                .split_ascii_whitespace(),
        ),
        "binary_little_endian" => Body::Binary(bytes, body_start),
        "binary_big_endian" => {
            return Err(
                "binary_big_endian PLY is not supported (convert it to binary_little_endian or ascii)"
                    .into(),
            );
        }
        f => return Err(format!("unknown format \"{f}\"")),
    };
    let mut out = PlyMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        colors: Vec::new(),
        indices: Vec::new(),
        face_colors: Vec::new(),
    };
    let mut saw_vertices = false;
    for el in &elements {
        match el.name.as_str() {
            "vertex" => {
                saw_vertices = true;
                read_vertices(el, &mut body, bytes.len(), &mut out)?;
            }
            "face" => read_faces(el, &mut body, &mut out)?,
            _ => {
                for _ in 0..el.count {
                    for p in &el.props {
                        read_prop(p, &mut body)?;
                    }
                }
            }
        }
    }
    if !saw_vertices {
        return Err("no vertex element".into());
    }
    let n = out.positions.len() as u32;
    if out.indices.iter().flatten().any(|&i| i >= n) {
        return Err("a face indexes a vertex that does not exist".into());
    }
    if out.indices.is_empty() {
        return Err("no triangles".into());
    }
    Ok(out)
}

/// The header text and the offset where the body starts.
fn split_header(bytes: &[u8]) -> Result<(&str, usize), String> {
    const END: &[u8] = b"end_header";
    let end = bytes
        .windows(END.len())
        .position(|w| w == END)
        .ok_or("no `end_header` line: not a PLY file")?;
    let mut body_start = end + END.len();
    // The header ends with its line break (LF or CRLF).
    if bytes.get(body_start) == Some(&b'\r') {
        body_start += 1;
    }
    if bytes.get(body_start) == Some(&b'\n') {
        body_start += 1;
    }
    let header = std::str::from_utf8(&bytes[..end]).map_err(|_| "the header is not text")?;
    Ok((header, body_start))
}

/// The `format` and the declared elements.
fn parse_header(header: &str) -> Result<(String, Vec<Element>), String> {
    let mut lines = header.lines().map(str::trim);
    if lines.next() != Some("ply") {
        return Err("the file does not start with `ply`".into());
    }
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [] => {}
            ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, _version] => format = Some(f.to_string()),
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: count
                    .parse()
                    .map_err(|_| format!("element {name} has a bad count \"{count}\""))?,
                props: Vec::new(),
            }),
            ["property", "list", ct, it, name] => {
                let el = elements.last_mut().ok_or("property before any element")?;
                let ct = Scalar::parse(ct).ok_or(format!("unknown type \"{ct}\""))?;
                let it = Scalar::parse(it).ok_or(format!("unknown type \"{it}\""))?;
                el.props.push(Prop::List(name.to_string(), ct, it));
            }
            ["property", ty, name] => {
                let el = elements.last_mut().ok_or("property before any element")?;
                let ty = Scalar::parse(ty).ok_or(format!("unknown type \"{ty}\""))?;
                el.props.push(Prop::Scalar(name.to_string(), ty));
            }
            _ => return Err(format!("cannot read header line \"{line}\"")),
        }
    }
    Ok((format.ok_or("no `format` line")?, elements))
}

/// Reads one property; a scalar's value, or 0 for a list (whose items are skipped).
fn read_prop(p: &Prop, body: &mut Body) -> Result<f64, String> {
    match p {
        Prop::Scalar(_, ty) => body.read(*ty),
        Prop::List(_, ct, it) => {
            let n = body.read(*ct)? as usize;
            for _ in 0..n {
                body.read(*it)?;
            }
            Ok(0.0)
        }
    }
}

/// The `vertex` element: positions and, when all three are there, normals. `file_len` bounds
/// what is reserved.
fn read_vertices(
    el: &Element,
    body: &mut Body,
    file_len: usize,
    out: &mut PlyMesh,
) -> Result<(), String> {
    let find = |n: &str| {
        el.props
            .iter()
            .position(|p| matches!(p, Prop::Scalar(name, _) if name == n))
    };
    let both = |names: [&str; 2]| match names.map(find) {
        [Some(a), Some(b)] => Some([a, b]),
        _ => None,
    };
    let uv_idx = both(["u", "v"])
        .or_else(|| both(["texture_u", "texture_v"]))
        .or_else(|| both(["s", "t"]));
    let (rgb_idx, rgb_scale) = colour_props(el);
    let pos_idx = ["x", "y", "z"].map(find);
    if pos_idx.iter().any(Option::is_none) {
        return Err("the vertex element lacks x, y or z".into());
    }
    let nrm_idx = ["nx", "ny", "nz"].map(find);
    let has_normals = nrm_idx.iter().all(Option::is_some);
    // The count comes from the header: never reserve more than the body can hold
    // (a hostile `element vertex 18446744073709551615` aborted the process).
    out.positions.reserve(el.count.min(file_len));
    let mut vals = vec![0.0f64; el.props.len()];
    for _ in 0..el.count {
        for (i, p) in el.props.iter().enumerate() {
            vals[i] = read_prop(p, body)?;
        }
        let p = pos_idx.map(|i| vals[i.expect("checked")] as f32);
        let p = Vec3::from_array(p);
        if !p.is_finite() {
            return Err("a vertex position is not finite".into());
        }
        out.positions.push(p);
        if has_normals {
            let n = nrm_idx.map(|i| vals[i.expect("checked")] as f32);
            out.normals.push(Vec3::from_array(n).normalize_or_zero());
        }
        if let Some(i) = uv_idx {
            out.uvs.push(Vec2::from_array(i.map(|i| vals[i] as f32)));
        }
        if let Some(i) = rgb_idx {
            out.colors
                .push(Vec3::from_array(i.map(|i| (vals[i] * rgb_scale) as f32)));
        }
    }
    Ok(())
}

/// The colour properties of an element (`r g b`, `red green blue` or `color_0 color_1
/// color_2`) and the factor that takes them to [0, 1] (1/255 for 8-bit ones).
fn colour_props(el: &Element) -> (Option<[usize; 3]>, f64) {
    let find = |n: &str| {
        el.props
            .iter()
            .position(|p| matches!(p, Prop::Scalar(name, _) if name == n))
    };
    let idx = [
        ["r", "g", "b"],
        ["red", "green", "blue"],
        ["color_0", "color_1", "color_2"],
    ]
    .into_iter()
    .find_map(|names| match names.map(find) {
        [Some(r), Some(g), Some(b)] => Some([r, g, b]),
        _ => None,
    });
    let scale = idx.map_or(1.0, |i| match &el.props[i[0]] {
        Prop::Scalar(_, Scalar::U8) => 1.0 / 255.0,
        _ => 1.0,
    });
    (idx, scale)
}

/// The `face` element: polygons of `vertex_indices` (or `vertex_index`), fan-triangulated,
/// and their colours (Mitsuba's `face_color`).
fn read_faces(el: &Element, body: &mut Body, out: &mut PlyMesh) -> Result<(), String> {
    let (rgb_idx, rgb_scale) = colour_props(el);
    let mut rgb = [0.0f64; 3];
    let indices = &mut out.indices;
    let list = el
        .props
        .iter()
        .position(|p| {
            matches!(p, Prop::List(name, _, _) if name == "vertex_indices" || name == "vertex_index")
        })
        .ok_or("the face element has no vertex_indices list")?;
    let mut poly = Vec::new();
    for _ in 0..el.count {
        for (i, p) in el.props.iter().enumerate() {
            let Prop::List(_, ct, it) = p else {
                let v = read_prop(p, body)?;
                if let Some(k) = rgb_idx.and_then(|c| c.iter().position(|&c| c == i)) {
                    rgb[k] = v * rgb_scale;
                }
                continue;
            };
            if i != list {
                read_prop(p, body)?;
                continue;
            }
            let n = body.read(*ct)? as usize;
            poly.clear();
            for _ in 0..n {
                let v = body.read(*it)?;
                if v < 0.0 || v.fract() != 0.0 || v >= u32::MAX as f64 {
                    return Err(format!("bad vertex index {v}"));
                }
                poly.push(v as u32);
            }
            for k in 1..poly.len().saturating_sub(1) {
                indices.push([poly[0], poly[k], poly[k + 1]]);
            }
        }
        // The polygon's colour (read with its other properties, in any order) for each of
        // its triangles.
        if rgb_idx.is_some() {
            let c = Vec3::from_array(rgb.map(|x| x as f32));
            out.face_colors.resize(indices.len(), c);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &str = "ply
format ascii 1.0
comment a unit square in z = 0 and a stray element
element vertex 4
property float x
property float y
property float z
property float u
element face 1
property list uchar int vertex_indices
element extra 1
property list uchar float stuff
end_header
0 0 0 0
1 0 0 1
1 1 0 1
0 1 0 0
4 0 1 2 3
2 0.5 0.5
";

    #[test]
    fn ascii_quad_is_fan_triangulated() {
        let m = parse_ply(ASCII.as_bytes()).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(m.normals.is_empty());
        assert!(m.uvs.is_empty(), "a lone `u` is not a texture coordinate");
    }

    #[test]
    fn texture_coordinates_and_colours_under_each_name() {
        for (u, v) in [("u", "v"), ("s", "t"), ("texture_u", "texture_v")] {
            let ply = format!(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float {u}\nproperty float {v}\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0 255 0 0\n1 0 0 1 0 0 255 0\n0 1 0 0.25 0.75 0 0 51\n3 0 1 2\n"
            );
            let m = parse_ply(ply.as_bytes()).unwrap();
            assert_eq!(m.uvs[2], Vec2::new(0.25, 0.75), "{u} {v}");
            assert_eq!(m.colors[0], Vec3::X);
            assert!((m.colors[2].z - 0.2).abs() < 1e-6);
        }
    }

    #[test]
    fn binary_little_endian_with_normals() {
        let mut b = b"ply\r\nformat binary_little_endian 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\nelement face 1\r\nproperty uchar flags\r\nproperty list uchar uint vertex_index\r\nend_header\r\n".to_vec();
        for v in [[0.0f32, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]] {
            for x in v.iter().chain(&[0.0, 0.0, 1.0]) {
                b.extend_from_slice(&x.to_le_bytes());
            }
        }
        b.push(7);
        b.push(3);
        for i in [0u32, 1, 2] {
            b.extend_from_slice(&i.to_le_bytes());
        }
        let m = parse_ply(&b).unwrap();
        assert_eq!(m.positions[1], Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(m.normals.len(), 3);
        assert_eq!(m.indices, vec![[0, 1, 2]]);
    }

    #[test]
    fn absurd_element_counts_are_errors_not_aborts() {
        for count in ["18446744073709551615", "4000000000000"] {
            for format in ["ascii", "binary_little_endian"] {
                let ply = ASCII
                    .replace("element vertex 4", &format!("element vertex {count}"))
                    .replace("ascii", format);
                let e = parse_ply(ply.as_bytes()).unwrap_err();
                assert!(e.contains("ends") || e.contains("number"), "{e}");
            }
        }
    }

    #[test]
    fn truncated_and_big_endian_files_are_errors() {
        let cut = &ASCII[..ASCII.len() - 20];
        assert!(parse_ply(cut.as_bytes()).unwrap_err().contains("ends"));
        let be = ASCII.replace("ascii", "binary_big_endian");
        assert!(parse_ply(be.as_bytes()).unwrap_err().contains("big_endian"));
    }
}
