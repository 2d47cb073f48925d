//! Tessellated analytic shapes: parallelogram quads, boxes and spheres, and Mitsuba's built-in
//! shapes in their object space with Mitsuba's UV parameterisation (`rectangle`, `cube`,
//! `sphere`, `disk`, `cylinder`).
//!
//! ```toml
//! [[shapes]]
//! type = "quad"                     # parallelogram corner, corner+u, corner+u+v, corner+v
//! corner = [0.0, 0.0, 0.0]          # default [-1, -1, 0]
//! u = [1.0, 0.0, 0.0]               # default [2, 0, 0]
//! v = [0.0, 0.0, 1.0]               # default [0, 2, 0]; the front (emitting) side is u × v
//! material = "white"
//!
//! [[shapes]]
//! type = "box"
//! min = [0.0, 0.0, 0.0]             # default [-1, -1, -1]
//! max = [1.0, 1.0, 1.0]             # default [1, 1, 1]; normals point outwards
//! material = "white"
//!
//! [[shapes]]
//! type = "sphere"
//! center = [0.0, 1.0, 0.0]
//! radius = 0.5
//! subdivisions = 4                  # icosphere level: 20·4^n triangles (default 4)
//! material = "white"
//! flip_normals = false              # true: the front side faces inwards (every shape has it)
//! ```
use crate::Mesh;
use glam::{Vec2, Vec3};
use std::f64::consts::TAU;

/// A parallelogram as two triangles; front side = `u × v`. UV (0, 0) at `corner`, (1, 0) at
/// `corner + u`, (0, 1) at `corner + v` (for Mitsuba's `rectangle`, corner (−1, −1, 0) and
/// u = (2, 0, 0), v = (0, 2, 0): uv = ((x + 1) / 2, (y + 1) / 2), as there).
pub fn quad_mesh(corner: Vec3, u: Vec3, v: Vec3) -> Mesh {
    Mesh {
        positions: vec![corner, corner + u, corner + u + v, corner + v],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        uvs: vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y],
        ..Mesh::default()
    }
}

/// Mitsuba's `cube`: [−1, 1]³, four vertices per face with the face's normal and the UVs
/// (0, 1), (1, 1), (1, 0), (0, 0), faces −y, +y, +x, +z, −x, −z in this order.
pub(crate) fn mitsuba_cube() -> Mesh {
    // Corner c is at (±1, ±1, ±1), bit k of c giving the sign of axis k.
    const CORNERS: [[u8; 4]; 6] = [
        [1, 5, 4, 0],
        [3, 2, 6, 7],
        [1, 3, 7, 5],
        [5, 7, 6, 4],
        [4, 6, 2, 0],
        [3, 1, 0, 2],
    ];
    const NORMALS: [Vec3; 6] = [
        Vec3::NEG_Y,
        Vec3::Y,
        Vec3::X,
        Vec3::Z,
        Vec3::NEG_X,
        Vec3::NEG_Z,
    ];
    let corner = |c: u8| {
        let s = |bit: u8| if c & bit != 0 { 1.0 } else { -1.0 };
        Vec3::new(s(1), s(2), s(4))
    };
    let mut m = Mesh::default();
    for (face, n) in CORNERS.iter().zip(NORMALS) {
        let v = m.positions.len() as u32;
        m.positions.extend(face.map(corner));
        m.normals.extend([n; 4]);
        m.uvs.extend([Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO]);
        m.indices.extend([[v, v + 1, v + 2], [v + 3, v, v + 2]]);
    }
    m
}

/// Segments around Mitsuba's round shapes (sphere, disk, cylinder) and, for the sphere, half
/// as many rings: 256 × 128 quads on the sphere.
pub(crate) const ROUND_SEGMENTS: usize = 256;

/// Mitsuba's `sphere` as a latitude–longitude mesh of the unit sphere: uv = (φ / 2π, θ / π)
/// with θ the angle from +z and φ = atan2(y, x) in [0, 2π) (exact at the vertices; the seam
/// and the poles have their own vertices). Smooth normals; the vertices sit slightly outside
/// the sphere so that the mesh's area is exactly 4π.
pub(crate) fn uv_sphere(segments: usize) -> Mesh {
    let rings = segments / 2;
    let mut m = Mesh::default();
    for i in 0..=rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..=segments {
            // The poles get one vertex per segment, at the segment's middle azimuth.
            let u = if i == 0 || i == rings {
                (j as f64 + 0.5) / segments as f64
            } else {
                j as f64 / segments as f64
            };
            let phi = TAU * u;
            let d = glam::DVec3::new(
                libm::sin(theta) * libm::cos(phi),
                libm::sin(theta) * libm::sin(phi),
                libm::cos(theta),
            );
            m.positions.push(d.as_vec3());
            m.normals.push(d.as_vec3());
            m.uvs
                .push(Vec2::new(u as f32, (i as f64 / rings as f64) as f32));
        }
    }
    let row = segments as u32 + 1;
    for i in 0..rings as u32 {
        for j in 0..segments as u32 {
            let (a, b) = (i * row + j, i * row + j + 1);
            let (c, d) = (a + row, b + row);
            if i > 0 {
                m.indices.push([a, c, b]);
            }
            if i + 1 < rings as u32 {
                m.indices.push([b, c, d]);
            }
        }
    }
    scale_to_area(&mut m, 4.0 * std::f64::consts::PI);
    m
}

/// Mitsuba's `disk`: the unit disk in z = 0, front +z, uv = (r, φ / 2π) (the centre has one
/// vertex per segment). The rim sits slightly outside radius 1 so that the area is exactly π.
pub(crate) fn disk(segments: usize) -> Mesh {
    let mut m = Mesh::default();
    for j in 0..=segments {
        let u = j as f64 / segments as f64;
        let (s, c) = libm::sincos(TAU * u);
        m.positions.push(Vec3::new(c as f32, s as f32, 0.0));
        m.uvs.push(Vec2::new(1.0, u as f32));
        m.positions.push(Vec3::ZERO);
        m.uvs
            .push(Vec2::new(0.0, ((j as f64 + 0.5) / segments as f64) as f32));
    }
    for j in 0..segments as u32 {
        m.indices.push([2 * j + 1, 2 * j, 2 * j + 2]);
    }
    scale_to_area(&mut m, std::f64::consts::PI);
    m
}

/// Mitsuba's `cylinder` before its placement: the open unit cylinder around z from z = 0 to
/// z = 1, normals outwards, uv = (φ / 2π, z). The radius is slightly above 1 so that the area
/// is exactly 2π.
pub(crate) fn cylinder(segments: usize) -> Mesh {
    let mut m = Mesh::default();
    for j in 0..=segments {
        let u = j as f64 / segments as f64;
        let (s, c) = libm::sincos(TAU * u);
        let n = Vec3::new(c as f32, s as f32, 0.0);
        for z in [0.0, 1.0] {
            m.positions.push(n + Vec3::Z * z);
            m.normals.push(n);
            m.uvs.push(Vec2::new(u as f32, z));
        }
    }
    for j in 0..segments as u32 {
        let (a, b, c, d) = (2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3);
        m.indices.extend([[a, c, d], [a, d, b]]);
    }
    let target = TAU;
    let k = target / m.area();
    // Only the radius changes: scale x and y by the area ratio.
    for p in &mut m.positions {
        p.x *= k as f32;
        p.y *= k as f32;
    }
    m
}

/// Scales positions about the origin so that the mesh's area is `area`.
fn scale_to_area(m: &mut Mesh, area: f64) {
    let k = (area / m.area()).sqrt() as f32;
    for p in &mut m.positions {
        *p *= k;
    }
}

/// An axis-aligned box with outward-facing triangles.
pub fn box_mesh(min: Vec3, max: Vec3) -> Mesh {
    let mut mesh = Mesh::default();
    let d = max - min;
    // Each face: corner, u, v with u × v pointing outwards.
    let faces = [
        (min, Vec3::new(0.0, d.y, 0.0), Vec3::new(d.x, 0.0, 0.0)), // -z
        (
            Vec3::new(min.x, min.y, max.z),
            Vec3::new(d.x, 0.0, 0.0),
            Vec3::new(0.0, d.y, 0.0),
        ), // +z
        (min, Vec3::new(0.0, 0.0, d.z), Vec3::new(0.0, d.y, 0.0)), // -x
        (
            Vec3::new(max.x, min.y, min.z),
            Vec3::new(0.0, d.y, 0.0),
            Vec3::new(0.0, 0.0, d.z),
        ), // +x
        (min, Vec3::new(d.x, 0.0, 0.0), Vec3::new(0.0, 0.0, d.z)), // -y
        (
            Vec3::new(min.x, max.y, min.z),
            Vec3::new(0.0, 0.0, d.z),
            Vec3::new(d.x, 0.0, 0.0),
        ), // +y
    ];
    for (c, u, v) in faces {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend([c, c + u, c + u + v, c + v]);
        mesh.indices
            .extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }
    mesh
}

/// An icosphere with `20·4^subdivisions` outward-facing triangles and smooth normals.
///
/// The vertices lie exactly on the sphere, so the tessellated surface is slightly inside it;
/// at the default level 4 (5120 triangles) the area is 0.3 % below 4πr².
pub fn sphere_mesh(center: Vec3, radius: f32, subdivisions: u32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut verts: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|v| Vec3::from_array(*v).normalize())
    .collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions.min(8) {
        let mut midpoint = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(faces.len() * 4);
        let mut mid = |a: u32, b: u32, verts: &mut Vec<Vec3>| -> u32 {
            let key = (a.min(b), a.max(b));
            *midpoint.entry(key).or_insert_with(|| {
                verts.push(((verts[a as usize] + verts[b as usize]) * 0.5).normalize());
                verts.len() as u32 - 1
            })
        };
        for [a, b, c] in faces {
            let ab = mid(a, b, &mut verts);
            let bc = mid(b, c, &mut verts);
            let ca = mid(c, a, &mut verts);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    Mesh {
        positions: verts.iter().map(|v| center + *v * radius).collect(),
        normals: verts.clone(),
        indices: faces,
        ..Mesh::default()
    }
}

/// Reverse the winding (and shading normals) so the front side faces the other way.
pub(crate) fn flip(mesh: &mut Mesh) {
    for t in &mut mesh.indices {
        t.swap(1, 2);
    }
    for n in &mut mesh.normals {
        *n = -*n;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outward(mesh: &Mesh, center: Vec3) -> bool {
        mesh.indices.iter().all(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a);
            n.dot((a + b + c) / 3.0 - center) > 0.0
        })
    }

    #[test]
    fn box_faces_point_outwards_and_area_is_right() {
        let m = box_mesh(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
        assert!(outward(&m, Vec3::new(0.5, 1.0, 1.5)));
        assert!((m.area() - 2.0 * (2.0 + 3.0 + 6.0)).abs() < 1e-5);
    }

    #[test]
    fn sphere_is_outward_and_close_to_analytic_area() {
        let m = sphere_mesh(Vec3::new(1.0, 2.0, 3.0), 2.0, 4);
        assert_eq!(m.triangle_count(), 20 * 256);
        assert!(outward(&m, Vec3::new(1.0, 2.0, 3.0)));
        let exact = 4.0 * std::f64::consts::PI * 4.0;
        assert!(
            (m.area() / exact - 1.0).abs() < 0.005,
            "{}",
            m.area() / exact
        );
    }

    #[test]
    fn flip_reverses_orientation() {
        let mut m = sphere_mesh(Vec3::ZERO, 1.0, 1);
        flip(&mut m);
        assert!(!outward(&m, Vec3::ZERO));
    }

    fn uv_at(m: &Mesh, p: Vec3) -> Vec2 {
        let i = (0..m.positions.len())
            .min_by(|&a, &b| {
                m.positions[a]
                    .distance(p)
                    .total_cmp(&m.positions[b].distance(p))
            })
            .unwrap();
        m.uvs[i]
    }

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn rectangle_uv_is_mitsubas() {
        let m = quad_mesh(Vec3::new(-1.0, -1.0, 0.0), 2.0 * Vec3::X, 2.0 * Vec3::Y);
        // uv = ((x + 1) / 2, (y + 1) / 2)
        assert!(close(uv_at(&m, Vec3::new(-1.0, -1.0, 0.0)), Vec2::ZERO));
        assert!(close(uv_at(&m, Vec3::new(1.0, -1.0, 0.0)), Vec2::X));
        assert!(close(uv_at(&m, Vec3::new(-1.0, 1.0, 0.0)), Vec2::Y));
    }

    #[test]
    fn cube_uvs_normals_and_winding_are_mitsubas() {
        let m = mitsuba_cube();
        assert_eq!((m.positions.len(), m.triangle_count()), (24, 12));
        assert!(outward(&m, Vec3::ZERO));
        assert!((m.area() - 24.0).abs() < 1e-5);
        // The −y face: corners 1, 5, 4, 0 carry uv (0, 1), (1, 1), (1, 0), (0, 0).
        assert_eq!(m.positions[0], Vec3::new(1.0, -1.0, -1.0));
        assert_eq!(m.positions[1], Vec3::new(1.0, -1.0, 1.0));
        assert_eq!(m.uvs[..4], [Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO]);
        assert_eq!(m.normals[0], Vec3::NEG_Y);
        // Face +z (the fourth): corner 5 = (1, -1, 1) has uv (0, 1).
        assert_eq!(m.positions[12], Vec3::new(1.0, -1.0, 1.0));
        assert_eq!(m.uvs[12], Vec2::Y);
    }

    #[test]
    fn sphere_uv_is_phi_over_two_pi_and_theta_over_pi_with_exact_area() {
        let m = uv_sphere(64);
        assert!(outward(&m, Vec3::ZERO));
        assert!((m.area() / (4.0 * std::f64::consts::PI) - 1.0).abs() < 1e-6);
        // +x: φ = 0, θ = π/2; +y: φ = π/2; −x: φ = π; the north pole (+z) has v = 0.
        let r = m.positions[1].length();
        assert!(
            close(uv_at(&m, Vec3::new(r, 0.0, 0.0)), Vec2::new(0.0, 0.5))
                || close(uv_at(&m, Vec3::new(r, 0.0, 0.0)), Vec2::new(1.0, 0.5))
        );
        assert!(close(
            uv_at(&m, Vec3::new(0.0, r, 0.0)),
            Vec2::new(0.25, 0.5)
        ));
        assert!(close(
            uv_at(&m, Vec3::new(-r, 0.0, 0.0)),
            Vec2::new(0.5, 0.5)
        ));
        assert!(close(
            uv_at(&m, Vec3::new(0.0, -r, 0.0)),
            Vec2::new(0.75, 0.5)
        ));
        assert!(uv_at(&m, Vec3::new(0.0, 0.0, r)).y == 0.0);
        assert!(uv_at(&m, Vec3::new(0.0, 0.0, -r)).y == 1.0);
        // Shading normals point away from the centre.
        assert!(
            m.positions
                .iter()
                .zip(&m.normals)
                .all(|(p, n)| p.normalize().dot(*n) > 0.9999)
        );
    }

    #[test]
    fn disk_uv_is_radius_and_azimuth_with_exact_area() {
        let m = disk(64);
        assert!((m.area() / std::f64::consts::PI - 1.0).abs() < 1e-6);
        let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0, "front is +z");
        let r = m.positions[0].length();
        assert!(close(
            uv_at(&m, Vec3::new(0.0, r, 0.0)),
            Vec2::new(1.0, 0.25)
        ));
        assert!(close(
            uv_at(&m, Vec3::new(-r, 0.0, 0.0)),
            Vec2::new(1.0, 0.5)
        ));
        assert!(uv_at(&m, Vec3::ZERO).x == 0.0);
    }

    #[test]
    fn cylinder_uv_is_azimuth_and_height_with_exact_area() {
        let m = cylinder(64);
        assert!((m.area() / TAU - 1.0).abs() < 1e-6);
        assert!(
            outward(&m, Vec3::new(0.0, 0.0, 0.5))
                || m.indices.iter().all(|t| {
                    let [a, b, c] = t.map(|i| m.positions[i as usize]);
                    let n = (b - a).cross(c - a);
                    n.dot(Vec3::new(a.x + b.x + c.x, a.y + b.y + c.y, 0.0)) > 0.0
                })
        );
        let r = m.positions[0].x;
        assert!(close(
            uv_at(&m, Vec3::new(0.0, r, 1.0)),
            Vec2::new(0.25, 1.0)
        ));
        assert!(close(
            uv_at(&m, Vec3::new(-r, 0.0, 0.0)),
            Vec2::new(0.5, 0.0)
        ));
    }

    #[test]
    fn quad_front_is_u_cross_v() {
        let m = quad_mesh(Vec3::ZERO, Vec3::X, Vec3::Y);
        let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).dot(Vec3::Z) > 0.0);
    }
}
