//! What the fuzz targets check, one function per target. Shared with `tests/corpus/fuzz.rs`, which
//! feeds every input kept in `tests/corpus/fuzz-regressions/TARGET/` to the same function in a
//! normal `cargo test` (so it depends on nothing but the eyeadapt crates).
#![allow(dead_code)]
use eyeadapt_scene::{Bsdf, Light, Param, Rgb as Vec3, Scene, check_colour, load_obj_bytes};
use eyeadapt_sequencer::{FrameSet, MAX_FRAMES};
use eyeadapt_tracer::{PathSettings, RenderSettings, SceneData, View, render};
use std::path::Path;

/// Builds the BVH and light set of an accepted scene and renders a 4×3 image at 1 spp: no
/// panic, and every pixel of every AOV is finite (non-finite samples must be dropped).
/// Scenes above `max_triangles` only get their BVH built (rendering them is slow for a fuzzer).
pub fn check_accepted_scene(scene: &Scene, max_triangles: usize) {
    for m in &scene.meshes {
        assert!(
            m.positions.iter().all(|p| p.is_finite()),
            "non-finite vertex accepted"
        );
        let n = m.positions.len() as u32;
        assert!(
            m.indices.iter().flatten().all(|&i| i < n),
            "index out of range accepted"
        );
    }
    for inst in &scene.instances {
        assert!(
            (inst.mesh.0 as usize) < scene.meshes.len(),
            "dangling mesh id"
        );
        if let Some(eyeadapt_scene::MaterialId(i)) = inst.material {
            assert!((i as usize) < scene.materials.len(), "dangling material id");
        }
    }
    for mat in &scene.materials {
        assert!(
            check_colour(mat.emission).is_ok(),
            "bad emission accepted: {mat:?}"
        );
        let ok = bsdf_ok(&mat.bsdf, scene.textures.len());
        assert!(ok, "bad material accepted: {mat:?}");
    }
    if let Some(c) = &scene.camera {
        assert!(
            c.position.is_finite() && c.look_at.is_finite() && c.up.is_finite(),
            "non-finite camera accepted: {c:?}"
        );
        assert!(
            c.fov_deg > 0.0 && c.fov_deg < 180.0,
            "bad fov accepted: {c:?}"
        );
        assert!(c.width >= 1 && c.height >= 1, "empty image accepted: {c:?}");
        assert!(c.forward().is_finite(), "no view direction accepted: {c:?}");
        if let eyeadapt_scene::Projection::Shifted {
            shift_x,
            shift_y,
            aperture_radius,
            focus_distance,
        } = c.projection
        {
            assert!(
                shift_x.is_finite()
                    && shift_y.is_finite()
                    && aperture_radius >= 0.0
                    && focus_distance > 0.0,
                "bad shifted projection accepted: {c:?}"
            );
        }
    }
    for l in &scene.lights {
        let ok = light_ok(l, scene.textures.len());
        assert!(ok, "bad light accepted: {l:?}");
    }
    for t in &scene.textures {
        assert!(texture_ok(t), "bad texture accepted: {t:?}");
    }
    for (m, t) in &scene.emission_textures {
        assert!(
            (m.0 as usize) < scene.materials.len() && (t.0 as usize) < scene.textures.len(),
            "dangling emission texture ({m:?}, {t:?})"
        );
    }
    for m in &scene.meshes {
        assert!(
            m.face_colors.is_empty() || m.face_colors.len() == m.indices.len(),
            "face colours that are not one per triangle accepted"
        );
        assert!(
            m.face_colors.iter().all(|c| c.is_finite()),
            "non-finite face colour accepted"
        );
    }
    if let Some(e) = scene.environment {
        assert!(check_colour(e).is_ok(), "bad environment accepted: {e:?}");
    }
    if let Some(m) = &scene.environment_map {
        assert!(
            eyeadapt_scene::check_lat_long(&m.image).is_ok()
                && m.scale.is_finite()
                && m.scale >= 0.0,
            "bad environment map accepted: {}",
            m.filename.display()
        );
    }
    if scene.triangle_count() > max_triangles {
        return;
    }
    let data = SceneData::new(scene);
    let view = match &scene.camera {
        Some(c) => View {
            width: 4,
            height: 3,
            ..View::from_camera(c)
        },
        None => View {
            position: Vec3::new(0.0, 0.0, 5.0),
            forward: Vec3::NEG_Z,
            up: Vec3::Y,
            fov_deg: 60.0,
            width: 4,
            height: 3,
            projection: eyeadapt_scene::Projection::Pinhole,
        },
    };
    let settings = RenderSettings {
        spp: 1,
        path: PathSettings {
            max_depth: 4,
            rr_depth: 3,
        },
        seed: 1,
        frame: 0,
        filter: scene.render.filter.unwrap_or_default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    let f = render(&data, &view, &settings);
    assert_eq!(f.stats.samples, 12);
    for v in [&f.rgb, &f.albedo, &f.achromatic, &f.irradiance, &f.normal] {
        assert_eq!(v.len(), 12);
        assert!(
            v.iter().flatten().all(|x| x.is_finite()),
            "non-finite pixel"
        );
    }
    for v in [&f.depth, &f.emitter, &f.hit] {
        assert!(v.iter().all(|x| x.is_finite()), "non-finite pixel");
    }
}

/// `scene_toml`: the TOML scene loader on arbitrary text returns a scene or located
/// diagnostics, never panics; accepted scenes build and render.
pub fn scene_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // A directory that does not exist: relative OBJ paths resolve to nothing.
    let path = Path::new("/nonexistent-eyeadapt-fuzz/scene.toml");
    match eyeadapt_scene::load_scene_str(text, path) {
        Ok(scene) => check_accepted_scene(&scene, 5_000),
        Err(e) => {
            assert!(!e.diagnostics.is_empty());
            for d in &e.diagnostics {
                // Every location lies inside the text (line 0 = whole file).
                assert!(d.line <= text.lines().count() + 1, "{d}");
                let _ = d.to_string();
            }
        }
    }
}

/// `obj`: the OBJ/MTL path (`load_obj_bytes`, the validation of a scene's obj shape) on
/// arbitrary bytes, split at the first NUL into an OBJ and the MTL every `mtllib` resolves
/// to. Never panics; accepted meshes build and render.
pub fn obj(data: &[u8]) {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], Some(&data[i + 1..])),
        None => (data, None),
    };
    let Ok(loaded) = load_obj_bytes(obj, mtl, Path::new("fuzz.obj")) else {
        return;
    };
    assert_eq!(loaded.meshes.len(), loaded.materials.len());
    let mut scene = Scene::default();
    for (mesh, mat) in loaded.meshes.into_iter().zip(loaded.materials) {
        let material = mat.map(|m| scene.add_material(m));
        scene.add_world_mesh(mesh, material);
    }
    scene.environment = Some(Vec3::splat(0.5));
    check_accepted_scene(&scene, 20_000);
}

/// `frame_spec`: frame specs (`FrameSet::from_str`, `from_start_end_step`, chunks) never
/// panic; results are sorted and unique, within `MAX_FRAMES`, and round-trip through Display.
pub fn frame_spec(data: &[u8]) {
    if data.len() >= 12 {
        let w = |i: usize| u32::from_le_bytes(data[i..i + 4].try_into().unwrap());
        let (start, end, step) = (w(0), w(4), w(8));
        // Only ranges small enough to enumerate cheaply; the cap itself is tested below.
        if start <= end && step > 0 && (end - start) / step < 100_000 {
            let set = FrameSet::from_start_end_step(start, end, step).unwrap();
            let s = set.as_slice();
            assert_eq!(s.first(), Some(&start));
            assert!(s.windows(2).all(|p| p[1] - p[0] == step));
            assert!(*s.last().unwrap() <= end && end - s.last().unwrap() < step);
        } else if start > end || step == 0 {
            assert!(FrameSet::from_start_end_step(start, end, step).is_err());
        }
    }
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match text.parse::<FrameSet>() {
        Ok(set) => {
            let s = set.as_slice();
            assert!(!s.is_empty());
            assert!(s.len() as u64 <= MAX_FRAMES);
            assert!(s.windows(2).all(|p| p[0] < p[1]), "not sorted and unique");
            let shown = set.to_string();
            let back: FrameSet = shown.parse().expect("Display output must parse");
            assert_eq!(back, set, "round trip through {shown:?}");
            // Chunking is linear in the set; keep executions fast on million-frame specs.
            let sizes: &[usize] = if s.len() <= 10_000 {
                &[1, 7, 1000]
            } else {
                &[]
            };
            for &size in sizes {
                let n = set.chunk_count(size).unwrap();
                let mut joined = Vec::new();
                for i in 0..n {
                    joined.extend(set.chunk(size, i).unwrap().iter());
                }
                assert_eq!(joined, s);
                assert!(set.chunk(size, n).is_err());
            }
        }
        Err(e) => {
            assert!(e.column >= 1 && e.column <= text.chars().count() + 1, "{e}");
            let _ = e.to_string();
        }
    }
}

/// `mitsuba_xml`: the Mitsuba 3 XML loader (`load_mitsuba_str`) on arbitrary text returns a
/// scene or located diagnostics, never panics; accepted scenes build and render. Bytes after
/// the first NUL become `mesh.ply` next to the scene, so `<string name="filename"
/// value="mesh.ply"/>` reaches the PLY reader too.
pub fn mitsuba_xml(data: &[u8]) {
    let (xml, ply) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], Some(&data[i + 1..])),
        None => (data, None),
    };
    let Ok(text) = std::str::from_utf8(xml) else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("eyeadapt-fuzz-xml-{}", std::process::id()));
    let mesh = dir.join("mesh.ply");
    match ply {
        Some(bytes) => {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&mesh, bytes).unwrap();
        }
        None => {
            let _ = std::fs::remove_file(&mesh);
        }
    }
    match eyeadapt_scene::load_mitsuba_str(text, &dir.join("scene.xml"), &[]) {
        Ok(scene) => check_accepted_scene(&scene, 5_000),
        Err(e) => {
            assert!(!e.diagnostics.is_empty());
            for d in &e.diagnostics {
                assert!(d.line <= text.lines().count() + 1, "{d}");
                let _ = d.to_string();
            }
        }
    }
}

/// A light's values are usable: finite positions and frames, colours, angles and textures
/// that exist.
fn light_ok(l: &Light, textures: usize) -> bool {
    match l {
        Light::Point {
            position,
            intensity,
        } => position.is_finite() && check_colour(*intensity).is_ok(),
        Light::Spot {
            position,
            direction,
            intensity,
            cone_deg,
            falloff_deg,
        } => {
            position.is_finite()
                && direction.is_finite()
                && check_colour(*intensity).is_ok()
                && cone_deg.is_finite()
                && falloff_deg.is_finite()
        }
        Light::Directional {
            direction,
            irradiance,
        } => (direction.length() - 1.0).abs() < 1e-4 && check_colour(*irradiance).is_ok(),
        Light::TexturedSpot {
            position,
            frame,
            intensity,
            cone_deg,
            falloff_deg,
            texture,
        } => {
            position.is_finite()
                && frame.is_finite()
                && frame.determinant() != 0.0
                && check_colour(*intensity).is_ok()
                && cone_deg.is_finite()
                && falloff_deg.is_finite()
                && (texture.0 as usize) < textures
        }
        Light::Projector {
            position,
            frame,
            irradiance,
            scale,
            tan_half_fov_x,
            aspect,
        } => {
            position.is_finite()
                && frame.is_finite()
                && frame.determinant() != 0.0
                && match irradiance {
                    Param::Const(c) => check_colour(*c).is_ok(),
                    Param::Texture(t) => (t.0 as usize) < textures,
                }
                && scale.is_finite()
                && *scale >= 0.0
                && tan_half_fov_x.is_finite()
                && *tan_half_fov_x > 0.0
                && aspect.is_finite()
                && *aspect > 0.0
        }
    }
}

/// A texture's values are usable: finite colours (constants, checkerboards) and images whose
/// texels fill their size.
fn texture_ok(t: &eyeadapt_scene::Texture) -> bool {
    use eyeadapt_scene::Texture;
    match t {
        Texture::Bitmap(b) => {
            b.image.texels.len() == b.image.width as usize * b.image.height as usize
                && b.to_uv.is_finite()
        }
        Texture::Checkerboard {
            color0,
            color1,
            to_uv,
        } => check_colour(*color0).is_ok() && check_colour(*color1).is_ok() && to_uv.is_finite(),
        Texture::MeshAttribute { name } => name == "vertex_color" || name == "face_color",
        Texture::Constant { value } => check_colour(*value).is_ok(),
    }
}

/// Every value a BSDF (and the BSDFs it wraps) holds is usable: finite colours, numbers and
/// IORs (positive for dielectrics), textures that exist.
fn bsdf_ok(bsdf: &Bsdf, textures: usize) -> bool {
    let colour = |p: &Param<Vec3>| match p {
        Param::Const(c) => check_colour(*c).is_ok(),
        Param::Texture(t) => (t.0 as usize) < textures,
    };
    let number = |p: &Param<f32>| match p {
        Param::Const(x) => x.is_finite(),
        Param::Texture(t) => (t.0 as usize) < textures,
    };
    let glass = |eta: f32, r: Vec3, t: Vec3| {
        eta.is_finite() && eta > 0.0 && check_colour(r).is_ok() && check_colour(t).is_ok()
    };
    match bsdf {
        Bsdf::Diffuse { reflectance } => colour(reflectance),
        Bsdf::Conductor {
            alpha,
            alpha_v,
            distribution: _,
            eta,
            k,
            specular_reflectance,
        } => {
            number(alpha)
                && alpha_v.as_ref().is_none_or(number)
                && check_colour(*eta).is_ok()
                && check_colour(*k).is_ok()
                && colour(specular_reflectance)
        }
        Bsdf::Plastic {
            reflectance,
            alpha,
            distribution: _,
            ior,
        } => colour(reflectance) && number(alpha) && ior.is_finite(),
        Bsdf::Dielectric {
            eta,
            specular_reflectance,
            specular_transmittance,
        }
        | Bsdf::ThinDielectric {
            eta,
            specular_reflectance,
            specular_transmittance,
        } => glass(*eta, *specular_reflectance, *specular_transmittance),
        Bsdf::RoughDielectric {
            alpha,
            alpha_v,
            distribution: _,
            eta,
            specular_reflectance,
            specular_transmittance,
        } => {
            number(alpha)
                && alpha_v.as_ref().is_none_or(number)
                && glass(*eta, *specular_reflectance, *specular_transmittance)
        }
        Bsdf::OneSided(inner) => bsdf_ok(inner, textures),
        Bsdf::Mask { opacity, bsdf } => number(opacity) && bsdf_ok(bsdf, textures),
        Bsdf::NormalMap { normals, bsdf } => {
            (normals.0 as usize) < textures && bsdf_ok(bsdf, textures)
        }
        Bsdf::Principled(p) => principled_ok(p, textures),
        Bsdf::PrincipledThin(p) => principled_thin_ok(p, textures),
        Bsdf::BumpMap {
            height,
            scale,
            bsdf,
        } => (height.0 as usize) < textures && scale.is_finite() && bsdf_ok(bsdf, textures),
        Bsdf::Blend { weight, bsdfs } => {
            let weight_ok = match weight {
                Param::Const(w) => (0.0..=1.0).contains(w),
                Param::Texture(t) => (t.0 as usize) < textures,
            };
            weight_ok && bsdfs.iter().all(|b| bsdf_ok(b, textures))
        }
        Bsdf::Null => true,
        Bsdf::PPlastic {
            diffuse_reflectance,
            specular_reflectance,
            alpha,
            alpha_v,
            distribution: _,
            eta,
        } => {
            colour(diffuse_reflectance)
                && colour(specular_reflectance)
                && number(alpha)
                && alpha_v.as_ref().is_none_or(number)
                && eta.is_finite()
                && *eta > 0.0
        }
    }
}

/// A weight is a texture that exists or a constant in `[0, max]`.
fn weight_ok(p: &Param<f32>, max: f32, textures: usize) -> bool {
    match p {
        Param::Const(x) => (0.0..=max).contains(x),
        Param::Texture(t) => (t.0 as usize) < textures,
    }
}

fn base_colour_ok(p: &Param<Vec3>, textures: usize) -> bool {
    match p {
        Param::Const(c) => check_colour(*c).is_ok() && c.max_element() <= 1.0,
        Param::Texture(t) => (t.0 as usize) < textures,
    }
}

/// Every weight of a principled BSDF in [0, 1], its IOR positive and finite.
fn principled_ok(p: &eyeadapt_scene::Principled, textures: usize) -> bool {
    let weights = [
        &p.roughness,
        &p.metallic,
        &p.spec_tint,
        &p.anisotropic,
        &p.sheen,
        &p.sheen_tint,
        &p.clearcoat,
        &p.clearcoat_gloss,
        &p.spec_trans,
        &p.flatness,
    ];
    base_colour_ok(&p.base_color, textures)
        && weights.iter().all(|w| weight_ok(w, 1.0, textures))
        && p.eta.is_finite()
        && p.eta > 0.0
}

/// As [`principled_ok`], with `diff_trans` in [0, 2] and a positive IOR (or a texture).
fn principled_thin_ok(p: &eyeadapt_scene::PrincipledThin, textures: usize) -> bool {
    let weights = [
        &p.roughness,
        &p.spec_tint,
        &p.anisotropic,
        &p.sheen,
        &p.sheen_tint,
        &p.spec_trans,
        &p.flatness,
    ];
    let eta = match p.eta {
        Param::Const(e) => e.is_finite() && e > 0.0,
        Param::Texture(t) => (t.0 as usize) < textures,
    };
    base_colour_ok(&p.base_color, textures)
        && weights.iter().all(|w| weight_ok(w, 1.0, textures))
        && weight_ok(&p.diff_trans, 2.0, textures)
        && eta
}
