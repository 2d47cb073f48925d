//! Textures: the table [`crate::Scene::textures`] that material parameters point into.
//!
//! Bitmaps are decoded when the scene loads, so a scene is plain data: [`Image`] holds linear
//! RGB texels (8-bit sRGB files already converted unless `raw`), and the tracer only filters.
use crate::Rgb;
use glam::Affine2;
use std::path::PathBuf;
use std::sync::Arc;

/// Index into [`crate::Scene::textures`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TextureId(pub u32);

/// A spatially varying colour (or, read as its luminance, a number such as a roughness).
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    Bitmap(Bitmap),
    /// Mitsuba's `checkerboard`: `color0` where ⌊2u⌋ + ⌊2v⌋ is even (of the transformed UV's
    /// fractional part), `color1` elsewhere.
    Checkerboard {
        color0: Rgb,
        color1: Rgb,
        to_uv: Affine2,
    },
    /// An attribute of the mesh (Mitsuba's `mesh_attribute`): `vertex_color`
    /// ([`crate::Mesh::colors`], interpolated over the triangle) or `face_color`
    /// ([`crate::Mesh::face_colors`], one per triangle).
    MeshAttribute {
        name: String,
    },
    /// The same value everywhere, without colour conversion (Mitsuba's `rawconstant`).
    Constant {
        value: Rgb,
    },
}

/// An image texture and how it is looked up.
#[derive(Clone, Debug, PartialEq)]
pub struct Bitmap {
    /// The file it was decoded from (messages, fingerprints of what the user named).
    pub filename: PathBuf,
    /// Decoded texels; shared by every texture that names the same file and `raw` flag.
    pub image: Arc<Image>,
    /// True: the file's values are used as they are (no sRGB decoding).
    pub raw: bool,
    pub filter: FilterType,
    pub wrap: WrapMode,
    /// Applied to the mesh's UV before the lookup (Mitsuba's `to_uv`).
    pub to_uv: Affine2,
}

/// Decoded texels, linear, row-major from the **top** row of the file (UV v = 0 is row 0).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Rgb>,
}

/// Mitsuba's `filter_type`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FilterType {
    Nearest,
    #[default]
    Bilinear,
}

/// Mitsuba's `wrap_mode`: what a UV outside [0, 1] reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum WrapMode {
    #[default]
    Repeat,
    Mirror,
    Clamp,
}
