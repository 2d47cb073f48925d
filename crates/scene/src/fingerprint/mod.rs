//! [`Scene::fingerprint`]: a SHA-256 of everything a scene renders from, so that a resumed run
//! can tell whether its outputs came from the same scene.
//!
//! Every type feeds its fields by exhaustive destructuring, so a field added to the model
//! does not compile until it is fed here (or explicitly declared irrelevant). Each value is
//! preceded by a tag naming its variant and each sequence by its length, so no two different
//! scenes feed the same bytes. Floats feed their bits: −0.0 and 0.0 differ, which can only
//! make a resume refuse, never mix scenes.
use crate::gltf::{Node, NodeTracks, Rest, SceneAnimation};
use crate::{
    Bitmap, Camera, CameraPath, EnvironmentMap, FilterType, Image, Instance, Keyframe, Mesh,
    Orientation, Param, PixelFilter, Projection, RenderDefaults, Scene, Texture, Transform,
    WrapMode,
};
use crate::{Interpolation, Track};
use glam::{Affine2, DQuat, DVec3, Mat3, Mat4, Vec2, Vec3};
use sha2::{Digest, Sha256};

mod light;
mod material;

/// Something that contributes to a fingerprint.
trait Feed {
    fn feed(&self, h: &mut Sha256);
}

impl Scene {
    /// Hex SHA-256 of the scene's content: camera, materials, textures (decoded texels
    /// included), meshes, instances, lights, environment and its portals, render defaults and
    /// camera path.
    /// The file it came from and its load warnings are not content and are left out.
    pub fn fingerprint(&self) -> String {
        let mut h = Sha256::new();
        h.update(b"eyeadapt scene v1\n");
        self.feed(&mut h);
        h.finalize().iter().map(|b| format!("{b:02x}")).collect()
    }
}

fn tag(h: &mut Sha256, t: u8) {
    h.update([t]);
}

impl Feed for f32 {
    fn feed(&self, h: &mut Sha256) {
        h.update(self.to_bits().to_le_bytes());
    }
}

impl Feed for f64 {
    fn feed(&self, h: &mut Sha256) {
        h.update(self.to_bits().to_le_bytes());
    }
}

impl Feed for u32 {
    fn feed(&self, h: &mut Sha256) {
        h.update(self.to_le_bytes());
    }
}

impl Feed for i32 {
    fn feed(&self, h: &mut Sha256) {
        h.update(self.to_le_bytes());
    }
}

impl Feed for u64 {
    fn feed(&self, h: &mut Sha256) {
        h.update(self.to_le_bytes());
    }
}

impl Feed for bool {
    fn feed(&self, h: &mut Sha256) {
        h.update([*self as u8]);
    }
}

impl Feed for str {
    fn feed(&self, h: &mut Sha256) {
        (self.len() as u64).feed(h);
        h.update(self.as_bytes());
    }
}

impl Feed for String {
    fn feed(&self, h: &mut Sha256) {
        self.as_str().feed(h);
    }
}

impl<T: Feed> Feed for [T] {
    fn feed(&self, h: &mut Sha256) {
        (self.len() as u64).feed(h);
        for x in self {
            x.feed(h);
        }
    }
}

impl<T: Feed> Feed for Vec<T> {
    fn feed(&self, h: &mut Sha256) {
        self.as_slice().feed(h);
    }
}

impl<T: Feed, const N: usize> Feed for [T; N] {
    fn feed(&self, h: &mut Sha256) {
        for x in self {
            x.feed(h);
        }
    }
}

impl<T: Feed> Feed for Option<T> {
    fn feed(&self, h: &mut Sha256) {
        match self {
            None => tag(h, 0),
            Some(x) => {
                tag(h, 1);
                x.feed(h);
            }
        }
    }
}

impl Feed for Vec2 {
    fn feed(&self, h: &mut Sha256) {
        self.to_array().feed(h);
    }
}

impl Feed for Vec3 {
    fn feed(&self, h: &mut Sha256) {
        self.to_array().feed(h);
    }
}

impl Feed for DVec3 {
    fn feed(&self, h: &mut Sha256) {
        self.to_array().feed(h);
    }
}

impl Feed for Mat3 {
    fn feed(&self, h: &mut Sha256) {
        self.to_cols_array().feed(h);
    }
}

impl Feed for Mat4 {
    fn feed(&self, h: &mut Sha256) {
        self.to_cols_array().feed(h);
    }
}

impl Feed for Affine2 {
    fn feed(&self, h: &mut Sha256) {
        self.to_cols_array().feed(h);
    }
}

impl Feed for Scene {
    fn feed(&self, h: &mut Sha256) {
        let Scene {
            source: _,
            camera,
            materials,
            textures,
            meshes,
            instances,
            lights,
            environment,
            environment_map,
            portals,
            emission_textures,
            render,
            cutout_shadows,
            camera_path,
            warnings: _,
            animation,
        } = self;
        camera.feed(h);
        materials.feed(h);
        textures.feed(h);
        meshes.feed(h);
        instances.feed(h);
        lights.feed(h);
        environment.feed(h);
        environment_map.feed(h);
        // Nothing for the scenes without (their fingerprints stay what they were).
        for (m, t) in emission_textures {
            tag(h, 0xE7);
            m.0.feed(h);
            t.0.feed(h);
        }
        // Nothing for the scenes without (their fingerprints stay what they were).
        for p in portals {
            tag(h, 0x9F);
            p.corner.feed(h);
            p.u.feed(h);
            p.v.feed(h);
        }
        render.feed(h);
        // Nothing for the default (fingerprints of TOML and glTF scenes stay what they were).
        match cutout_shadows {
            crate::CutoutShadows::Transmit => {}
            crate::CutoutShadows::Block => tag(h, 0xC5),
        }
        camera_path.feed(h);
        animation.as_deref().feed(h);
    }
}

impl Feed for SceneAnimation {
    fn feed(&self, h: &mut Sha256) {
        let SceneAnimation {
            tree,
            instances,
            lights,
        } = self;
        tree.nodes.feed(h);
        (instances.len() as u64).feed(h);
        for &(i, node) in instances {
            i.feed(h);
            (node as u64).feed(h);
        }
        (lights.len() as u64).feed(h);
        for (i, node, light) in lights {
            i.feed(h);
            (*node as u64).feed(h);
            light.feed(h);
        }
    }
}

impl Feed for Node {
    fn feed(&self, h: &mut Sha256) {
        // The name and index only label the node; the parent, rest pose and tracks place it.
        let Node {
            index: _,
            name: _,
            parent,
            rest,
            tracks,
        } = self;
        parent.map(|p| p as u64).feed(h);
        match rest {
            Rest::Matrix(m) => {
                tag(h, 0);
                m.to_cols_array().feed(h);
            }
            Rest::Trs {
                translation,
                rotation,
                scale,
            } => {
                tag(h, 1);
                translation.feed(h);
                rotation.to_array().feed(h);
                scale.feed(h);
            }
        }
        let NodeTracks {
            translation,
            rotation,
            scale,
        } = tracks;
        translation.feed(h);
        rotation.feed(h);
        scale.feed(h);
    }
}

impl<T: Copy> Feed for Track<T>
where
    [T]: Feed,
{
    fn feed(&self, h: &mut Sha256) {
        let Track {
            times,
            values,
            interpolation,
        } = self;
        times.feed(h);
        values.as_slice().feed(h);
        tag(
            h,
            match interpolation {
                Interpolation::Step => 0,
                Interpolation::Linear => 1,
                Interpolation::CubicSpline => 2,
            },
        );
    }
}

impl Feed for DQuat {
    fn feed(&self, h: &mut Sha256) {
        self.to_array().feed(h);
    }
}

impl<T: Feed + ?Sized> Feed for &T {
    fn feed(&self, h: &mut Sha256) {
        (**self).feed(h);
    }
}

impl Feed for Camera {
    fn feed(&self, h: &mut Sha256) {
        let Camera {
            position,
            look_at,
            up,
            fov_deg,
            width,
            height,
            projection,
        } = self;
        position.feed(h);
        look_at.feed(h);
        up.feed(h);
        fov_deg.feed(h);
        width.feed(h);
        height.feed(h);
        match *projection {
            Projection::Pinhole => tag(h, 0),
            Projection::ThinLens {
                aperture_radius,
                focus_distance,
            } => {
                tag(h, 1);
                aperture_radius.feed(h);
                focus_distance.feed(h);
            }
            Projection::Orthographic {
                half_width,
                half_height,
            } => {
                tag(h, 2);
                half_width.feed(h);
                half_height.feed(h);
            }
            Projection::Shifted {
                shift_x,
                shift_y,
                aperture_radius,
                focus_distance,
            } => {
                tag(h, 3);
                shift_x.feed(h);
                shift_y.feed(h);
                aperture_radius.feed(h);
                focus_distance.feed(h);
            }
        }
    }
}

impl<T: Feed> Feed for Param<T> {
    fn feed(&self, h: &mut Sha256) {
        match self {
            Param::Const(x) => {
                tag(h, 0);
                x.feed(h);
            }
            Param::Texture(t) => {
                tag(h, 1);
                t.0.feed(h);
            }
        }
    }
}

impl Feed for Texture {
    fn feed(&self, h: &mut Sha256) {
        match self {
            Texture::Bitmap(b) => {
                tag(h, 0);
                b.feed(h);
            }
            Texture::Checkerboard {
                color0,
                color1,
                to_uv,
            } => {
                tag(h, 1);
                color0.feed(h);
                color1.feed(h);
                to_uv.feed(h);
            }
            Texture::MeshAttribute { name } => {
                tag(h, 2);
                name.feed(h);
            }
            Texture::Constant { value } => {
                tag(h, 3);
                value.feed(h);
            }
        }
    }
}

impl Feed for Bitmap {
    fn feed(&self, h: &mut Sha256) {
        let Bitmap {
            filename,
            image,
            raw,
            filter,
            wrap,
            to_uv,
        } = self;
        filename.to_string_lossy().feed(h);
        image.as_ref().feed(h);
        raw.feed(h);
        tag(
            h,
            match filter {
                FilterType::Nearest => 0,
                FilterType::Bilinear => 1,
            },
        );
        tag(
            h,
            match wrap {
                WrapMode::Repeat => 0,
                WrapMode::Mirror => 1,
                WrapMode::Clamp => 2,
            },
        );
        to_uv.feed(h);
    }
}

impl Feed for EnvironmentMap {
    fn feed(&self, h: &mut Sha256) {
        let EnvironmentMap {
            filename,
            image,
            scale,
            to_world,
        } = self;
        filename.to_string_lossy().feed(h);
        image.as_ref().feed(h);
        scale.feed(h);
        to_world.to_cols_array().feed(h);
    }
}

impl Feed for Image {
    fn feed(&self, h: &mut Sha256) {
        let Image {
            width,
            height,
            texels,
        } = self;
        width.feed(h);
        height.feed(h);
        texels.feed(h);
    }
}

impl Feed for std::borrow::Cow<'_, str> {
    fn feed(&self, h: &mut Sha256) {
        self.as_ref().feed(h);
    }
}

impl Feed for Mesh {
    fn feed(&self, h: &mut Sha256) {
        let Mesh {
            name,
            positions,
            indices,
            normals,
            uvs,
            colors,
            face_colors,
        } = self;
        name.feed(h);
        positions.feed(h);
        indices.feed(h);
        normals.feed(h);
        uvs.feed(h);
        colors.feed(h);
        if !face_colors.is_empty() {
            tag(h, 0xFC);
            face_colors.feed(h);
        }
    }
}

impl Feed for Instance {
    fn feed(&self, h: &mut Sha256) {
        let Instance {
            mesh,
            material,
            to_world: Transform { matrix },
        } = self;
        mesh.0.feed(h);
        material.map(|m| m.0).feed(h);
        matrix.feed(h);
    }
}

impl Feed for RenderDefaults {
    fn feed(&self, h: &mut Sha256) {
        let RenderDefaults {
            spp,
            max_depth,
            rr_depth,
            seed,
            filter,
        } = self;
        spp.feed(h);
        max_depth.feed(h);
        rr_depth.feed(h);
        seed.feed(h);
        filter.feed(h);
    }
}

impl Feed for PixelFilter {
    fn feed(&self, h: &mut Sha256) {
        match *self {
            PixelFilter::Box => tag(h, 0),
            PixelFilter::Tent { radius } => {
                tag(h, 1);
                radius.feed(h);
            }
            PixelFilter::Gaussian { stddev, radius } => {
                tag(h, 2);
                stddev.feed(h);
                radius.feed(h);
            }
        }
    }
}

impl Feed for CameraPath {
    fn feed(&self, h: &mut Sha256) {
        let CameraPath { fps, keyframes } = self;
        fps.feed(h);
        keyframes.feed(h);
    }
}

impl Feed for Keyframe {
    fn feed(&self, h: &mut Sha256) {
        let Keyframe {
            time,
            position,
            orientation,
            fov_deg,
        } = self;
        time.feed(h);
        position.feed(h);
        match orientation {
            Orientation::LookAt { look_at, up } => {
                tag(h, 0);
                look_at.feed(h);
                up.feed(h);
            }
            Orientation::YawPitch { yaw_deg, pitch_deg } => {
                tag(h, 1);
                yaw_deg.feed(h);
                pitch_deg.feed(h);
            }
        }
        fov_deg.feed(h);
    }
}
