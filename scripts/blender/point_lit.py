"""A closed grey room lit by one Blender point light: exported to glTF and rendered by Cycles,
so that eyeadapt's reading of Blender's light units can be checked against Cycles.

    python scripts/blender/point_lit.py OUT_DIR [--size W H] [--spp N] [--bounces B]

Writes OUT_DIR/point_lit.glb and OUT_DIR/cycles.exr (linear Rec.709, the "Standard" view, no
exposure: the raw radiance Cycles computes). Cycles is set up to compute what eyeadapt does:
`--bounces B` bounces (eyeadapt's max_depth = B + 2), no clamping, no light threshold, no
caustic filtering, a near-box pixel filter, and a true point light (radius 0).
"""
import sys
from pathlib import Path

import bpy  # first: bmesh is importable only once bpy is loaded
import bmesh


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    out = Path(args[0])
    opt = lambda name, n, default: (
        [type(d)(a) for d, a in zip(default, args[args.index(name) + 1 : args.index(name) + 1 + n])]
        if name in args
        else default
    )
    width, height = opt("--size", 2, [64, 36])
    (spp,) = opt("--spp", 1, [256])
    (bounces,) = opt("--bounces", 1, [14])
    out.mkdir(parents=True, exist_ok=True)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    grey = bpy.data.materials.new("Grey")
    grey.use_nodes = True
    p = grey.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (0.5, 0.45, 0.4, 1.0)
    p.inputs["Roughness"].default_value = 1.0
    p.inputs["Metallic"].default_value = 0.0
    p.inputs["Specular IOR Level"].default_value = 0.0  # a pure Lambertian, as glTF roughness 1 reads

    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.reverse_faces(bm, faces=bm.faces)  # normals inwards: a room
    mesh = bpy.data.meshes.new("Room")
    bm.to_mesh(mesh)
    bm.free()
    room = bpy.data.objects.new("Room", mesh)
    room.scale = (4.0, 4.0, 3.0)
    room.location = (0.0, 0.0, 1.5)
    room.data.materials.append(grey)
    bpy.context.collection.objects.link(room)

    light = bpy.data.lights.new("Bulb", "POINT")
    light.energy = 100.0
    light.shadow_soft_size = 0.0
    lo = bpy.data.objects.new("Bulb", light)
    lo.location = (0.5, 0.3, 2.2)
    bpy.context.collection.objects.link(lo)

    cam_data = bpy.data.cameras.new("View")
    cam_data.sensor_fit = "VERTICAL"
    cam = bpy.data.objects.new("View", cam_data)
    cam.location = (-1.5, -1.5, 1.4)
    cam.rotation_euler = (1.45, 0.0, -0.8)
    bpy.context.collection.objects.link(cam)
    scene.camera = cam

    bpy.ops.export_scene.gltf(
        filepath=str(out / "point_lit.glb"),
        export_format="GLB",
        export_yup=True,
        export_cameras=True,
        export_lights=True,
    )

    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = bounces
    c.diffuse_bounces = bounces
    c.glossy_bounces = bounces
    c.transmission_bounces = bounces
    c.transparent_max_bounces = bounces
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.filter_width = 0.01
    c.seed = 1
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.world = bpy.data.worlds.new("Black")
    scene.world.use_nodes = True
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = str(out / "cycles.exr")
    bpy.ops.render.render(write_still=True)


main()
