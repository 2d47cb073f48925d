"""The scenes of the benchmark suite (suite.py) and how each is given to both renderers.

Each scene is a pair: what eyeadapt renders and the Mitsuba XML Mitsuba renders (made into
parameters by bench_xml.patch), with the max depth both get.

  cbox         mitsuba-data scenes/cbox/cbox-rgb.xml, for both (its max_depth, 6)
  matpreview   mitsuba-data scenes/matpreview/matpreview.xml, for both (its max_depth, -1:
               unlimited, Russian roulette from depth 5); envmap, smooth plastic, checkerboard
  interior     builtin:interior (scenes/interior/scene.toml) WITHOUT its two window panes, for
               both: eyeadapt renders that TOML (toml_to_mitsuba.toml_without), Mitsuba its
               conversion (toml_to_mitsuba.convert). Why without: eyeadapt's shadow rays pass
               thin panes with their transmittance, so the sun lights the room through the
               glazed windows; Mitsuba's `path` integrator, like any unidirectional path
               tracer without that rule, cannot light a surface with a delta light through a
               delta surface (the shadow ray is blocked, a BSDF sample never hits the sun), so
               with the panes its room has no sunlight at all (16-50 % darker means). Open
               windows are the nearest scene both render alike.
  three-rooms  builtin:three-rooms for eyeadapt, its conversion for Mitsuba (max_depth 8)
  1M triangles make_big_mesh.py's displaced sphere in a room (1 046 528 triangles, PLY), the
               same XML for both; generated into the cache directory
  many lights  make_many_lights.py's nine rooms lit by 27 ceiling lamps (eyeadapt's light tree;
               Mitsuba chooses lamps by its default rule), TOML for eyeadapt, its conversion for
               Mitsuba; generated into the cache directory
"""
import hashlib
import os
import subprocess
import sys
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import toml_to_mitsuba  # noqa: E402


@dataclass
class BenchScene:
    name: str
    eyeadapt: str  # the scene argument of `eyeadapt render`
    mitsuba: str  # Mitsuba XML (unpatched)
    max_depth: int
    inputs: list = field(default_factory=list)  # files whose content keys the reference
    note: str = ""


def sha_of(*paths):
    h = hashlib.sha256()
    for p in paths:
        with open(p, "rb") as f:
            h.update(f.read())
    return h.hexdigest()[:16]


def builtin_toml(name):
    return os.path.join(REPO, "scenes", name, "scene.toml")


def write_if_changed(path, text):
    if not os.path.exists(path) or open(path).read() != text:
        with open(path, "w") as f:
            f.write(text)


def prepare(data_dir, work, python):
    """The suite's scenes, writing the generated ones into `work` (a cache directory)."""
    os.makedirs(work, exist_ok=True)
    cbox = os.path.join(data_dir, "scenes", "cbox", "cbox-rgb.xml")
    mat = os.path.join(data_dir, "scenes", "matpreview", "matpreview.xml")
    for p in (cbox, mat):
        if not os.path.exists(p):
            raise SystemExit(f"{p}: not found (is {data_dir} a mitsuba-data checkout?)")
    frags = os.path.join(data_dir, "scenes", "cbox", "fragments")
    meshes = os.path.join(data_dir, "scenes", "cbox", "meshes")
    cbox_inputs = [cbox] + [os.path.join(frags, f) for f in sorted(os.listdir(frags))] + [
        os.path.join(meshes, f) for f in sorted(os.listdir(meshes))]
    mat_dir = os.path.dirname(mat)
    mat_inputs = [os.path.join(mat_dir, f) for f in sorted(os.listdir(mat_dir))]

    interior = builtin_toml("interior")
    open_toml = os.path.join(work, "interior-open-windows.toml")
    open_xml = os.path.join(work, "interior-open-windows.xml")
    write_if_changed(open_toml, toml_to_mitsuba.toml_without(interior, ("pane",)))
    write_if_changed(open_xml, toml_to_mitsuba.convert(interior, ("pane",))[0])
    idir = os.path.dirname(interior)
    interior_inputs = [open_toml, open_xml] + [os.path.join(idir, f) for f in ("sky.png", "planks.png")]

    rooms_xml = os.path.join(work, "three-rooms.xml")
    write_if_changed(rooms_xml, toml_to_mitsuba.convert(builtin_toml("three-rooms"))[0])

    gen = os.path.join(HERE, "make_big_mesh.py")
    big_dir = os.path.join(work, "big-mesh-" + sha_of(gen))
    big_xml = os.path.join(big_dir, "big-mesh.xml")
    if not os.path.exists(big_xml):
        subprocess.run([python, gen, big_dir], check=True)
    many_gen = os.path.join(HERE, "make_many_lights.py")
    many_toml = os.path.join(work, "many-lights-" + sha_of(many_gen) + ".toml")
    many_xml = many_toml[:-len(".toml")] + ".xml"
    if not os.path.exists(many_toml):
        subprocess.run([python, many_gen, many_toml], check=True)
    write_if_changed(many_xml, toml_to_mitsuba.convert(many_toml)[0])
    return [
        BenchScene("cbox", cbox, cbox, 6, cbox_inputs, "mitsuba-data cbox-rgb.xml"),
        BenchScene("matpreview", mat, mat, -1, mat_inputs, "mitsuba-data matpreview.xml"),
        BenchScene("interior", open_toml, open_xml, 8, interior_inputs,
                   "builtin:interior without its 2 window panes (suite_scenes.py says why)"),
        BenchScene("three-rooms", "builtin:three-rooms", rooms_xml, 8,
                   [builtin_toml("three-rooms"), rooms_xml], "builtin:three-rooms"),
        BenchScene("1M triangles", big_xml, big_xml, 8,
                   [big_xml, os.path.join(big_dir, "big-mesh.ply")], "make_big_mesh.py, 1 046 528 triangles"),
        BenchScene("many lights", many_toml, many_xml, 8, [many_toml, many_xml],
                   "make_many_lights.py, 9 rooms, 27 lamps"),
    ]
