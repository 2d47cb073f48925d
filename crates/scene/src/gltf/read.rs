//! Opening a `.gltf`/`.glb` file: the document, its buffers, and every problem as a
//! diagnostic naming the file and the JSON pointer of the offending value (`/nodes/3/camera`).
use crate::{Diagnostic, SceneError, Severity};
use std::path::{Path, PathBuf};

/// Largest glTF file (JSON or GLB) read, and largest external buffer: far above any scene a
/// 24 GB machine renders, small enough that a wrong path (a disk image, /dev/zero) fails fast.
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// A parsed and validated glTF document with its binary buffers loaded.
pub struct GltfFile {
    pub path: PathBuf,
    pub document: gltf::Document,
    pub buffers: Vec<gltf::buffer::Data>,
}

/// An error about the value at `pointer` in `file`.
pub fn at(file: &Path, pointer: &str, message: impl std::fmt::Display) -> Diagnostic {
    Diagnostic {
        severity: Severity::Error,
        file: file.to_path_buf(),
        line: 0,
        col: 0,
        message: format!("{pointer}: {message}"),
    }
}

/// An error about the file as a whole.
pub fn whole_file(file: &Path, message: impl Into<String>) -> Diagnostic {
    Diagnostic {
        severity: Severity::Error,
        file: file.to_path_buf(),
        line: 0,
        col: 0,
        message: message.into(),
    }
}

pub fn fail(d: Diagnostic) -> SceneError {
    SceneError {
        diagnostics: vec![d],
    }
}

/// Refuses anything that is not a regular file of sane size before it is read: reading a
/// FIFO would block forever, a device never ends.
pub fn check_regular(path: &Path, what: &str) -> Result<(), String> {
    let len = crate::check_input(path)
        .map_err(|e| format!("cannot read {what} {}: {e}", path.display()))?;
    if len > MAX_FILE_BYTES {
        return Err(format!(
            "{what} {} is {len} bytes, more than the {MAX_FILE_BYTES} this reader accepts",
            path.display()
        ));
    }
    Ok(())
}

/// gltf-json's validation paths (`nodes[3].camera`, `foo["bar"]`) as JSON pointers
/// (`/nodes/3/camera`, `/foo/bar`).
pub fn json_pointer(path: &str) -> String {
    let (path, value) = match path.split_once(" = ") {
        Some((p, v)) => (p, Some(v)),
        None => (path, None),
    };
    let mut out = String::new();
    for part in path.split('.') {
        let mut rest = part;
        let head_end = rest.find('[').unwrap_or(rest.len());
        if head_end > 0 {
            out.push('/');
            out.push_str(&rest[..head_end]);
        }
        rest = &rest[head_end..];
        while let Some(inner) = rest.strip_prefix('[') {
            let close = inner.find(']').unwrap_or(inner.len());
            out.push('/');
            out.push_str(inner[..close].trim_matches('"'));
            rest = inner.get(close + 1..).unwrap_or("");
        }
    }
    if out.is_empty() {
        out.push('/');
    }
    match value {
        Some(v) => format!("{out} (= {v})"),
        None => out,
    }
}

/// Reads, parses and validates `path` and loads its buffers (external `.bin` files relative
/// to it, data URIs, the GLB binary chunk).
pub fn open(path: &Path) -> Result<GltfFile, SceneError> {
    let whole = |m: String| fail(whole_file(path, m));
    check_regular(path, "glTF file").map_err(whole)?;
    let bytes = crate::read_input(path)
        .map_err(|e| whole(format!("cannot read glTF file {}: {e}", path.display())))?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| document_error(path, e))?;
    let base = path.parent().unwrap_or(Path::new("."));
    for buffer in gltf.document.buffers() {
        if let gltf::buffer::Source::Uri(uri) = buffer.source()
            && !uri.starts_with("data:")
        {
            let file = base.join(uri_to_path(uri));
            check_regular(&file, "buffer")
                .map_err(|m| fail(at(path, &format!("/buffers/{}/uri", buffer.index()), m)))?;
        }
    }
    let buffers = gltf::import_buffers(&gltf.document, Some(base), gltf.blob)
        .map_err(|e| document_error(path, e))?;
    Ok(GltfFile {
        path: path.to_path_buf(),
        document: gltf.document,
        buffers,
    })
}

/// A relative URI reference as a file path (percent-decoding what exporters escape).
pub fn uri_to_path(uri: &str) -> PathBuf {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    PathBuf::from(String::from_utf8_lossy(&out).into_owned())
}

fn document_error(path: &Path, e: gltf::Error) -> SceneError {
    use gltf::Error as E;
    let diagnostics = match e {
        E::Validation(problems) => problems
            .iter()
            .map(|(p, kind)| {
                let what = match kind {
                    gltf::json::validation::Error::IndexOutOfBounds => "index out of bounds",
                    gltf::json::validation::Error::Invalid => "invalid value",
                    gltf::json::validation::Error::Missing => "required value missing",
                    gltf::json::validation::Error::Oversize => "size beyond the system's limits",
                    gltf::json::validation::Error::Unsupported => {
                        "required extension not supported by eyeadapt"
                    }
                };
                at(path, &json_pointer(p.as_str()), what)
            })
            .collect(),
        E::Deserialize(j) => vec![Diagnostic {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: j.line(),
            col: j.column(),
            message: format!("not valid glTF JSON: {j}"),
        }],
        E::BufferLength {
            buffer,
            expected,
            actual,
        } => vec![at(
            path,
            &format!("/buffers/{buffer}/byteLength"),
            format!("says {expected} bytes but the data has {actual}"),
        )],
        other => vec![whole_file(path, format!("cannot read glTF file: {other}"))],
    };
    SceneError { diagnostics }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_paths_become_json_pointers() {
        assert_eq!(json_pointer("nodes[3].camera"), "/nodes/3/camera");
        assert_eq!(
            json_pointer("extensionsRequired[0]"),
            "/extensionsRequired/0"
        );
        assert_eq!(
            json_pointer("meshes[0].primitives[1].attributes[\"POSITION\"]"),
            "/meshes/0/primitives/1/attributes/POSITION"
        );
        assert_eq!(
            json_pointer("extensionsRequired[0] = \"KHR_x\""),
            "/extensionsRequired/0 (= \"KHR_x\")"
        );
        assert_eq!(json_pointer(""), "/");
    }

    #[test]
    fn uris_are_percent_decoded() {
        assert_eq!(uri_to_path("a%20b.bin"), PathBuf::from("a b.bin"));
        assert_eq!(uri_to_path("plain.bin"), PathBuf::from("plain.bin"));
        assert_eq!(uri_to_path("bad%2"), PathBuf::from("bad%2"));
    }
}
