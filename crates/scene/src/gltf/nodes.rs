//! The node hierarchy of a glTF scene and its transforms at any time of one animation.
//!
//! A node's local transform is `T · R · S` (glTF §3.5.3); a node given by a matrix cannot be
//! animated (the spec forbids animation channels on such nodes, and the reader refuses them)
//! and keeps its matrix. World transforms compose parents first: `world(n) = world(parent) ·
//! local(n)`. Everything is in double precision so that a camera deep in a hierarchy keeps
//! its pose to far better than the 1e-4 the Blender comparison asks for.
use crate::track::Track;
use glam::{DMat4, DQuat, DVec3};

/// A node's transform when no animation drives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rest {
    Matrix(DMat4),
    Trs {
        translation: DVec3,
        rotation: DQuat,
        scale: DVec3,
    },
}

/// The tracks of one animation that drive one node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeTracks {
    pub translation: Option<Track<DVec3>>,
    pub rotation: Option<Track<DQuat>>,
    pub scale: Option<Track<DVec3>>,
}

impl NodeTracks {
    pub fn is_empty(&self) -> bool {
        self.translation.is_none() && self.rotation.is_none() && self.scale.is_none()
    }

    /// First and last keyframe time over the node's tracks, if any.
    pub fn range(&self) -> Option<(f64, f64)> {
        let ranges = [
            self.translation.as_ref().map(Track::range),
            self.rotation.as_ref().map(Track::range),
            self.scale.as_ref().map(Track::range),
        ];
        ranges
            .into_iter()
            .flatten()
            .reduce(|(a0, a1), (b0, b1)| (a0.min(b0), a1.max(b1)))
    }
}

/// One node: its parent, its rest transform and the tracks of the chosen animation.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Index in the file's `nodes` array (for messages and JSON pointers).
    pub index: usize,
    pub name: Option<String>,
    pub parent: Option<usize>,
    pub rest: Rest,
    pub tracks: NodeTracks,
}

/// All nodes of the file, indexed as in the file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeTree {
    pub nodes: Vec<Node>,
}

impl Node {
    /// The local transform at time `t`: animated properties replace the rest ones.
    pub fn local(&self, t: f64) -> DMat4 {
        match self.rest {
            Rest::Matrix(m) => m,
            Rest::Trs {
                translation,
                rotation,
                scale,
            } => {
                let tr = &self.tracks;
                let translation = tr.translation.as_ref().map_or(translation, |k| k.sample(t));
                let rotation = tr.rotation.as_ref().map_or(rotation, |k| k.sample(t));
                let scale = tr.scale.as_ref().map_or(scale, |k| k.sample(t));
                DMat4::from_scale_rotation_translation(scale, rotation, translation)
            }
        }
    }
}

impl NodeTree {
    /// The node's transform to world space at time `t`.
    pub fn world(&self, node: usize, t: f64) -> DMat4 {
        let mut m = self.nodes[node].local(t);
        let mut at = self.nodes[node].parent;
        // The reader refuses cycles, so this walk ends at a root.
        while let Some(p) = at {
            m = self.nodes[p].local(t) * m;
            at = self.nodes[p].parent;
        }
        m
    }

    /// True when the node or one of its ancestors is animated.
    pub fn is_animated(&self, node: usize) -> bool {
        self.chain(node).any(|n| !self.nodes[n].tracks.is_empty())
    }

    /// First and last keyframe time over the node and its ancestors, if any is animated.
    pub fn animation_range(&self, node: usize) -> Option<(f64, f64)> {
        self.chain(node)
            .filter_map(|n| self.nodes[n].tracks.range())
            .reduce(|(a0, a1), (b0, b1)| (a0.min(b0), a1.max(b1)))
    }

    /// First and last keyframe time over every node's tracks, if anything is animated.
    pub fn range(&self) -> Option<(f64, f64)> {
        self.nodes
            .iter()
            .filter_map(|n| n.tracks.range())
            .reduce(|(a0, a1), (b0, b1)| (a0.min(b0), a1.max(b1)))
    }

    /// The node, its parent, its grandparent … up to the root.
    fn chain(&self, node: usize) -> impl Iterator<Item = usize> + '_ {
        std::iter::successors(Some(node), |&n| self.nodes[n].parent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::Interpolation;

    fn trs(translation: DVec3, rotation: DQuat) -> Rest {
        Rest::Trs {
            translation,
            rotation,
            scale: DVec3::ONE,
        }
    }

    #[test]
    fn world_transform_composes_parents_first() {
        // Parent turned 90° about +y and moved to x = 10; child 1 unit along the parent's +z.
        let parent = Node {
            index: 0,
            name: None,
            parent: None,
            rest: trs(
                DVec3::new(10.0, 0.0, 0.0),
                DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
            ),
            tracks: NodeTracks::default(),
        };
        let child = Node {
            index: 1,
            name: None,
            parent: Some(0),
            rest: trs(DVec3::new(0.0, 0.0, 1.0), DQuat::IDENTITY),
            tracks: NodeTracks::default(),
        };
        let tree = NodeTree {
            nodes: vec![parent, child],
        };
        let p = tree.world(1, 0.0).transform_point3(DVec3::ZERO);
        // Rotating +z by 90° about +y gives +x.
        assert!((p - DVec3::new(11.0, 0.0, 0.0)).length() < 1e-12, "{p}");
        assert!(!tree.is_animated(1));
        assert_eq!(tree.animation_range(1), None);
    }

    #[test]
    fn an_animated_parent_moves_its_child() {
        let mut tree = NodeTree {
            nodes: vec![
                Node {
                    index: 0,
                    name: None,
                    parent: None,
                    rest: trs(DVec3::ZERO, DQuat::IDENTITY),
                    tracks: NodeTracks {
                        translation: Some(Track {
                            times: vec![0.0, 2.0],
                            values: vec![DVec3::ZERO, DVec3::new(0.0, 4.0, 0.0)],
                            interpolation: Interpolation::Linear,
                        }),
                        ..NodeTracks::default()
                    },
                },
                Node {
                    index: 1,
                    name: None,
                    parent: Some(0),
                    rest: trs(DVec3::X, DQuat::IDENTITY),
                    tracks: NodeTracks::default(),
                },
            ],
        };
        let p = tree.world(1, 0.5).transform_point3(DVec3::ZERO);
        assert!((p - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12, "{p}");
        assert!(tree.is_animated(1));
        assert_eq!(tree.animation_range(1), Some((0.0, 2.0)));
        tree.nodes[0].tracks = NodeTracks::default();
        assert!(!tree.is_animated(1));
    }
}
