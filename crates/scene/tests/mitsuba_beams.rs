//! Mitsuba 3 XML: the emitters and textures of Mitsuba's common plugins that part 2 adds:
//! `projector`, a `spot` with a `texture`, a textured area `radiance`, `rawconstant`, PLY face
//! colours (`mesh_attribute` `face_color`), and their errors.
use eyeadapt_scene::{Light, Param, Scene, SceneError, Texture, load_mitsuba_str};
use glam::{Mat3, Vec3};
use std::path::{Path, PathBuf};

/// A folder with a 4 × 2 PNG, `img.png` (and whatever the test writes next to it).
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eyeadapt-beams-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let img = image::RgbImage::from_fn(4, 2, |x, _| image::Rgb([(x * 60) as u8, 128, 255]));
    img.save(dir.join("img.png")).unwrap();
    dir
}

fn load_in(dir: &Path, body: &str) -> Result<Scene, SceneError> {
    let text =
        format!("<scene version=\"3.0.0\">\n<shape type=\"rectangle\"/>\n{body}\n</scene>\n");
    load_mitsuba_str(&text, &dir.join("test.xml"), &[])
}

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-5 * b.abs().max(1.0)
}

#[test]
fn a_projector_takes_its_aspect_from_its_image_and_its_fov_along_x() {
    let dir = folder("projector");
    let look = "<transform name=\"to_world\"><lookat origin=\"0, 0, 2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>";
    let s = load_in(
        &dir,
        &format!("<emitter type=\"projector\"><float name=\"fov\" value=\"60\"/><float name=\"scale\" value=\"3\"/>{look}<texture type=\"bitmap\" name=\"irradiance\"><string name=\"filename\" value=\"img.png\"/></texture></emitter>"),
    )
    .unwrap();
    let Light::Projector {
        position,
        frame,
        irradiance,
        scale,
        tan_half_fov_x,
        aspect,
    } = &s.lights[0]
    else {
        panic!("{:?}", s.lights);
    };
    assert_eq!(*position, Vec3::new(0.0, 0.0, 2.0));
    assert!((frame.z_axis - Vec3::NEG_Z).length() < 1e-6, "{frame:?}");
    assert!(matches!(irradiance, Param::Texture(_)));
    assert_eq!(*scale, 3.0);
    assert_eq!(*aspect, 2.0, "the image is 4 × 2");
    assert!(
        close(*tan_half_fov_x, libm::tanf(30f32.to_radians())),
        "{tan_half_fov_x}"
    );
    // A constant irradiance is a 1 × 1 image; without fov, Mitsuba's 50 mm lens on the
    // diagonal of a square.
    let s = load_in(
        &dir,
        "<emitter type=\"projector\"><rgb name=\"irradiance\" value=\"1, 2, 3\"/></emitter>",
    )
    .unwrap();
    let Light::Projector {
        irradiance,
        tan_half_fov_x,
        aspect,
        frame,
        ..
    } = &s.lights[0]
    else {
        panic!()
    };
    assert_eq!(*irradiance, Param::Const(Vec3::new(1.0, 2.0, 3.0)));
    assert_eq!(*aspect, 1.0);
    assert_eq!(*frame, Mat3::IDENTITY);
    let diagonal_half = (libm::hypotf(36f32, 24.0) / 100.0) as f64;
    assert!(
        close(*tan_half_fov_x, (diagonal_half / 2f64.sqrt()) as f32),
        "{tan_half_fov_x}"
    );
}

#[test]
fn a_textured_spot_keeps_its_frame_and_texture() {
    let dir = folder("spot");
    let s = load_in(
        &dir,
        "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"30\"/><transform name=\"to_world\"><rotate y=\"1\" angle=\"90\"/></transform><texture type=\"bitmap\" name=\"texture\"><string name=\"filename\" value=\"img.png\"/></texture></emitter><emitter type=\"spot\"/>",
    )
    .unwrap();
    let Light::TexturedSpot {
        frame,
        cone_deg,
        falloff_deg,
        texture,
        ..
    } = &s.lights[0]
    else {
        panic!("{:?}", s.lights);
    };
    assert!((frame.z_axis - Vec3::X).length() < 1e-6, "{frame:?}");
    assert_eq!((*cone_deg, *falloff_deg), (30.0, 22.5));
    assert!(matches!(s.texture(*texture), Texture::Bitmap(_)));
    // Without a texture it stays a plain spot.
    assert!(matches!(s.lights[1], Light::Spot { .. }));
}

#[test]
fn a_textured_area_radiance_is_listed_with_its_material() {
    let dir = folder("area");
    let s = load_in(
        &dir,
        "<shape type=\"sphere\"><emitter type=\"area\"><texture type=\"bitmap\" name=\"radiance\"><string name=\"filename\" value=\"img.png\"/></texture></emitter></shape>",
    )
    .unwrap();
    assert_eq!(s.emission_textures.len(), 1);
    let (m, t) = s.emission_textures[0];
    assert_eq!(s.materials[m.0 as usize].emission, Vec3::ONE);
    assert!(matches!(s.texture(t), Texture::Bitmap(_)));
    assert_eq!(s.emission_texture(m), Some(t));
}

#[test]
fn rawconstant_is_a_constant_texture_and_face_colours_come_from_ply_faces() {
    let dir = folder("raw");
    let s = load_in(
        &dir,
        "<shape type=\"cube\"><bsdf type=\"normalmap\"><texture type=\"rawconstant\" name=\"normalmap\"><vector name=\"value\" value=\"0.5, 0.5, 1\"/></texture><bsdf type=\"diffuse\"/></bsdf></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    assert_eq!(
        s.textures[0],
        Texture::Constant {
            value: Vec3::new(0.5, 0.5, 1.0)
        }
    );
    // A quad and a triangle, each with its own colour: the quad's for both its triangles.
    let ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n4 0 1 2 3 255 0 0\n3 1 4 2 0 0 255\n";
    std::fs::write(dir.join("faces.ply"), ply).unwrap();
    let s = load_in(
        &dir,
        "<shape type=\"ply\"><string name=\"filename\" value=\"faces.ply\"/><bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\"><string name=\"name\" value=\"face_color\"/></texture></bsdf></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    let m = s.meshes.iter().find(|m| m.indices.len() == 3).unwrap();
    assert_eq!(m.face_colors, vec![Vec3::X, Vec3::X, Vec3::Z]);
    assert!(matches!(&s.textures[0], Texture::MeshAttribute { name } if name == "face_color"));
}

#[test]
fn beams_and_textures_report_bad_input_at_the_element() {
    let dir = folder("bad");
    let err = |body: &str| load_in(&dir, body).unwrap_err().to_string();
    let e = err("<emitter type=\"spot\"><rgb name=\"texture\" value=\"1\"/></emitter>");
    assert!(
        e.contains("test.xml:3:") && e.contains("`texture` must be a texture"),
        "{e}"
    );
    let e = err(
        "<emitter type=\"projector\"><texture type=\"bitmap\" name=\"irradiance\"><string name=\"filename\" value=\"nope.png\"/></texture></emitter>",
    );
    assert!(e.contains("test.xml:3:") && e.contains("nope.png"), "{e}");
    let e = err("<emitter type=\"projector\"><float name=\"fov\" value=\"180\"/></emitter>");
    assert!(e.contains("fov 180 must be in (0, 180)"), "{e}");
    let e = err("<emitter type=\"projector\"><float name=\"scale\" value=\"-1\"/></emitter>");
    assert!(e.contains("scale -1 must be in [0"), "{e}");
    // A singular to_world is refused where the transform is read (a <scale> by 0) or, for a
    // matrix, by the light.
    let e = err(
        "<emitter type=\"spot\"><transform name=\"to_world\"><matrix value=\"1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1\"/></transform></emitter>",
    );
    assert!(e.contains("test.xml:3:") && e.contains("singular"), "{e}");
    let e = err(
        "<shape type=\"cube\"><bsdf type=\"normalmap\"><texture type=\"rawconstant\" name=\"normalmap\"><vector name=\"value\" value=\"-1, 0, 1\"/></texture><bsdf type=\"diffuse\"/></bsdf></shape>",
    );
    assert!(
        e.contains("parameter `value`") && e.contains("negative"),
        "{e}"
    );
    let e = err(
        "<shape type=\"cube\"><emitter type=\"area\"><texture type=\"mesh_attribute\" name=\"radiance\"><string name=\"name\" value=\"vertex_color\"/></texture></emitter></shape>",
    );
    assert!(
        e.contains("mesh_attribute radiance is not supported"),
        "{e}"
    );
}

#[test]
fn principal_point_offsets_shift_perspective_views() {
    let dir = folder("pp");
    let sensor = |kind: &str, extra: &str| {
        format!(
            "<sensor type=\"{kind}\"><float name=\"fov\" value=\"40\"/>{extra}<float name=\"principal_point_offset_x\" value=\"0.25\"/><float name=\"principal_point_offset_y\" value=\"-0.1\"/></sensor><emitter type=\"constant\"/>"
        )
    };
    let s = load_in(&dir, &sensor("perspective", "")).unwrap();
    assert_eq!(
        s.camera.unwrap().projection,
        eyeadapt_scene::Projection::Shifted {
            shift_x: 0.25,
            shift_y: -0.1,
            aperture_radius: 0.0,
            focus_distance: 1.0
        }
    );
    // Mitsuba's thin lens and orthographic sensors have no principal point: an unknown
    // parameter.
    let lens = "<float name=\"aperture_radius\" value=\"0.2\"/><float name=\"focus_distance\" value=\"5\"/>";
    let e = load_in(&dir, &sensor("thinlens", lens))
        .unwrap_err()
        .to_string();
    assert!(e.contains("principal_point_offset_x"), "{e}");
    let e = load_in(&dir, &sensor("orthographic", ""))
        .unwrap_err()
        .to_string();
    assert!(e.contains("principal_point_offset_x"), "{e}");
}
