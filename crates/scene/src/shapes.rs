//! Tessellated analytic shapes: parallelogram quads, boxes and spheres.
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

/// A parallelogram as two triangles; front side = `u × v`. UV (0, 0) at `corner`, (1, 0) at
/// `corner + u`, (0, 1) at `corner + v` (Mitsuba's `rectangle` parameterisation).
pub fn quad_mesh(corner: Vec3, u: Vec3, v: Vec3) -> Mesh {
    Mesh {
        positions: vec![corner, corner + u, corner + u + v, corner + v],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        uvs: vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y],
        ..Mesh::default()
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

    #[test]
    fn quad_front_is_u_cross_v() {
        let m = quad_mesh(Vec3::ZERO, Vec3::X, Vec3::Y);
        let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).dot(Vec3::Z) > 0.0);
    }
}
