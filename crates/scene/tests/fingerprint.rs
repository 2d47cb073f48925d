//! The scene fingerprint changes when any single field of any type changes (a resumed run must
//! never mix outputs of different scenes), and only then.
use eyeadapt_scene::gltf::{Node, NodeTracks, NodeTree, Rest, SceneAnimation};
use eyeadapt_scene::{
    Bitmap, Bsdf, Camera, CameraPath, Distribution, EnvironmentMap, FilterType, Image, Instance,
    Keyframe, Light, Material, MaterialId, Mesh, MeshId, Orientation, Param, PixelFilter, Portal,
    Projection, RenderDefaults, Rgb, Scene, Texture, TextureId, Transform, WrapMode,
};
use eyeadapt_scene::{Interpolation, Track};
use glam::{Affine2, DMat4, DQuat, DVec3, Mat4, Vec2, Vec3};
use std::collections::BTreeMap;
use std::sync::Arc;
#[path = "fingerprint/surface.rs"]
mod surface;
use surface::{changes, full};

/// A scene with every type and every variant in it but those of `surface.rs`.
fn base() -> Scene {
    let image = Arc::new(Image {
        width: 2,
        height: 1,
        texels: vec![Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.4, 0.5, 0.6)],
    });
    Scene {
        source: "a.toml".into(),
        camera: Some(Camera {
            position: Vec3::new(0.0, 1.0, 3.0),
            look_at: Vec3::ZERO,
            up: Vec3::Y,
            fov_deg: 40.0,
            width: 32,
            height: 24,
            projection: eyeadapt_scene::Projection::Pinhole,
        }),
        materials: vec![
            Material {
                name: "d".into(),
                bsdf: Bsdf::Diffuse {
                    reflectance: Param::Texture(TextureId(0)),
                },
                emission: Rgb::ZERO,
            },
            Material {
                name: "c".into(),
                bsdf: Bsdf::Conductor {
                    distribution: Distribution::Ggx,
                    alpha: Param::Const(0.2),
                    alpha_v: None,
                    eta: Rgb::splat(0.2),
                    k: Rgb::splat(3.0),
                    specular_reflectance: Param::Const(Rgb::ONE),
                },
                emission: Rgb::ZERO,
            },
            Material {
                name: "p".into(),
                bsdf: Bsdf::Plastic {
                    distribution: Distribution::Ggx,
                    reflectance: Param::Const(Rgb::splat(0.5)),
                    alpha: Param::Texture(TextureId(1)),
                    ior: 1.5,
                },
                emission: Rgb::new(1.0, 2.0, 3.0),
            },
        ],
        textures: vec![
            Texture::Bitmap(Bitmap {
                filename: "t.png".into(),
                image,
                raw: false,
                filter: FilterType::Bilinear,
                wrap: WrapMode::Repeat,
                to_uv: Affine2::IDENTITY,
            }),
            Texture::Checkerboard {
                color0: Rgb::splat(0.4),
                color1: Rgb::splat(0.2),
                to_uv: Affine2::IDENTITY,
            },
            Texture::MeshAttribute {
                name: "vertex_color".into(),
            },
            Texture::Constant {
                value: Rgb::new(0.5, 0.5, 1.0),
            },
        ],
        meshes: vec![Mesh {
            name: "m".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            normals: vec![Vec3::Z; 3],
            uvs: vec![Vec2::ZERO, Vec2::X, Vec2::Y],
            colors: vec![Rgb::ONE; 3],
            face_colors: vec![Rgb::splat(0.5)],
        }],
        instances: vec![Instance {
            mesh: MeshId(0),
            material: Some(MaterialId(0)),
            to_world: Transform::default(),
        }],
        lights: vec![
            Light::Point {
                position: Vec3::Y,
                intensity: Rgb::ONE,
            },
            Light::Spot {
                position: Vec3::Y,
                direction: -Vec3::Y,
                intensity: Rgb::ONE,
                cone_deg: 30.0,
                falloff_deg: 20.0,
            },
            Light::Directional {
                direction: -Vec3::Y,
                irradiance: Rgb::ONE,
            },
            Light::TexturedSpot {
                position: Vec3::Y,
                frame: glam::Mat3::IDENTITY,
                intensity: Rgb::ONE,
                cone_deg: 30.0,
                falloff_deg: 20.0,
                texture: TextureId(0),
            },
            Light::Projector {
                position: Vec3::Y,
                frame: glam::Mat3::IDENTITY,
                irradiance: Param::Texture(TextureId(0)),
                scale: 1.0,
                tan_half_fov_x: 0.5,
                aspect: 2.0,
            },
        ],
        emission_textures: vec![(MaterialId(2), TextureId(0))],
        environment: Some(Rgb::splat(0.1)),
        environment_map: Some(EnvironmentMap {
            filename: "sky.exr".into(),
            image: std::sync::Arc::new(Image {
                width: 2,
                height: 1,
                texels: vec![Rgb::ONE, Rgb::splat(2.0)],
            }),
            scale: 1.0,
            to_world: glam::Mat3::IDENTITY,
        }),
        portals: vec![Portal {
            corner: Vec3::new(-1.0, 0.5, 0.0),
            u: Vec3::Y,
            v: Vec3::Z,
        }],
        render: RenderDefaults {
            spp: Some(16),
            max_depth: Some(8),
            rr_depth: Some(5),
            seed: Some(1),
            filter: Some(PixelFilter::GAUSSIAN),
        },
        cutout_shadows: Default::default(),
        camera_path: Some(CameraPath {
            fps: 24.0,
            keyframes: vec![
                Keyframe {
                    time: 0.0,
                    position: DVec3::ZERO,
                    orientation: Orientation::LookAt {
                        look_at: DVec3::Z,
                        up: DVec3::Y,
                    },
                    fov_deg: None,
                },
                Keyframe {
                    time: 1.0,
                    position: DVec3::X,
                    orientation: Orientation::YawPitch {
                        yaw_deg: 10.0,
                        pitch_deg: 0.0,
                    },
                    fov_deg: None,
                },
            ],
        }),
        warnings: Vec::new(),
        animation: Some(Arc::new(animation())),
    }
}

/// Two nodes, the child animated, placing instance 0 and light 0.
fn animation() -> SceneAnimation {
    let still = Node {
        index: 0,
        name: Some("root".into()),
        parent: None,
        rest: Rest::Matrix(DMat4::IDENTITY),
        tracks: NodeTracks::default(),
    };
    let moving = Node {
        index: 1,
        name: None,
        parent: Some(0),
        rest: Rest::Trs {
            translation: DVec3::X,
            rotation: DQuat::IDENTITY,
            scale: DVec3::ONE,
        },
        tracks: NodeTracks {
            translation: Some(Track {
                times: vec![0.0, 1.0],
                values: vec![DVec3::ZERO, DVec3::Y],
                interpolation: Interpolation::Linear,
            }),
            rotation: None,
            scale: None,
        },
    };
    SceneAnimation {
        tree: NodeTree {
            nodes: vec![still, moving],
        },
        instances: vec![(0, 1)],
        lights: vec![(
            0,
            1,
            Light::Point {
                position: Vec3::ZERO,
                intensity: Rgb::ONE,
            },
        )],
    }
}

type Change = fn(&mut Scene);

/// One change of every field (and of every variant's fields), by name, but `surface.rs`'s.
fn base_changes() -> Vec<(&'static str, Change)> {
    fn cam(s: &mut Scene) -> &mut Camera {
        s.camera.as_mut().unwrap()
    }
    fn bsdf(s: &mut Scene, i: usize) -> &mut Bsdf {
        &mut s.materials[i].bsdf
    }
    fn bitmap(s: &mut Scene) -> &mut Bitmap {
        match &mut s.textures[0] {
            Texture::Bitmap(b) => b,
            _ => unreachable!(),
        }
    }
    fn anim(s: &mut Scene) -> &mut SceneAnimation {
        Arc::make_mut(s.animation.as_mut().unwrap())
    }
    fn key(s: &mut Scene, i: usize) -> &mut Keyframe {
        &mut s.camera_path.as_mut().unwrap().keyframes[i]
    }
    vec![
        ("camera", |s| s.camera = None),
        ("camera.position", |s| cam(s).position.x += 0.5),
        ("camera.look_at", |s| cam(s).look_at.y += 0.5),
        ("camera.up", |s| cam(s).up = Vec3::X),
        ("camera.fov_deg", |s| cam(s).fov_deg = 41.0),
        ("camera.projection thin lens", |s| {
            cam(s).projection = Projection::ThinLens {
                aperture_radius: 0.1,
                focus_distance: 2.0,
            }
        }),
        ("camera.projection orthographic", |s| {
            cam(s).projection = Projection::Orthographic {
                half_width: 1.0,
                half_height: 0.75,
            }
        }),
        ("camera.width", |s| cam(s).width = 33),
        ("camera.height", |s| cam(s).height = 25),
        ("material.name", |s| s.materials[0].name = "e".into()),
        ("material.emission", |s| s.materials[0].emission.x = 1.0),
        ("material order", |s| s.materials.swap(0, 1)),
        ("diffuse.reflectance", |s| {
            *bsdf(s, 0) = Bsdf::Diffuse {
                reflectance: Param::Texture(TextureId(2)),
            }
        }),
        ("diffuse.reflectance const", |s| {
            *bsdf(s, 0) = Bsdf::Diffuse {
                reflectance: Param::Const(Rgb::ZERO),
            }
        }),
        ("conductor.alpha", |s| {
            if let Bsdf::Conductor { alpha, .. } = bsdf(s, 1) {
                *alpha = Param::Const(0.3);
            }
        }),
        ("conductor.eta", |s| {
            if let Bsdf::Conductor { eta, .. } = bsdf(s, 1) {
                eta.y = 0.3;
            }
        }),
        ("conductor.k", |s| {
            if let Bsdf::Conductor { k, .. } = bsdf(s, 1) {
                k.z = 2.0;
            }
        }),
        ("conductor.specular_reflectance", |s| {
            if let Bsdf::Conductor {
                specular_reflectance,
                ..
            } = bsdf(s, 1)
            {
                *specular_reflectance = Param::Texture(TextureId(0));
            }
        }),
        ("plastic.reflectance", |s| {
            if let Bsdf::Plastic { reflectance, .. } = bsdf(s, 2) {
                *reflectance = Param::Const(Rgb::splat(0.6));
            }
        }),
        ("plastic.alpha", |s| {
            if let Bsdf::Plastic { alpha, .. } = bsdf(s, 2) {
                *alpha = Param::Texture(TextureId(0));
            }
        }),
        ("plastic.ior", |s| {
            if let Bsdf::Plastic { ior, .. } = bsdf(s, 2) {
                *ior = 1.4;
            }
        }),
        ("bitmap.filename", |s| bitmap(s).filename = "u.png".into()),
        ("bitmap.image.width", |s| {
            let img = Image {
                width: 1,
                height: 2,
                ..(*bitmap(s).image).clone()
            };
            bitmap(s).image = Arc::new(img);
        }),
        ("bitmap.image.texels", |s| {
            let mut img = (*bitmap(s).image).clone();
            img.texels[1].z = 0.7;
            bitmap(s).image = Arc::new(img);
        }),
        ("bitmap.raw", |s| bitmap(s).raw = true),
        ("bitmap.filter", |s| bitmap(s).filter = FilterType::Nearest),
        ("bitmap.wrap", |s| bitmap(s).wrap = WrapMode::Clamp),
        ("bitmap.to_uv", |s| {
            bitmap(s).to_uv = Affine2::from_scale(Vec2::splat(2.0))
        }),
        ("checkerboard.color0", |s| {
            if let Texture::Checkerboard { color0, .. } = &mut s.textures[1] {
                color0.x = 0.5;
            }
        }),
        ("checkerboard.color1", |s| {
            if let Texture::Checkerboard { color1, .. } = &mut s.textures[1] {
                color1.y = 0.5;
            }
        }),
        ("checkerboard.to_uv", |s| {
            if let Texture::Checkerboard { to_uv, .. } = &mut s.textures[1] {
                *to_uv = Affine2::from_translation(Vec2::X);
            }
        }),
        ("mesh_attribute.name", |s| {
            s.textures[2] = Texture::MeshAttribute { name: "uv".into() }
        }),
        ("rawconstant.value", |s| {
            s.textures[3] = Texture::Constant {
                value: Rgb::new(0.5, 0.5, 0.9),
            }
        }),
        ("mesh.face_colors", |s| s.meshes[0].face_colors[0].y = 0.1),
        ("emission_textures", |s| s.emission_textures.clear()),
        ("emission_textures.texture", |s| {
            s.emission_textures[0].1 = TextureId(1)
        }),
        ("textured_spot.frame", |s| {
            if let Light::TexturedSpot { frame, .. } = &mut s.lights[3] {
                *frame = glam::Mat3::from_rotation_z(1.0);
            }
        }),
        ("textured_spot.texture", |s| {
            if let Light::TexturedSpot { texture, .. } = &mut s.lights[3] {
                *texture = TextureId(1);
            }
        }),
        ("textured_spot.cone_deg", |s| {
            if let Light::TexturedSpot { cone_deg, .. } = &mut s.lights[3] {
                *cone_deg = 31.0;
            }
        }),
        ("projector.irradiance", |s| {
            if let Light::Projector { irradiance, .. } = &mut s.lights[4] {
                *irradiance = Param::Const(Rgb::ONE);
            }
        }),
        ("projector.scale", |s| {
            if let Light::Projector { scale, .. } = &mut s.lights[4] {
                *scale = 2.0;
            }
        }),
        ("projector.tan_half_fov_x", |s| {
            if let Light::Projector { tan_half_fov_x, .. } = &mut s.lights[4] {
                *tan_half_fov_x = 0.6;
            }
        }),
        ("projector.aspect", |s| {
            if let Light::Projector { aspect, .. } = &mut s.lights[4] {
                *aspect = 1.0;
            }
        }),
        ("projector.position", |s| {
            if let Light::Projector { position, .. } = &mut s.lights[4] {
                position.x = 1.0;
            }
        }),
        ("mesh.name", |s| s.meshes[0].name = "n".into()),
        ("mesh.positions", |s| s.meshes[0].positions[2].z = 0.1),
        ("mesh.indices", |s| s.meshes[0].indices[0] = [0, 2, 1]),
        ("mesh.normals", |s| s.meshes[0].normals.clear()),
        ("mesh.uvs", |s| s.meshes[0].uvs[1].y = 0.5),
        ("mesh.colors", |s| s.meshes[0].colors[0].x = 0.5),
        ("instance.mesh", |s| {
            s.meshes.push(s.meshes[0].clone());
            s.instances[0].mesh = MeshId(1);
        }),
        ("instance.material", |s| s.instances[0].material = None),
        ("instance.to_world", |s| {
            s.instances[0].to_world = Transform {
                matrix: Mat4::from_translation(Vec3::X),
            }
        }),
        ("instance added", |s| s.instances.push(s.instances[0])),
        ("point.position", |s| {
            if let Light::Point { position, .. } = &mut s.lights[0] {
                position.x = 1.0;
            }
        }),
        ("point.intensity", |s| {
            if let Light::Point { intensity, .. } = &mut s.lights[0] {
                intensity.x = 2.0;
            }
        }),
        ("spot.position", |s| {
            if let Light::Spot { position, .. } = &mut s.lights[1] {
                position.z = 1.0;
            }
        }),
        ("spot.direction", |s| {
            if let Light::Spot { direction, .. } = &mut s.lights[1] {
                *direction = -Vec3::Z;
            }
        }),
        ("spot.intensity", |s| {
            if let Light::Spot { intensity, .. } = &mut s.lights[1] {
                intensity.y = 2.0;
            }
        }),
        ("spot.cone_deg", |s| {
            if let Light::Spot { cone_deg, .. } = &mut s.lights[1] {
                *cone_deg = 31.0;
            }
        }),
        ("spot.falloff_deg", |s| {
            if let Light::Spot { falloff_deg, .. } = &mut s.lights[1] {
                *falloff_deg = 21.0;
            }
        }),
        ("sun.direction", |s| {
            if let Light::Directional { direction, .. } = &mut s.lights[2] {
                *direction = -Vec3::Z;
            }
        }),
        ("sun.irradiance", |s| {
            if let Light::Directional { irradiance, .. } = &mut s.lights[2] {
                *irradiance = Rgb::splat(2.0);
            }
        }),
        ("environment_map", |s| s.environment_map = None),
        ("environment_map.filename", |s| {
            s.environment_map.as_mut().unwrap().filename = "other.exr".into()
        }),
        ("environment_map.texels", |s| {
            let m = s.environment_map.as_mut().unwrap();
            let mut img = (*m.image).clone();
            img.texels[1] = Rgb::splat(3.0);
            m.image = std::sync::Arc::new(img);
        }),
        ("environment_map.scale", |s| {
            s.environment_map.as_mut().unwrap().scale = 2.0
        }),
        ("environment_map.to_world", |s| {
            s.environment_map.as_mut().unwrap().to_world = glam::Mat3::from_rotation_y(1.0)
        }),
        ("portals", |s| s.portals.clear()),
        ("portals.corner", |s| s.portals[0].corner.x -= 0.5),
        ("portals.u", |s| s.portals[0].u = 2.0 * Vec3::Y),
        ("portals.v", |s| s.portals[0].v = -Vec3::Z),
        ("environment", |s| s.environment = None),
        ("environment value", |s| {
            s.environment = Some(Rgb::splat(0.2))
        }),
        ("render.spp", |s| s.render.spp = None),
        ("render.max_depth", |s| s.render.max_depth = Some(-1)),
        ("render.rr_depth", |s| s.render.rr_depth = Some(6)),
        ("render.seed", |s| s.render.seed = Some(2)),
        ("render.filter", |s| {
            s.render.filter = Some(PixelFilter::Box)
        }),
        ("render.filter radius", |s| {
            s.render.filter = Some(PixelFilter::Gaussian {
                stddev: 0.5,
                radius: 1.5,
            })
        }),
        ("camera_path", |s| s.camera_path = None),
        ("camera_path.fps", |s| {
            s.camera_path.as_mut().unwrap().fps = 25.0
        }),
        ("keyframe.time", |s| key(s, 1).time = 2.0),
        ("keyframe.position", |s| key(s, 0).position.y = 1.0),
        ("keyframe.look_at", |s| {
            key(s, 0).orientation = Orientation::LookAt {
                look_at: DVec3::X,
                up: DVec3::Y,
            }
        }),
        ("keyframe.up", |s| {
            key(s, 0).orientation = Orientation::LookAt {
                look_at: DVec3::Z,
                up: DVec3::X,
            }
        }),
        ("keyframe.yaw_deg", |s| {
            key(s, 1).orientation = Orientation::YawPitch {
                yaw_deg: 11.0,
                pitch_deg: 0.0,
            }
        }),
        ("keyframe.pitch_deg", |s| {
            key(s, 1).orientation = Orientation::YawPitch {
                yaw_deg: 10.0,
                pitch_deg: 1.0,
            }
        }),
        ("keyframe.fov_deg", |s| key(s, 0).fov_deg = Some(40.0)),
        ("cutout_shadows", |s| {
            s.cutout_shadows = eyeadapt_scene::CutoutShadows::Block
        }),
        ("animation", |s| s.animation = None),
        ("animation.parent", |s| anim(s).tree.nodes[1].parent = None),
        ("animation.rest", |s| {
            anim(s).tree.nodes[0].rest = Rest::Matrix(DMat4::from_scale(DVec3::splat(2.0)))
        }),
        ("animation.track.times", |s| {
            anim(s).tree.nodes[1]
                .tracks
                .translation
                .as_mut()
                .unwrap()
                .times[1] = 2.0
        }),
        ("animation.track.values", |s| {
            anim(s).tree.nodes[1]
                .tracks
                .translation
                .as_mut()
                .unwrap()
                .values[1] = DVec3::Z
        }),
        ("animation.track.interpolation", |s| {
            anim(s).tree.nodes[1]
                .tracks
                .translation
                .as_mut()
                .unwrap()
                .interpolation = Interpolation::Step
        }),
        ("animation.instances", |s| anim(s).instances[0].1 = 0),
        ("animation.lights", |s| anim(s).lights[0].1 = 0),
    ]
}

#[test]
fn every_single_change_changes_the_fingerprint() {
    let base = full().fingerprint();
    assert_eq!(base, full().fingerprint(), "deterministic");
    let mut seen: BTreeMap<String, &str> = BTreeMap::new();
    for (what, change) in changes() {
        let mut s = full();
        change(&mut s);
        let f = s.fingerprint();
        assert_ne!(f, base, "changing {what} left the fingerprint unchanged");
        if let Some(other) = seen.insert(f, what) {
            panic!("changing {what} and {other} gave the same fingerprint");
        }
    }
}

#[test]
fn where_the_scene_came_from_and_its_warnings_are_not_content() {
    let base = full().fingerprint();
    let mut s = full();
    s.source = "elsewhere/b.toml".into();
    s.warnings.push(eyeadapt_scene::Diagnostic {
        severity: eyeadapt_scene::Severity::Warning,
        file: "b.toml".into(),
        line: 3,
        col: 1,
        message: "a warning".into(),
    });
    assert_eq!(s.fingerprint(), base);
}
