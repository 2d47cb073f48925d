//! Reading the node hierarchy and an animation's channels into a [`NodeTree`].
//!
//! Which animation plays: a job may name one (`animation = "CameraAction"`); without a name
//! every animation of the file plays at once on the same clock, as Blender plays the actions
//! it exports as separate animations (camera, door, lamp). A node property driven by two of
//! them is ambiguous and an error that asks for a name.
use super::nodes::{Node, NodeTracks, NodeTree, Rest};
use super::read::{GltfFile, at};
use super::track::{Interpolation, Track, TrackValue};
use crate::Diagnostic;
use glam::{DMat4, DQuat, DVec3};
use gltf::animation::util::ReadOutputs;

/// Longest animation accepted, in seconds (a year): beyond it frame counts at any sane frame
/// rate stop fitting in memory, and times lose sub-frame precision in f32.
pub const MAX_ANIMATION_SECONDS: f64 = 3.2e7;

/// Every node with its parent and rest transform, and the tracks of the chosen animation(s).
pub fn node_tree(f: &GltfFile, animation: Option<&str>) -> Result<NodeTree, Vec<Diagnostic>> {
    let mut nodes: Vec<Node> = f
        .document
        .nodes()
        .map(|n| Node {
            index: n.index(),
            name: n.name().map(str::to_string),
            parent: None,
            rest: rest(&n),
            tracks: NodeTracks::default(),
        })
        .collect();
    let mut errors = Vec::new();
    for n in f.document.nodes() {
        for c in n.children() {
            match nodes[c.index()].parent {
                Some(p) => errors.push(at(
                    &f.path,
                    &format!("/nodes/{}/children", n.index()),
                    format!(
                        "node {} already has parent {p}: a node has one parent",
                        c.index()
                    ),
                )),
                None => nodes[c.index()].parent = Some(n.index()),
            }
        }
    }
    if let Some(n) = cycle(&nodes) {
        errors.push(at(
            &f.path,
            &format!("/nodes/{n}/children"),
            "the node hierarchy has a cycle",
        ));
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let chosen: Vec<gltf::Animation> = match animation {
        Some(name) => {
            let found: Vec<_> = f
                .document
                .animations()
                .filter(|a| a.name() == Some(name) || format!("animations/{}", a.index()) == name)
                .collect();
            if found.is_empty() {
                let names: Vec<String> = f.document.animations().map(|a| label(&a)).collect();
                return Err(vec![at(
                    &f.path,
                    "/animations",
                    format!(
                        "no animation named \"{name}\" (the file has: {})",
                        if names.is_empty() {
                            "none".into()
                        } else {
                            names.join(", ")
                        }
                    ),
                )]);
            }
            found.into_iter().take(1).collect()
        }
        None => f.document.animations().collect(),
    };
    for a in &chosen {
        for ch in a.channels() {
            if let Err(e) = add_channel(f, &mut nodes, a, &ch, animation.is_none()) {
                errors.push(e);
            }
        }
    }
    if errors.is_empty() {
        Ok(NodeTree { nodes })
    } else {
        Err(errors)
    }
}

/// The animation's name, or `animations/N`.
pub fn label(a: &gltf::Animation) -> String {
    a.name()
        .map_or_else(|| format!("animations/{}", a.index()), str::to_string)
}

fn rest(n: &gltf::Node) -> Rest {
    match n.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            Rest::Matrix(DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from))))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => Rest::Trs {
            translation: DVec3::from_array(translation.map(f64::from)),
            rotation: quat(rotation),
            scale: DVec3::from_array(scale.map(f64::from)),
        },
    }
}

fn quat(q: [f32; 4]) -> DQuat {
    let [x, y, z, w] = q.map(f64::from);
    DQuat::from_xyzw(x, y, z, w).normalize()
}

/// A node that is its own ancestor, if any.
fn cycle(nodes: &[Node]) -> Option<usize> {
    (0..nodes.len()).find(|&start| {
        let mut at = nodes[start].parent;
        for _ in 0..nodes.len() {
            match at {
                Some(p) if p == start => return true,
                Some(p) => at = nodes[p].parent,
                None => return false,
            }
        }
        true
    })
}

fn add_channel(
    f: &GltfFile,
    nodes: &mut [Node],
    a: &gltf::Animation,
    ch: &gltf::animation::Channel,
    all_play: bool,
) -> Result<(), Diagnostic> {
    let here = format!("/animations/{}/channels/{}", a.index(), ch.index());
    let node = ch.target().node().index();
    if matches!(nodes[node].rest, Rest::Matrix(_)) {
        return Err(at(
            &f.path,
            &format!("{here}/target/node"),
            format!("node {node} is given by a matrix, which glTF forbids animating"),
        ));
    }
    let reader = ch.reader(|b| f.buffers.get(b.index()).map(|d| &d.0[..]));
    let sampler_at = format!(
        "/animations/{}/samplers/{}",
        a.index(),
        ch.sampler().index()
    );
    let times: Vec<f64> = reader
        .read_inputs()
        .ok_or_else(|| at(&f.path, &format!("{sampler_at}/input"), "no keyframe times"))?
        .map(f64::from)
        .collect();
    check_times(&times).map_err(|m| at(&f.path, &format!("{sampler_at}/input"), m))?;
    let interpolation = match ch.sampler().interpolation() {
        gltf::animation::Interpolation::Linear => Interpolation::Linear,
        gltf::animation::Interpolation::Step => Interpolation::Step,
        gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
    };
    let outputs = reader.read_outputs().ok_or_else(|| {
        at(
            &f.path,
            &format!("{sampler_at}/output"),
            "no keyframe values",
        )
    })?;
    let tracks = &mut nodes[node].tracks;
    let clash = |what: &str| {
        at(
            &f.path,
            &format!("{here}/target"),
            format!(
                "node {node}'s {what} is animated by more than one animation; choose one with \
                 `animation = \"NAME\"` in the job"
            ),
        )
    };
    let bad_output = |m: String| at(&f.path, &format!("{sampler_at}/output"), m);
    match outputs {
        ReadOutputs::Translations(v) => {
            let values = v.map(|x| DVec3::from_array(x.map(f64::from))).collect();
            let t = track(times, values, interpolation).map_err(bad_output)?;
            set(&mut tracks.translation, t, all_play).map_err(|()| clash("translation"))
        }
        ReadOutputs::Scales(v) => {
            let values = v.map(|x| DVec3::from_array(x.map(f64::from))).collect();
            let t = track(times, values, interpolation).map_err(bad_output)?;
            set(&mut tracks.scale, t, all_play).map_err(|()| clash("scale"))
        }
        ReadOutputs::Rotations(r) => {
            let values = r.into_f32().map(quat_raw).collect();
            let t = track(times, values, interpolation).map_err(bad_output)?;
            set(&mut tracks.rotation, t, all_play).map_err(|()| clash("rotation"))
        }
        // Morph-target weights deform meshes, which rigid rendering does not; the channel is
        // ignored like any animation of a property eyeadapt does not render.
        ReadOutputs::MorphTargetWeights(_) => Ok(()),
    }
}

/// Spline tangents are not unit quaternions, so only keyframe values of LINEAR/STEP tracks
/// may be normalised; the spline result is normalised after evaluation.
fn quat_raw(q: [f32; 4]) -> DQuat {
    let [x, y, z, w] = q.map(f64::from);
    DQuat::from_xyzw(x, y, z, w)
}

fn set<T>(slot: &mut Option<T>, value: T, all_play: bool) -> Result<(), ()> {
    if slot.is_some() && all_play {
        return Err(());
    }
    *slot = Some(value);
    Ok(())
}

fn check_times(times: &[f64]) -> Result<(), String> {
    if times.is_empty() {
        return Err("no keyframe times".into());
    }
    if let Some(t) = times.iter().find(|t| !t.is_finite() || **t < 0.0) {
        return Err(format!("keyframe time {t} is not a finite time ≥ 0"));
    }
    if let Some(w) = times.windows(2).find(|w| w[1] <= w[0]) {
        return Err(format!(
            "keyframe times must increase strictly ({} then {})",
            w[0], w[1]
        ));
    }
    if times[times.len() - 1] > MAX_ANIMATION_SECONDS {
        return Err(format!(
            "the animation lasts {} s, more than the {MAX_ANIMATION_SECONDS} s accepted",
            times[times.len() - 1]
        ));
    }
    Ok(())
}

fn track<T: TrackValue + NonFinite>(
    times: Vec<f64>,
    mut values: Vec<T>,
    interpolation: Interpolation,
) -> Result<Track<T>, String> {
    let per_key = if interpolation == Interpolation::CubicSpline {
        3
    } else {
        1
    };
    if values.len() != times.len() * per_key {
        return Err(format!(
            "{} values for {} keyframe times ({per_key} per keyframe expected)",
            values.len(),
            times.len()
        ));
    }
    if values.iter().any(|v| v.non_finite()) {
        return Err("a keyframe value is not finite".into());
    }
    if per_key == 1 {
        values.iter_mut().for_each(|v| *v = v.finish());
    }
    Ok(Track {
        times,
        values,
        interpolation,
    })
}

trait NonFinite {
    fn non_finite(&self) -> bool;
}

impl NonFinite for DVec3 {
    fn non_finite(&self) -> bool {
        !self.is_finite()
    }
}

impl NonFinite for DQuat {
    fn non_finite(&self) -> bool {
        !self.is_finite()
    }
}
