"""Builds a small two-room walkthrough in Blender, exports it to glTF and dumps Blender's own
camera poses, so that eyeadapt's reading of the file can be checked against Blender.

    python scripts/blender/walkthrough.py OUT_DIR [--frames N]

Writes OUT_DIR/walkthrough.glb and OUT_DIR/blender_camera.json: the scene's fps and, for every
frame, the camera's `matrix_world` evaluated by Blender, turned into glTF's +Y-up axes
(x, y, z)_gltf = (x, z, -y)_blender, with position, forward (the camera's -Z) and up (+Y).

The rooms: two 4 m x 4 m x 3 m boxes side by side along +x with a doorway between them, a point
light in the first, a spot and an emissive ceiling panel (the area-like emitter) in the second.
The camera is keyframed with Blender's default Bezier interpolation and turns by 210 degrees
about the vertical while it walks through the doorway. Run with Blender's Python module (bpy).
"""
import json
import math
import sys
from pathlib import Path

import bpy  # first: bmesh and mathutils are importable only once bpy is loaded
import bmesh
from mathutils import Vector


def material(name, rgb, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (*rgb, 1.0)
    p.inputs["Roughness"].default_value = 1.0
    p.inputs["Metallic"].default_value = 0.0
    if emission is not None:
        p.inputs["Emission Color"].default_value = (*emission, 1.0)
        p.inputs["Emission Strength"].default_value = strength
    return m


def box_room(name, x0, mat, door=False):
    """An inward-facing box x0..x0+4, 0..4, 0..3; with `door`, its +x wall has a 1 m x 2 m hole."""
    bm = bmesh.new()
    x1 = x0 + 4.0
    quads = [
        [(x0, 0, 0), (x1, 0, 0), (x1, 4, 0), (x0, 4, 0)],  # floor
        [(x0, 0, 3), (x0, 4, 3), (x1, 4, 3), (x1, 0, 3)],  # ceiling
        [(x0, 0, 0), (x0, 0, 3), (x1, 0, 3), (x1, 0, 0)],
        [(x0, 4, 0), (x1, 4, 0), (x1, 4, 3), (x0, 4, 3)],
        [(x0, 0, 0), (x0, 4, 0), (x0, 4, 3), (x0, 0, 3)],
    ]
    if door:
        # The shared wall at x1 with a doorway y in [1.5, 2.5], z in [0, 2].
        quads += [
            [(x1, 0, 0), (x1, 0, 3), (x1, 1.5, 3), (x1, 1.5, 0)],
            [(x1, 2.5, 0), (x1, 2.5, 3), (x1, 4, 3), (x1, 4, 0)],
            [(x1, 1.5, 2), (x1, 1.5, 3), (x1, 2.5, 3), (x1, 2.5, 2)],
        ]
    else:
        quads.append([(x1, 0, 0), (x1, 4, 0), (x1, 4, 3), (x1, 0, 3)])
    for q in quads:
        bm.faces.new([bm.verts.new(v) for v in q])
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(mat)
    bpy.context.collection.objects.link(obj)
    return obj


def build(frames):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 24
    scene.frame_start = 0
    scene.frame_end = frames - 1
    box_room("RoomA", 0.0, material("WhiteWalls", (0.8, 0.8, 0.8)), door=True)
    # Room B is the second box; its -x wall would close the doorway, so it has none: build it
    # from the same helper shifted by 4 m, then delete that wall's face.
    b = box_room("RoomB", 4.0, material("WarmWalls", (0.8, 0.6, 0.4)))
    bm = bmesh.new()
    bm.from_mesh(b.data)
    bm.faces.ensure_lookup_table()
    gone = [f for f in bm.faces if all(abs(v.co.x - 4.0) < 1e-6 for v in f.verts)]
    bmesh.ops.delete(bm, geom=gone, context="FACES")
    bm.to_mesh(b.data)
    bm.free()
    panel = bmesh.new()
    panel.faces.new(
        [panel.verts.new(v) for v in [(6.0, 1.5, 2.95), (6.0, 2.5, 2.95), (7.0, 2.5, 2.95), (7.0, 1.5, 2.95)]]
    )
    pm = bpy.data.meshes.new("Panel")
    panel.to_mesh(pm)
    panel.free()
    po = bpy.data.objects.new("Panel", pm)
    po.data.materials.append(material("PanelLight", (0.0, 0.0, 0.0), (1.0, 0.9, 0.8), 5.0))
    bpy.context.collection.objects.link(po)

    for name, kind, loc, power in [
        ("PointA", "POINT", (2.0, 2.0, 2.5), 150.0),
        ("SpotB", "SPOT", (5.0, 3.5, 2.8), 300.0),
    ]:
        light = bpy.data.lights.new(name, kind)
        light.energy = power
        light.shadow_soft_size = 0.0
        if kind == "SPOT":
            light.spot_size = math.radians(50.0)
            light.spot_blend = 0.2
        lo = bpy.data.objects.new(name, light)
        lo.location = loc
        if kind == "SPOT":
            lo.rotation_euler = (math.radians(40.0), 0.0, math.radians(-120.0))
        bpy.context.collection.objects.link(lo)

    cam_data = bpy.data.cameras.new("Eye")
    cam_data.lens_unit = "FOV"
    cam_data.angle = math.radians(60.0)
    cam_data.sensor_fit = "VERTICAL"
    cam = bpy.data.objects.new("Eye", cam_data)
    bpy.context.collection.objects.link(cam)
    scene.camera = cam
    cam.rotation_mode = "XYZ"
    keys = [
        (0, (1.0, 2.0, 1.6), 0.0),
        (frames // 3, (3.0, 2.2, 1.6), 60.0),
        (2 * frames // 3, (5.0, 1.8, 1.7), 150.0),
        (frames - 1, (6.5, 2.0, 1.6), 210.0),
    ]
    for f, loc, yaw in keys:
        cam.location = loc
        # Blender cameras look down -Z: pitch 90 degrees about X looks along +Y, and the yaw
        # about Z turns the gaze; -90 first turns it to look along +x, down the walkthrough.
        cam.rotation_euler = (math.radians(88.0), 0.0, math.radians(-90.0 + yaw))
        cam.keyframe_insert("location", frame=f)
        cam.keyframe_insert("rotation_euler", frame=f)
    return scene, cam


def to_gltf(v):
    return [v.x, v.z, -v.y]


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    out = Path(args[0])
    frames = int(args[args.index("--frames") + 1]) if "--frames" in args else 48
    out.mkdir(parents=True, exist_ok=True)
    scene, cam = build(frames)
    poses = []
    for f in range(scene.frame_start, scene.frame_end + 1):
        scene.frame_set(f)
        m = cam.matrix_world
        rot = m.to_3x3()
        poses.append(
            {
                "frame": f,
                "position": to_gltf(m.translation),
                "forward": to_gltf((rot @ Vector((0, 0, -1))).normalized()),
                "up": to_gltf((rot @ Vector((0, 1, 0))).normalized()),
            }
        )
    scene.frame_set(scene.frame_start)
    bpy.ops.export_scene.gltf(
        filepath=str(out / "walkthrough.glb"),
        export_format="GLB",
        export_yup=True,
        export_cameras=True,
        export_lights=True,
        export_animations=True,
        export_apply=True,
    )
    fps = scene.render.fps / scene.render.fps_base
    yfov = cam.data.angle_y
    (out / "blender_camera.json").write_text(
        json.dumps({"fps": fps, "yfov_deg": math.degrees(yfov), "poses": poses}, indent=1)
    )


main()
