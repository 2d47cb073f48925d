//! A shifted projection (Mitsuba's `principal_point_offset_x`/`_y`): pixel (x, y) looks where
//! pixel (x + shift_x·width, y + shift_y·height) of the centred view does, for a pinhole and a
//! thin lens, and the frustum test moves with it.
use eyeadapt_scene::Projection;
use eyeadapt_tracer::View;
use glam::Vec3;

fn view(projection: Projection) -> View {
    View {
        position: Vec3::new(1.0, 2.0, 3.0),
        forward: Vec3::new(0.0, 0.0, -1.0),
        up: Vec3::Y,
        fov_deg: 40.0,
        width: 32,
        height: 16,
        projection,
    }
}

#[test]
fn a_shifted_view_sees_the_centred_view_moved_by_its_shift() {
    let (sx, sy) = (0.25f32, -0.125f32); // 8 pixels right, 2 up
    for (centred, aperture_radius) in [
        (Projection::Pinhole, 0.0),
        (
            Projection::ThinLens {
                aperture_radius: 0.3,
                focus_distance: 4.0,
            },
            0.3,
        ),
    ] {
        let c = view(centred);
        let s = view(Projection::Shifted {
            shift_x: sx,
            shift_y: sy,
            aperture_radius,
            focus_distance: 4.0,
        });
        let (bc, bs) = (c.basis(), s.basis());
        for (x, y, lens) in [
            (0.5, 0.5, [0.2, 0.7]),
            (10.25, 7.5, [0.9, 0.1]),
            (3.0, 12.0, [0.5, 0.5]),
        ] {
            let (o1, d1) = s.ray(bs, x, y, lens);
            let (o2, d2) = c.ray(bc, x + sx * 32.0, y + sy * 16.0, lens);
            assert!(
                (o1 - o2).length() < 1e-5 && (d1 - d2).length() < 1e-5,
                "{x}, {y}: {d1} vs {d2}"
            );
        }
        // The frustum is the shifted image's: the centred view's right edge is inside.
        let right = c.ray_dir(bc, 31.9, 8.0);
        let left = c.ray_dir(bc, 0.1, 8.0);
        assert!(c.in_frustum(bc, right) && c.in_frustum(bc, left));
        assert!(s.in_frustum(bs, right), "the shift moved the view right");
        assert!(!s.in_frustum(bs, left), "... so the left edge left it");
    }
}
