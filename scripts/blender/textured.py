"""A closed grey room with an image-textured floor, lit by one Blender point light: exported to
glTF and rendered by Cycles, so that eyeadapt's reading of glTF base colour textures (sRGB
decoding, UV orientation, the sampler) can be checked against Cycles block by block.

    python scripts/blender/textured.py OUT_DIR [--size W H] [--spp N] [--bounces B]

The floor's texture is a 4 x 4 board of sixteen different colours, so that a flipped or
mirrored UV, a missed sRGB decoding or a wrong texel would move colour between image blocks.
Writes OUT_DIR/textured.glb (the PNG embedded) and OUT_DIR/cycles.exr (linear Rec.709, the
"Standard" view). Cycles is set up as in point_lit.py: `--bounces B` bounces (eyeadapt's
max_depth = B + 2), no clamping, a near-box pixel filter, a true point light, closest-texel
lookups on both sides (the glTF sampler says NEAREST).
"""
import sys
from pathlib import Path

import bpy  # first: bmesh is importable only once bpy is loaded
import bmesh

# Sixteen distinct sRGB byte colours, row by row from the image's top row.
BOARD = [
    (230, 40, 40), (40, 200, 60), (50, 70, 220), (240, 220, 60),
    (200, 60, 200), (60, 210, 210), (250, 140, 30), (120, 120, 120),
    (30, 30, 30), (250, 250, 250), (140, 60, 20), (90, 160, 40),
    (20, 90, 140), (220, 150, 170), (160, 200, 240), (100, 40, 120),
]


def board_image(path):
    n = 4
    img = bpy.data.images.new("Board", width=n, height=n, alpha=False)
    px = []
    # Blender's pixel rows run from the bottom of the image up.
    for row in reversed(range(n)):
        for col in range(n):
            r, g, b = BOARD[row * n + col]
            px += [r / 255.0, g / 255.0, b / 255.0, 1.0]
    img.pixels = px
    img.filepath_raw = str(path)
    img.file_format = "PNG"
    img.save()
    return img


def diffuse(name, colour):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = colour
    p.inputs["Roughness"].default_value = 1.0
    p.inputs["Metallic"].default_value = 0.0
    p.inputs["Specular IOR Level"].default_value = 0.0  # a pure Lambertian, as glTF roughness 1 reads
    return m


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
    grey = diffuse("Grey", (0.5, 0.45, 0.4, 1.0))

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

    floor_mat = diffuse("Board", (1.0, 1.0, 1.0, 1.0))
    nodes = floor_mat.node_tree.nodes
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = board_image(out / "board.png")
    tex.interpolation = "Closest"
    tex.extension = "REPEAT"
    floor_mat.node_tree.links.new(tex.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])

    bm = bmesh.new()
    bm.loops.layers.uv.new("UVMap")
    bmesh.ops.create_grid(bm, x_segments=1, y_segments=1, size=1.0, calc_uvs=True)
    mesh = bpy.data.meshes.new("Floor")
    bm.to_mesh(mesh)
    bm.free()
    floor = bpy.data.objects.new("Floor", mesh)
    floor.scale = (1.5, 1.0, 1.0)  # not square: a transposed UV shows
    floor.location = (0.2, 0.1, 0.01)
    floor.data.materials.append(floor_mat)
    bpy.context.collection.objects.link(floor)

    light = bpy.data.lights.new("Bulb", "POINT")
    light.energy = 150.0
    light.shadow_soft_size = 0.0
    lo = bpy.data.objects.new("Bulb", light)
    lo.location = (0.3, -0.4, 2.2)
    bpy.context.collection.objects.link(lo)

    cam_data = bpy.data.cameras.new("View")
    cam_data.sensor_fit = "VERTICAL"
    cam = bpy.data.objects.new("View", cam_data)
    cam.location = (0.2, -1.6, 2.2)
    cam.rotation_euler = (0.75, 0.0, 0.0)
    bpy.context.collection.objects.link(cam)
    scene.camera = cam

    bpy.ops.export_scene.gltf(
        filepath=str(out / "textured.glb"),
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
    for k in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
              "transparent_max_bounces"):
        setattr(c, k, bounces)
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
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
