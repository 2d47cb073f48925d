//! Shadow rays through surfaces that let light straight through (`shadow.rs`): a floor lit
//! from above through a cover at half the light's height, seen from a camera between the cover
//! and the floor (so camera rays never meet the cover). With a point light every pixel's light
//! sample is the same whatever covers it, so the ratio of two renders is the cover's
//! transmittance exactly: a mask of opacity 0.3 passes 0.7, a null surface 1, a textured mask
//! its texels' 1 − opacity, a blend its weight of its pane's. With an area light the covered
//! floor must be 0.7 times the open one whether shadow rays pass the mask or stop there (as in
//! Mitsuba's `path`), and also at the depth limit, where only a crossing continues the path.
mod common;

use common::settings;
use eyeadapt_scene::{
    Bitmap, Bsdf, CutoutShadows, FilterType, Image, Light, Material, Param, Rgb, Scene, Texture,
    Transform, WrapMode, quad_mesh,
};
use eyeadapt_tracer::{EyeSettings, Frame, PathSettings, SceneData, View, eye_sensor, render};
use glam::{Affine2, Mat4, Vec3};
use std::sync::Arc;

const OPEN: Option<Bsdf> = None;

fn black() -> Bsdf {
    Bsdf::Diffuse {
        reflectance: Param::Const(Rgb::ZERO),
    }
}

fn mask(opacity: Param<f32>) -> Bsdf {
    Bsdf::Mask {
        opacity,
        bsdf: Box::new(black()),
    }
}

fn pane() -> Bsdf {
    Bsdf::ThinDielectric {
        eta: 1.5,
        specular_reflectance: Rgb::ONE,
        specular_transmittance: Rgb::ONE,
    }
}

#[derive(Clone, Copy)]
enum Lamp {
    Point,
    Area,
}

/// A grey floor at z = 0, `cover` (if any) over all of it at z = 1, `lamp` at z = 2.
fn scene(cover: Option<Bsdf>, lamp: Lamp, shadows: CutoutShadows) -> Scene {
    let mut s = Scene {
        cutout_shadows: shadows,
        ..Scene::default()
    };
    let floor = s.add_material(Material::diffuse("floor", Rgb::splat(0.5)));
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-3.0, -3.0, 0.0),
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(0.0, 6.0, 0.0),
        ),
        Some(floor),
    );
    if let Some(bsdf) = cover {
        let m = s.add_material(Material {
            name: "cover".into(),
            bsdf,
            emission: Rgb::ZERO,
        });
        // u runs along +x: a 2-texel texture splits the cover at x = 0.
        s.add_world_mesh(
            quad_mesh(
                Vec3::new(-4.0, -4.0, 1.0),
                Vec3::new(8.0, 0.0, 0.0),
                Vec3::new(0.0, 8.0, 0.0),
            ),
            Some(m),
        );
    }
    match lamp {
        Lamp::Point => s.lights.push(Light::Point {
            position: Vec3::new(0.0, 0.0, 2.0),
            intensity: Rgb::splat(10.0),
        }),
        Lamp::Area => {
            let m = s.add_material(Material {
                name: "lamp".into(),
                bsdf: black(),
                emission: Rgb::splat(5.0),
            });
            // Facing down (−z).
            s.add_world_mesh(
                quad_mesh(
                    Vec3::new(-0.5, -0.5, 2.0),
                    Vec3::new(0.0, 1.0, 0.0),
                    Vec3::new(1.0, 0.0, 0.0),
                ),
                Some(m),
            );
        }
    }
    s
}

/// The floor from (0, 0, 0.5), looking straight down, 16 × 16 px (x = 0 between columns 7
/// and 8).
fn shoot(s: &Scene, spp: u32, max_depth: i32) -> Frame {
    let view = View {
        position: Vec3::new(0.0, 0.0, 0.5),
        forward: -Vec3::Z,
        up: Vec3::Y,
        fov_deg: 90.0,
        width: 16,
        height: 16,
        projection: Default::default(),
    };
    render(&SceneData::new(s), &view, &settings(spp, 11, max_depth))
}

/// Per pixel, the red channel of `a` over that of `b` (both lit everywhere).
fn ratios(a: &Frame, b: &Frame) -> Vec<f32> {
    a.rgb
        .iter()
        .zip(&b.rgb)
        .map(|(x, y)| {
            assert!(y[0] > 0.0, "the open floor is lit everywhere");
            x[0] / y[0]
        })
        .collect()
}

fn mean(f: &Frame) -> f32 {
    f.rgb.iter().map(|p| p[0]).sum::<f32>() / f.rgb.len() as f32
}

fn assert_all(r: &[f32], expect: f32, what: &str) {
    let worst = r.iter().map(|x| (x - expect).abs()).fold(0.0, f32::max);
    assert!(worst < 1e-5, "{what}: ratios {r:?}, expected {expect}");
}

#[test]
fn a_mask_of_opacity_0_3_passes_0_7_of_a_point_light() {
    let open = shoot(&scene(OPEN, Lamp::Point, CutoutShadows::Transmit), 4, 2);
    let covered = |shadows| {
        shoot(
            &scene(Some(mask(Param::Const(0.3))), Lamp::Point, shadows),
            4,
            2,
        )
    };
    assert_all(
        &ratios(&covered(CutoutShadows::Transmit), &open),
        0.7,
        "mask 0.3",
    );
    // Mitsuba's `path`: shadow rays stop at the mask, and nothing else reaches a point light.
    assert_eq!(mean(&covered(CutoutShadows::Block)), 0.0);
}

#[test]
fn a_null_surface_is_invisible_to_shadow_rays() {
    let open = shoot(&scene(OPEN, Lamp::Point, CutoutShadows::Transmit), 4, 2);
    let null = |shadows| shoot(&scene(Some(Bsdf::Null), Lamp::Point, shadows), 4, 2);
    assert_eq!(null(CutoutShadows::Transmit).rgb, open.rgb);
    assert_eq!(mean(&null(CutoutShadows::Block)), 0.0);
}

#[test]
fn a_textured_mask_passes_light_where_its_texels_are_open() {
    // Opacity 0.2 for x < 0 and 0.6 for x > 0 (a raw 2 × 1 bitmap, nearest texel). The shadow
    // ray from floor point (x, y) crosses the cover at (x/2, y/2): on the same side.
    let mut s = scene(None, Lamp::Point, CutoutShadows::Transmit);
    let open = shoot(&s, 4, 2);
    let t = s.add_texture(Texture::Bitmap(Bitmap {
        filename: "opacity".into(),
        image: Arc::new(Image {
            width: 2,
            height: 1,
            texels: vec![Rgb::splat(0.2), Rgb::splat(0.6)],
        }),
        raw: true,
        filter: FilterType::Nearest,
        wrap: WrapMode::Clamp,
        to_uv: Affine2::IDENTITY,
    }));
    let m = s.add_material(Material {
        name: "leaf".into(),
        bsdf: mask(Param::Texture(t)),
        emission: Rgb::ZERO,
    });
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-4.0, -4.0, 1.0),
            Vec3::new(8.0, 0.0, 0.0),
            Vec3::new(0.0, 8.0, 0.0),
        ),
        Some(m),
    );
    let r = ratios(&shoot(&s, 4, 2), &open);
    let side = |left: bool| -> Vec<f32> {
        (0..r.len())
            .filter(|i| (i % 16 < 8) == left)
            .map(|i| r[i])
            .collect()
    };
    assert_all(&side(true), 0.8, "x < 0 (opacity 0.2)");
    assert_all(&side(false), 0.4, "x > 0 (opacity 0.6)");
}

#[test]
fn a_blended_pane_passes_its_weight_of_the_pane() {
    // Blend weight 0.3 chooses the pane (child 1) with probability 0.3, a black diffuse
    // otherwise: shadow rays carry 0.3 of the pane's transmittance, in every pixel.
    let blend = Bsdf::Blend {
        weight: Param::Const(0.3),
        bsdfs: Box::new([black(), pane()]),
    };
    let open = shoot(&scene(OPEN, Lamp::Point, CutoutShadows::Transmit), 4, 2);
    let through_pane = shoot(
        &scene(Some(pane()), Lamp::Point, CutoutShadows::Block),
        4,
        2,
    );
    let through_blend = shoot(&scene(Some(blend), Lamp::Point, CutoutShadows::Block), 4, 2);
    let t = ratios(&through_pane, &open);
    assert!(t.iter().all(|&x| x > 0.8 && x < 0.93), "pane {t:?}");
    assert_all(&ratios(&through_blend, &through_pane), 0.3, "blend / pane");
}

#[test]
fn area_light_through_a_cover_is_the_same_whether_shadow_rays_pass_or_stop() {
    let spp = 256;
    let open = mean(&shoot(
        &scene(OPEN, Lamp::Area, CutoutShadows::Transmit),
        spp,
        2,
    ));
    let check = |cover: Bsdf, shadows, max_depth, expect: f32, what: &str| {
        let m = mean(&shoot(
            &scene(Some(cover), Lamp::Area, shadows),
            spp,
            max_depth,
        ));
        eprintln!("{what}: {:.4} (expected {expect:.4})", m / open);
        assert!(
            (m / open - expect).abs() < 0.015,
            "{what}: {m} / {open} = {}, expected {expect}",
            m / open
        );
    };
    let mask = || mask(Param::Const(0.3));
    // Light sampling through the holes plus BSDF sampling, MIS-weighted; at max_depth 2 the
    // BSDF-sampled half still reaches the lamp (a crossing is no segment).
    check(mask(), CutoutShadows::Transmit, 2, 0.7, "passed, depth 2");
    check(mask(), CutoutShadows::Transmit, 8, 0.7, "passed, depth 8");
    // BSDF sampling alone (Mitsuba's `path`); the crossing counts, so it needs depth 3.
    check(mask(), CutoutShadows::Block, 3, 0.7, "stopped, depth 3");
    // A pane at depth 2, and its blend (MIS through a blend's pane child).
    let t = 1.0 - 2.0 * 0.04 / 1.04; // at normal incidence; the lamp is small and high
    check(pane(), CutoutShadows::Block, 2, t, "pane, depth 2");
    let blend = Bsdf::Blend {
        weight: Param::Const(0.3),
        bsdfs: Box::new([black(), pane()]),
    };
    check(
        blend,
        CutoutShadows::Block,
        2,
        0.3 * t,
        "blended pane, depth 2",
    );
}

#[test]
fn the_eye_sees_a_point_light_through_a_mask() {
    // The eye near the floor's centre looking up at the lamp through the cover (not along
    // the cover's diagonal, where the triangle test may miss); nothing else reflects, so its
    // reading is the lamp's direct term alone, times what the cover passes.
    let view = View {
        position: Vec3::new(0.3, -0.2, 0.1),
        forward: Vec3::Z,
        up: Vec3::Y,
        fov_deg: 60.0,
        width: 8,
        height: 8,
        projection: Default::default(),
    };
    let reading = |cover: Option<Bsdf>| {
        let mut s = scene(cover, Lamp::Point, CutoutShadows::Transmit);
        s.materials[0] = Material::diffuse("floor", Rgb::ZERO);
        let settings = EyeSettings {
            samples: 1024,
            min_samples: 1024,
            ..Default::default()
        };
        let path = PathSettings {
            max_depth: 5,
            rr_depth: 5,
        };
        eye_sensor(&SceneData::new(&s), &view, &settings, 0, path).mean_rgb
    };
    let open = reading(None);
    let r = reading(Some(mask(Param::Const(0.3)))) / open;
    assert!(open.x > 0.0 && (r - 0.7).abs().max_element() < 1e-5, "{r}");
    let r = reading(Some(Bsdf::Null)) / open;
    assert!((r - 1.0).abs().max_element() < 1e-5, "{r}");
}

#[test]
fn cut_out_shadows_are_the_same_bits_on_any_thread_count() {
    let s = scene(
        Some(Bsdf::Blend {
            weight: Param::Const(0.5),
            bsdfs: Box::new([mask(Param::Const(0.4)), pane()]),
        }),
        Lamp::Area,
        CutoutShadows::Transmit,
    );
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| shoot(&s, 16, 8))
    };
    let one = on(1);
    assert!(mean(&one) > 0.0);
    assert_eq!(one.rgb, on(3).rgb);
}

/// A see-through material that no shape wears does not make the scene see-through: its
/// shadow rays stay the any-hit test (and pair with the path's next ray), and the image is
/// that of the scene without the material, bit for bit. Placed on the cover, it is.
#[test]
fn unplaced_pane_leaves_shadow_rays_opaque() {
    let open = scene(OPEN, Lamp::Area, CutoutShadows::Transmit);
    let mut unplaced = open.clone();
    unplaced.add_material(Material {
        name: "unused pane".into(),
        bsdf: pane(),
        emission: Rgb::ZERO,
    });
    assert!(!SceneData::new(&open).see_through);
    assert!(!SceneData::new(&unplaced).see_through);
    assert!(SceneData::new(&scene(Some(pane()), Lamp::Area, CutoutShadows::Transmit)).see_through);
    let (a, b) = (shoot(&open, 4, 4), shoot(&unplaced, 4, 4));
    assert!(mean(&a) > 0.0);
    assert_eq!(a.rgb, b.rgb);
}

/// `s` with one more cover over the whole floor at height `z`.
fn with_sheet(mut s: Scene, bsdf: Bsdf, z: f32) -> Scene {
    let m = s.add_material(Material {
        name: format!("sheet at {z}"),
        bsdf,
        emission: Rgb::ZERO,
    });
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-4.0, -4.0, z),
            Vec3::new(8.0, 0.0, 0.0),
            Vec3::new(0.0, 8.0, 0.0),
        ),
        Some(m),
    );
    s
}

/// Shadow rays cross every see-through surface on their segment once, whatever the order
/// the structure meets them in: two masks pass the product of their shares, and an opaque
/// sheet 0.1 mm behind a mask (nearer than any offset past a crossing) blocks the light.
#[test]
fn stacked_covers_multiply_and_an_opaque_sheet_just_behind_a_mask_blocks() {
    let open = shoot(&scene(OPEN, Lamp::Point, CutoutShadows::Transmit), 4, 2);
    let one = scene(
        Some(mask(Param::Const(0.3))),
        Lamp::Point,
        CutoutShadows::Transmit,
    );
    let two = with_sheet(one.clone(), mask(Param::Const(0.5)), 1.5);
    assert_all(
        &ratios(&shoot(&two, 4, 2), &open),
        0.35,
        "masks 0.3 and 0.5",
    );
    let three = with_sheet(two, pane(), 1.25);
    let behind = with_sheet(one, black(), 1.0001);
    assert_eq!(
        mean(&shoot(&behind, 4, 2)),
        0.0,
        "opaque sheet behind a mask"
    );
    // A pane between the masks: its Fresnel transmittance at each pixel's angle, below 1.
    let r = ratios(&shoot(&three, 4, 2), &open);
    assert!(r.iter().all(|&x| x > 0.25 && x < 0.35), "{r:?}");
    // The two masks as one mesh placed twice (two levels): the same product.
    let mut placed = scene(OPEN, Lamp::Point, CutoutShadows::Transmit);
    let sheet = placed.add_mesh(quad_mesh(
        Vec3::new(-4.0, -4.0, 0.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 8.0, 0.0),
    ));
    for (opacity, z) in [(0.3, 1.0), (0.5, 1.5)] {
        let m = placed.add_material(Material {
            name: format!("mask {opacity}"),
            bsdf: mask(Param::Const(opacity)),
            emission: Rgb::ZERO,
        });
        let to_world = Transform {
            matrix: Mat4::from_translation(Vec3::Z * z),
        };
        placed.add_instance(sheet, Some(m), to_world);
    }
    assert!(SceneData::new(&placed).geometry.is_two_level());
    assert_all(&ratios(&shoot(&placed, 4, 2), &open), 0.35, "placed masks");
}
