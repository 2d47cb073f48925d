//! The scene's geometry for ray queries, in two levels: an [`Accel`] per unique mesh in object
//! space and a [`WideBvh`] over the instances' world-space boxes (both obvhs's binary builds
//! collapsed to float eight-wide nodes, `collapse.rs`), so memory grows with the unique meshes,
//! not with the instances.
//! When no mesh is placed twice, every triangle is put into one world-space [`Accel`] instead
//! (the flat layout): nothing is shared then, and one traversal without per-instance ray
//! transforms is faster.
//!
//! Hits name the instance, the mesh's triangle and the barycentrics; [`Geometry::interaction`]
//! turns one into a [`SurfaceInteraction`].
use crate::accel::{Accel, InputTri, binary_bvh_of, build_params};
use crate::collapse::{Leaf, collapse};
use crate::emitter::AreaTri;
use crate::interaction::{Attributes, SurfaceInteraction};

mod query;
use crate::wide_bvh::WideBvh;
use crate::wide_walk::WalkStack;
use eyeadapt_scene::{MaterialId, Scene};
use glam::{Affine3A, Mat3A, Vec2, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::ray::Ray;
use rayon::prelude::*;

/// One instance as the tracer shades it.
struct InstanceData {
    /// Index into `Geometry::attributes` (and, in two levels, into the per-mesh structures).
    mesh: u32,
    material: u32,
    /// First entry of this instance in `Geometry::light_of`, or `u32::MAX` when not emissive.
    light_base: u32,
    to_object: Affine3A,
    to_world: Affine3A,
    /// Inverse transpose of `to_world`'s linear part (shading normals).
    normal_to_world: Mat3A,
    /// Sign of `to_world`'s determinant: a mirroring transform keeps the winding, so the
    /// geometric normal (the cross product of the world-space edges) flips.
    winding: f32,
}

enum Levels {
    /// Every triangle in world space, in one structure.
    Flat(Accel),
    /// Object-space structures per mesh under a structure over instances; `top_instance` maps
    /// a top-level slot to its instance.
    Two {
        top: WideBvh,
        top_instance: Vec<u32>,
        meshes: Vec<Accel>,
    },
}

pub struct Geometry {
    levels: Levels,
    instances: Vec<InstanceData>,
    /// Flat: per instance, baked to world space; two levels: per mesh, in object space.
    attributes: Vec<Attributes>,
    /// Area-light index of (instance light_base + triangle), `u32::MAX` for degenerate ones.
    light_of: Vec<u32>,
    /// Triangles skipped because they have no area.
    pub degenerate: usize,
    pub bounds_min: Vec3A,
    pub bounds_max: Vec3A,
    triangles: usize,
}

/// Per-ray traversal state, reused across the rays of a path.
pub struct RayScratch {
    top: WalkStack,
    bottom: WalkStack,
    /// The shadow ray's, while it is walked together with a path's next ray.
    shadow: WalkStack,
    /// The see-through surfaces a shadow ray crosses (`shadow.rs`).
    pub(crate) crossings: Vec<Hit>,
    /// A packet walk's stack ([`crate::packet`]).
    packet: crate::packet::PacketStack,
}

/// A ray's closest hit: distance, instance, the mesh's triangle and the BVH slot it sits in.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub instance: u32,
    pub prim: u32,
    slot: u32,
}

/// The scene's geometry and the emissive triangles of its emissive instances, in hit order.
pub struct Built {
    pub geometry: Geometry,
    pub area_lights: Vec<AreaTri>,
}

impl Geometry {
    /// Builds from the scene's instances; `material_index` maps a material to the tracer's
    /// table, `emission` gives a material-table entry's emitted radiance (zero: not a light)
    /// and `emission_texture` the texture multiplying it, with the texture's mean.
    pub fn build(
        scene: &Scene,
        material_index: impl Fn(Option<MaterialId>) -> u32,
        emission: impl Fn(u32) -> Vec3A,
        emission_texture: impl Fn(u32) -> Option<(u32, Vec3A)>,
    ) -> Built {
        let mut uses = vec![0u32; scene.meshes.len()];
        for inst in &scene.instances {
            uses[inst.mesh.0 as usize] += 1;
        }
        let flat = uses.iter().all(|&n| n <= 1);
        let mut instances = Vec::with_capacity(scene.instances.len());
        let mut light_of = Vec::new();
        let mut area_lights = Vec::new();
        for (i, inst) in scene.instances.iter().enumerate() {
            let mesh = scene.mesh(inst.mesh);
            let material = material_index(inst.material);
            let le = emission(material);
            let m = inst.to_world.matrix;
            let textured = emission_texture(material);
            let light_base = if le.max_element() > 0.0 {
                let base = light_of.len() as u32;
                for t in &mesh.indices {
                    let v = t.map(|k| Vec3A::from(m.transform_point3(mesh.positions[k as usize])));
                    let tri = AreaTri::new(v, le).map(|a| match textured {
                        None => a,
                        // The mesh's UVs, else the barycentrics (as hits read them).
                        Some((tex, mean)) => {
                            let uv = if mesh.uvs.is_empty() {
                                [Vec2::ZERO, Vec2::X, Vec2::Y]
                            } else {
                                t.map(|k| mesh.uvs[k as usize])
                            };
                            a.textured(tex, mean, uv)
                        }
                    });
                    light_of.push(match tri {
                        Some(a) => {
                            area_lights.push(a);
                            area_lights.len() as u32 - 1
                        }
                        None => u32::MAX,
                    });
                }
                base
            } else {
                u32::MAX
            };
            let to_world = if flat {
                Affine3A::IDENTITY
            } else {
                Affine3A::from_mat4(m)
            };
            let linear = to_world.matrix3;
            instances.push(InstanceData {
                mesh: if flat { i as u32 } else { inst.mesh.0 },
                material,
                light_base,
                to_object: to_world.inverse(),
                to_world,
                normal_to_world: linear.inverse().transpose(),
                winding: linear.determinant().signum(),
            });
        }
        let (levels, attributes) = if flat {
            flat_levels(scene)
        } else {
            two_levels(scene)
        };
        let (degenerate, bounds_min, bounds_max) = match &levels {
            Levels::Flat(a) => (a.degenerate, a.bounds_min, a.bounds_max),
            Levels::Two { meshes, .. } => {
                let mut lo = Vec3A::splat(f32::INFINITY);
                let mut hi = Vec3A::splat(f32::NEG_INFINITY);
                for (inst, i) in scene.instances.iter().zip(&instances) {
                    let a = &meshes[inst.mesh.0 as usize];
                    if a.triangle_count() > 0 {
                        let b = world_box(&i.to_world, a);
                        lo = lo.min(b.min);
                        hi = hi.max(b.max);
                    }
                }
                if lo.x > hi.x {
                    (lo, hi) = (Vec3A::ZERO, Vec3A::ZERO);
                }
                let degenerate = scene
                    .instances
                    .iter()
                    .map(|i| meshes[i.mesh.0 as usize].degenerate)
                    .sum();
                (degenerate, lo, hi)
            }
        };
        let triangles = scene.triangle_count() - degenerate;
        let geometry = Geometry {
            levels,
            instances,
            attributes,
            light_of,
            degenerate,
            bounds_min,
            bounds_max,
            triangles,
        };
        Built {
            geometry,
            area_lights,
        }
    }

    pub fn scratch(&self) -> RayScratch {
        RayScratch {
            top: WalkStack::default(),
            bottom: WalkStack::default(),
            shadow: WalkStack::default(),
            crossings: Vec::new(),
            packet: Default::default(),
        }
    }

    /// True when meshes are shared and rays are transformed into each instance.
    pub fn is_two_level(&self) -> bool {
        matches!(self.levels, Levels::Two { .. })
    }

    /// Triangles that can be hit, as placed (every instance counts its mesh's).
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// The materials of the placed instances (with repeats): what a ray can hit.
    pub fn materials_in_use(&self) -> impl Iterator<Item = u32> + '_ {
        self.instances.iter().map(|i| i.material)
    }

    /// The material at `hit` (the [`SurfaceInteraction::material`] of its interaction).
    #[inline]
    pub fn material_of(&self, hit: &Hit) -> u32 {
        self.instances[hit.instance as usize].material
    }

    /// The surface at `hit` of the ray from `origin` along `dir`: world-space position,
    /// geometric and shading normals, UV, ∂p/∂u, vertex colour, material and light. Without
    /// `parameterisation` (nothing in the scene reads them) UV, ∂p/∂u, ∂p/∂v and the colours
    /// are left zero.
    #[inline]
    pub fn interaction(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        hit: &Hit,
        parameterisation: bool,
    ) -> SurfaceInteraction {
        let inst = &self.instances[hit.instance as usize];
        let attr = &self.attributes[inst.mesh as usize];
        if !parameterisation && !attr.has_normals() {
            return self.flat_interaction(origin, dir, hit, inst);
        }
        let (accel, ray) = match &self.levels {
            Levels::Flat(a) => (a, Ray::new(origin, dir, 0.0, f32::INFINITY)),
            Levels::Two { meshes, .. } => {
                let world = Ray::new(origin, dir, 0.0, f32::INFINITY);
                (&meshes[inst.mesh as usize], object_ray(inst, &world))
            }
        };
        let bary = accel.barycentric(hit.slot, &ray);
        let ng_local = accel.info[hit.slot as usize].ng;
        let mut si = attr.interpolate(hit.prim, bary, accel.vertices(hit.slot), ng_local);
        if let Levels::Two { .. } = self.levels {
            si.ng = (inst.normal_to_world * si.ng * inst.winding).normalize();
            si.ns = (inst.normal_to_world * si.ns).normalize_or_zero();
            if si.ns == Vec3A::ZERO {
                si.ns = si.ng;
            }
            si.dpdu = inst.to_world.transform_vector3a(si.dpdu);
            si.dpdv = inst.to_world.transform_vector3a(si.dpdv);
        }
        si.t = hit.t;
        si.p = origin + dir * hit.t;
        si.instance = hit.instance;
        si.prim = hit.prim;
        si.material = inst.material;
        si.light = self.light_of_hit(inst, hit);
        si
    }

    /// [`Geometry::interaction`] of a triangle without vertex normals when nothing reads the
    /// parameterisation: the shading normal is the geometric one, no barycentrics are needed.
    #[inline]
    fn flat_interaction(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        hit: &Hit,
        inst: &InstanceData,
    ) -> SurfaceInteraction {
        // The normals exactly as `interpolate` and the transform in `interaction` give them.
        let (ng, ns) = match &self.levels {
            Levels::Flat(a) => {
                let ng = a.info[hit.slot as usize].ng;
                (ng, ng)
            }
            Levels::Two { meshes, .. } => {
                let n =
                    inst.normal_to_world * meshes[inst.mesh as usize].info[hit.slot as usize].ng;
                let ng = (n * inst.winding).normalize();
                let ns = n.normalize_or_zero();
                (ng, if ns == Vec3A::ZERO { ng } else { ns })
            }
        };
        SurfaceInteraction {
            t: hit.t,
            p: origin + dir * hit.t,
            ng,
            ns,
            instance: hit.instance,
            prim: hit.prim,
            material: inst.material,
            light: self.light_of_hit(inst, hit),
            ..SurfaceInteraction::default()
        }
    }

    #[inline]
    fn light_of_hit(&self, inst: &InstanceData, hit: &Hit) -> u32 {
        if inst.light_base == u32::MAX {
            u32::MAX
        } else {
            self.light_of[(inst.light_base + hit.prim) as usize]
        }
    }

    /// Approximate heap size: BVHs, triangles, per-vertex attributes and instance records.
    pub fn memory_bytes(&self) -> usize {
        let levels = match &self.levels {
            Levels::Flat(a) => a.memory_bytes(),
            Levels::Two {
                top,
                top_instance,
                meshes,
            } => {
                top.memory_bytes()
                    + top_instance.len() * 4
                    + meshes.iter().map(Accel::memory_bytes).sum::<usize>()
            }
        };
        levels
            + self
                .attributes
                .iter()
                .map(Attributes::memory_bytes)
                .sum::<usize>()
            + self.instances.len() * std::mem::size_of::<InstanceData>()
            + self.light_of.len() * 4
    }
}

/// The world ray `r` in the instance's object space; the direction is not renormalised, so
/// distances along it are the world ray's.
#[inline(always)]
fn object_ray(inst: &InstanceData, r: &Ray) -> Ray {
    Ray::new(
        inst.to_object.transform_point3a(r.origin),
        inst.to_object.transform_vector3a(r.direction),
        r.tmin,
        r.tmax,
    )
}

/// The world-space box of `a`'s bounds under `m`.
fn world_box(m: &Affine3A, a: &Accel) -> Aabb {
    let mut b = Aabb {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };
    for k in 0..8 {
        let pick = |bit: u32, lo: f32, hi: f32| if k & bit == 0 { lo } else { hi };
        let c = Vec3A::new(
            pick(1, a.bounds_min.x, a.bounds_max.x),
            pick(2, a.bounds_min.y, a.bounds_max.y),
            pick(4, a.bounds_min.z, a.bounds_max.z),
        );
        let w = m.transform_point3a(c);
        b.min = b.min.min(w);
        b.max = b.max.max(w);
    }
    b
}

/// Every instance's triangles and attributes baked to world space, in one structure.
fn flat_levels(scene: &Scene) -> (Levels, Vec<Attributes>) {
    let mut tris = Vec::with_capacity(scene.triangle_count());
    let mut attributes = Vec::with_capacity(scene.instances.len());
    for (i, inst) in scene.instances.iter().enumerate() {
        let mesh = scene.mesh(inst.mesh);
        let m = inst.to_world;
        // Side by side, in the mesh's order.
        tris.par_extend(
            mesh.indices
                .par_iter()
                .enumerate()
                .map(|(prim, t)| InputTri {
                    v: t.map(|k| Vec3A::from(m.point(mesh.positions[k as usize]))),
                    instance: i as u32,
                    prim: prim as u32,
                }),
        );
        attributes.push(Attributes::of(mesh, Some(&m)));
    }
    (Levels::Flat(Accel::build(&tris)), attributes)
}

/// One object-space structure per mesh, and the top level over the instances. The meshes'
/// structures are built side by side (each build is the same on any thread count, and
/// `collect` keeps the meshes' order, so the scene's bits do not depend on it).
fn two_levels(scene: &Scene) -> (Levels, Vec<Attributes>) {
    let meshes: Vec<Accel> = scene
        .meshes
        .par_iter()
        .map(|mesh| {
            let tris: Vec<InputTri> = mesh
                .indices
                .iter()
                .enumerate()
                .map(|(prim, t)| InputTri {
                    v: t.map(|k| Vec3A::from(mesh.positions[k as usize])),
                    instance: 0,
                    prim: prim as u32,
                })
                .collect();
            Accel::build(&tris)
        })
        .collect();
    let attributes = scene
        .meshes
        .iter()
        .map(|m| Attributes::of(m, None))
        .collect();
    let mut boxes = Vec::new();
    let mut ids = Vec::new();
    for (i, inst) in scene.instances.iter().enumerate() {
        let a = &meshes[inst.mesh.0 as usize];
        if a.triangle_count() > 0 {
            boxes.push(world_box(&Affine3A::from_mat4(inst.to_world.matrix), a));
            ids.push(i as u32);
        }
    }
    // One instance a leaf: an instance's test is a walk of its own.
    let top = binary_bvh_of(&boxes, build_params(boxes.len()));
    let (nodes, slots) = collapse(&top, Leaf::Single);
    let top_instance = slots.iter().map(|&k| ids[k as usize]).collect();
    (
        Levels::Two {
            top: WideBvh::from_nodes(nodes),
            top_instance,
            meshes,
        },
        attributes,
    )
}
