//! The surface at a ray hit ([`SurfaceInteraction`]) and the per-vertex attributes of a mesh it
//! is interpolated from.
use crate::triangle::normal_and_area;
use eyeadapt_scene::{Mesh, Transform};
use glam::{Vec2, Vec3A};

/// What shading needs to know about a hit, in world space.
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceInteraction {
    pub t: f32,
    pub p: Vec3A,
    /// Unit geometric normal on the triangle's front side.
    pub ng: Vec3A,
    /// Unit shading normal (interpolated vertex normals, else `ng`); not yet turned to the viewer.
    pub ns: Vec3A,
    /// Texture coordinates: the mesh's, else the barycentrics (Mitsuba's convention).
    pub uv: Vec2,
    /// ∂p/∂u: from the UVs, else the edge v1 − v0.
    pub dpdu: Vec3A,
    /// ∂p/∂v: from the UVs, else the edge v2 − v0 (bump maps need both).
    pub dpdv: Vec3A,
    /// Interpolated vertex colour (zero without vertex colours).
    pub color: Vec3A,
    /// The triangle's colour (zero without face colours).
    pub face_color: Vec3A,
    pub instance: u32,
    pub prim: u32,
    /// Index into the tracer's material table.
    pub material: u32,
    /// Index into the light set's area lights, or `u32::MAX` when not emissive.
    pub light: u32,
}

/// Per-vertex attributes of one mesh, in the space of its triangles.
pub struct Attributes {
    indices: Vec<[u32; 3]>,
    normals: Vec<Vec3A>,
    uvs: Vec<Vec2>,
    colors: Vec<Vec3A>,
    face_colors: Vec<Vec3A>,
}

impl Attributes {
    /// The mesh's attributes, with normals carried through `to_world` when given.
    pub fn of(mesh: &Mesh, to_world: Option<&Transform>) -> Attributes {
        // A normal that is not finite or is far from unit length disqualifies its triangles'
        // interpolation (they shade with `ng`): stored as NaN, it turns the interpolated sum
        // into NaN, which `normalize_or_zero` maps to zero, the same fallback as checking the
        // three normals on every hit.
        let mut normals: Vec<Vec3A> = mesh
            .normals
            .iter()
            .map(|&n| Vec3A::from(to_world.map_or(n, |m| m.normal(n))))
            .map(|n| {
                if n.is_finite() && n.length_squared() > 0.5 {
                    n
                } else {
                    Vec3A::NAN
                }
            })
            .collect();
        if !normals.is_empty() && face_normals_only(mesh, to_world, &normals) {
            normals = Vec::new();
        }
        let any = !(normals.is_empty() && mesh.uvs.is_empty() && mesh.colors.is_empty());
        // Face colours need no indices, only one colour per triangle.
        Attributes {
            indices: if any {
                mesh.indices.clone()
            } else {
                Vec::new()
            },
            normals,
            uvs: mesh.uvs.clone(),
            colors: mesh.colors.iter().map(|&c| Vec3A::from(c)).collect(),
            face_colors: if mesh.face_colors.len() == mesh.indices.len() {
                mesh.face_colors.iter().map(|&c| Vec3A::from(c)).collect()
            } else {
                Vec::new()
            },
        }
    }

    /// True when the mesh has vertex normals (its shading normal is interpolated).
    #[inline]
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    pub fn memory_bytes(&self) -> usize {
        self.indices.len() * 12
            + self.normals.len() * 16
            + self.uvs.len() * 8
            + self.colors.len() * 16
            + self.face_colors.len() * 16
    }

    /// The interaction at barycentrics `b` (weights of vertices 1 and 2) of triangle `prim`,
    /// whose vertices are `v` and geometric normal `ng`, all in this mesh's space. Position,
    /// distance and ids are left for the caller.
    #[inline]
    pub fn interpolate(&self, prim: u32, b: Vec2, v: [Vec3A; 3], ng: Vec3A) -> SurfaceInteraction {
        let w = [1.0 - b.x - b.y, b.x, b.y];
        let idx = self.indices.get(prim as usize);
        let ns = match idx {
            Some(t) if !self.normals.is_empty() => {
                // An invalid normal is NaN (`Attributes::of`), so ns is zero then.
                let n = t.map(|k| self.normals[k as usize]);
                let ns = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]).normalize_or_zero();
                if ns != Vec3A::ZERO { ns } else { ng }
            }
            _ => ng,
        };
        let (uv, [dpdu, dpdv]) = match idx {
            Some(t) if !self.uvs.is_empty() => {
                let uv = t.map(|k| self.uvs[k as usize]);
                (uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2], dp_duv(v, uv))
            }
            _ => (b, [v[1] - v[0], v[2] - v[0]]),
        };
        let color = match idx {
            Some(t) if !self.colors.is_empty() => {
                let c = t.map(|k| self.colors[k as usize]);
                c[0] * w[0] + c[1] * w[1] + c[2] * w[2]
            }
            _ => Vec3A::ZERO,
        };
        let face_color = self
            .face_colors
            .get(prim as usize)
            .copied()
            .unwrap_or(Vec3A::ZERO);
        SurfaceInteraction {
            t: 0.0,
            p: Vec3A::ZERO,
            ng,
            ns,
            uv,
            dpdu,
            dpdv,
            color,
            face_color,
            instance: 0,
            prim,
            material: 0,
            light: u32::MAX,
        }
    }
}

/// The least cosine between a vertex normal and its triangle's geometric normal (in the same
/// space, on the same side) at which the two count as one: 0.08°, far below any smoothing a
/// modeller means (degrees) and far above what a file's rounding of a face's own normal leaves.
const FACE_NORMAL_COS: f32 = 1.0 - 1e-6;

/// True when every vertex normal of every triangle with an area is its triangle's geometric
/// normal (within [`FACE_NORMAL_COS`]), as in flat-shaded meshes exported with their face
/// normals: interpolating them would give `ng` back, at the cost of a barycentric solve, three
/// normal loads and a normalisation on the chain from a hit to the next ray. Such a mesh keeps
/// no normals and shades with `ng` (within 0.08° of what interpolating would give).
fn face_normals_only(mesh: &Mesh, to_world: Option<&Transform>, normals: &[Vec3A]) -> bool {
    use rayon::prelude::*;
    let point = |k: u32| {
        let p = mesh.positions[k as usize];
        Vec3A::from(to_world.map_or(p, |m| m.point(p)))
    };
    mesh.indices.par_iter().all(|t| {
        let v = t.map(point);
        let Some((ng, _)) = normal_and_area(v[1] - v[0], v[2] - v[0]) else {
            return true; // no area: never hit
        };
        t.iter().all(|&k| {
            let n = normals[k as usize];
            // NaN (an unusable normal) fails, and keeps the normals.
            n.dot(ng) >= FACE_NORMAL_COS * n.length()
        })
    })
}

/// ∂p/∂u and ∂p/∂v of the triangle `v` with texture coordinates `uv`; a degenerate
/// parameterisation falls back to the edges v1 − v0 and v2 − v0.
fn dp_duv(v: [Vec3A; 3], uv: [Vec2; 3]) -> [Vec3A; 2] {
    let (d02, d12) = (uv[0] - uv[2], uv[1] - uv[2]);
    let det = d02.x * d12.y - d02.y * d12.x;
    if det.abs() < 1e-12 {
        return [v[1] - v[0], v[2] - v[0]];
    }
    let (p02, p12) = (v[0] - v[2], v[1] - v[2]);
    [
        (p02 * d12.y - p12 * d02.y) / det,
        (p12 * d02.x - p02 * d12.x) / det,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shading normals interpolate where all three vertex normals are usable, and fall back
    /// to the geometric normal where one is not finite or far from unit length, whatever its
    /// weight.
    #[test]
    fn unusable_vertex_normals_shade_with_the_geometric_normal() {
        use glam::Vec3;
        let up = Vec3::new(0.0, 0.0, 1.0);
        let tilted = Vec3::new(0.6, 0.0, 0.8);
        let mesh = Mesh {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::ONE,
                Vec3::Z,
                Vec3::NEG_X,
            ],
            indices: vec![[0, 1, 2], [0, 1, 3], [0, 1, 4], [0, 1, 5]],
            normals: vec![
                up,
                tilted,
                up,
                Vec3::new(f32::NAN, 0.0, 1.0),
                Vec3::new(0.0, 0.0, 0.5),
                -tilted,
            ],
            ..Default::default()
        };
        let attr = Attributes::of(&mesh, None);
        let v = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
        let ng = Vec3A::new(0.0, 0.0, 1.0);
        let b = Vec2::new(0.5, 0.0);
        let want = (Vec3A::from(up) * 0.5 + Vec3A::from(tilted) * 0.5).normalize();
        let ns = attr.interpolate(0, b, v, ng).ns;
        assert!((ns - want).length() < 1e-6, "{ns} vs {want}");
        // A NaN normal and a short one (length 0.5), both at weight 0 here.
        for prim in [1, 2] {
            assert_eq!(attr.interpolate(prim, b, v, ng).ns, ng, "triangle {prim}");
        }
        assert_eq!(attr.interpolate(1, Vec2::new(1.0, 0.0), v, ng).ns, ng);
        let tilted_n = Vec3A::from(tilted).normalize();
        let ns = attr.interpolate(3, Vec2::new(1.0, 0.0), v, ng).ns;
        assert!((ns - tilted_n).length() < 1e-6, "{ns} vs {tilted_n}");
    }

    /// A quad whose vertex normals are its face's keeps none (it shades with `ng`); one
    /// vertex normal turned by 1°, or all of them on the other side, keeps them; so does a
    /// mesh with an unusable normal. A triangle without area does not count.
    #[test]
    fn face_normals_are_dropped_and_smoothing_is_kept() {
        use glam::Vec3;
        let quad = |normals: Vec<Vec3>| Mesh {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::ONE.with_z(0.0),
                Vec3::Y,
                Vec3::X * 2.0,
            ],
            // The last triangle has no area.
            indices: vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]],
            normals,
            ..Default::default()
        };
        let up = Vec3::Z;
        let turned = Vec3::new(
            libm::sinf(1f32.to_radians()),
            0.0,
            libm::cosf(1f32.to_radians()),
        );
        // Not unit: normals are normalised only when interpolated.
        let long = up * 1.5;
        assert!(!Attributes::of(&quad(vec![up, up, up, long, -up]), None).has_normals());
        assert!(Attributes::of(&quad(vec![up, up, turned, up, up]), None).has_normals());
        assert!(Attributes::of(&quad(vec![-up; 5]), None).has_normals());
        let nan = Vec3::new(f32::NAN, 0.0, 1.0);
        assert!(Attributes::of(&quad(vec![up, up, up, nan, up]), None).has_normals());
        // In world space: a rotation keeps the match, so the normals go.
        let turn = Transform {
            matrix: glam::Mat4::from_rotation_x(0.7),
        };
        assert!(!Attributes::of(&quad(vec![up; 5]), Some(&turn)).has_normals());
    }

    #[test]
    fn dp_duv_follows_the_uv_parameterisation() {
        // u runs along 2·x, v along z: ∂p/∂u = (0.5, 0, 0).
        let v = [
            Vec3A::ZERO,
            Vec3A::new(1.0, 0.0, 0.0),
            Vec3A::new(0.0, 0.0, 1.0),
        ];
        let uv = [Vec2::ZERO, Vec2::new(2.0, 0.0), Vec2::new(0.0, 1.0)];
        let [du, dv] = dp_duv(v, uv);
        assert!((du - Vec3A::new(0.5, 0.0, 0.0)).length() < 1e-6);
        assert!((dv - Vec3A::new(0.0, 0.0, 1.0)).length() < 1e-6);
        // A collapsed parameterisation falls back to the edges.
        assert_eq!(dp_duv(v, [Vec2::ZERO; 3]), [v[1] - v[0], v[2] - v[0]]);
    }
}
