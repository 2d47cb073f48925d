#!/usr/bin/env python3
"""eyeadapt TOML scenes for Mitsuba 3: the subset the built-in walkthroughs use, as Mitsuba XML.

    python3 scripts/bench/toml_to_mitsuba.py scenes/interior/scene.toml OUT.xml [--drop-material pane]

Used by the benchmark suite (suite.py) to give the built-in interiors to Mitsuba. What it
writes follows docs/scene-format.md and docs/mitsuba.md:
  camera    perspective, fov_axis y (fov_deg is vertical), lookat; hdrfilm with a box filter
            (the TOML film's), pixel_format rgb; the sampler's type, sample count and the film
            size are the file's defaults, which suite.py replaces
  render    path integrator with the scene's max_depth and rr_depth
  materials every TOML surface reflects on both sides, so diffuse and plastic are wrapped in
            `twosided`; plastic is `roughplastic` (GGX, alpha = max(roughness, 0.01), as the
            TOML loader clamps it); dielectric and thin_dielectric have ext_ior 1 (the TOML's
            ior is interior over exterior); emission becomes an area emitter on each shape
  shapes    quad: `rectangle` whose to_world takes (-1, -1) to the corner and (1, -1) to
            corner + u, so UVs and the front side (u x v) are the TOML's; box: `cube`;
            sphere: Mitsuba's analytic `sphere` (eyeadapt tessellates it as an icosphere of
            20 * 4^subdivisions triangles: the surfaces differ by the facets' sagitta)
  textures  bitmap and checkerboard, to_uv = scale then translate (uv_scale, uv_offset)
  lights    point, sun (`directional`), environment (constant or `envmap`, scale)
  portals   dropped: they steer eyeadapt's sampling of the environment and change no
            expectation, and Mitsuba 3 has no counterpart
Anything else (transforms, OBJ shapes, instances, spot lights, conductors, principled, ...)
is an error naming the key, not a silent approximation. --drop-material NAME leaves out the
shapes of that material (repeatable): see suite.py for why the interior's window panes go.
Paths in the XML are absolute, so it can be written anywhere. Standard library only.
"""
import argparse
import math
import os
import re
import sys
import tomllib


class Unsupported(Exception):
    pass


def vec(v):
    return ", ".join(repr(float(x)) for x in v)


rgb = vec


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def only(table, where, allowed):
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise Unsupported(f"{where}: key(s) {', '.join(extra)} not supported by the converter")


def texture_xml(t):
    where = f"texture {t.get('name')!r}"
    kind = t.get("type")
    to_uv = ""
    if "uv_scale" in t or "uv_offset" in t:
        sx, sy = t.get("uv_scale", [1.0, 1.0])
        ox, oy = t.get("uv_offset", [0.0, 0.0])
        to_uv = (f'    <transform name="to_uv"><scale x="{sx!r}" y="{sy!r}"/>'
                 f'<translate x="{ox!r}" y="{oy!r}"/></transform>\n')
    if kind == "bitmap":
        only(t, where, ["name", "type", "file", "raw", "filter", "wrap", "uv_scale", "uv_offset"])
        return (f'  <texture type="bitmap" id="tex-{t["name"]}">\n'
                f'    <string name="filename" value="{t["file"]}"/>\n'
                f'    <boolean name="raw" value="{str(bool(t.get("raw", False))).lower()}"/>\n'
                f'    <string name="filter_type" value="{t.get("filter", "bilinear")}"/>\n'
                f'    <string name="wrap_mode" value="{t.get("wrap", "repeat")}"/>\n'
                f"{to_uv}  </texture>\n")
    if kind == "checkerboard":
        only(t, where, ["name", "type", "color0", "color1", "uv_scale", "uv_offset"])
        return (f'  <texture type="checkerboard" id="tex-{t["name"]}">\n'
                f'    <rgb name="color0" value="{rgb(t.get("color0", [0.4] * 3))}"/>\n'
                f'    <rgb name="color1" value="{rgb(t.get("color1", [0.2] * 3))}"/>\n'
                f"{to_uv}  </texture>\n")
    raise Unsupported(f"{where}: type {kind!r} not supported by the converter")


def colour(m, key, xml_name):
    if f"{key}_texture" in m:
        return f'<ref name="{xml_name}" id="tex-{m[key + "_texture"]}"/>'
    return f'<rgb name="{xml_name}" value="{rgb(m.get(key, [0.5] * 3))}"/>'


def bsdf_xml(m):
    """The BSDF of a TOML material, with id bsdf-NAME."""
    where, kind, name = f"material {m.get('name')!r}", m.get("type"), m["name"]
    if kind == "diffuse":
        only(m, where, ["name", "type", "reflectance", "reflectance_texture", "emission"])
        inner = f'<bsdf type="diffuse">{colour(m, "reflectance", "reflectance")}</bsdf>'
        return f'  <bsdf type="twosided" id="bsdf-{name}">{inner}</bsdf>\n'
    if kind == "plastic":
        only(m, where, ["name", "type", "reflectance", "reflectance_texture", "roughness", "ior",
                        "emission"])
        alpha = max(float(m.get("roughness", 0.1)), 0.01)
        inner = (f'<bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
                 f'<float name="alpha" value="{alpha!r}"/>'
                 f'<float name="int_ior" value="{float(m.get("ior", 1.5))!r}"/>'
                 f'<float name="ext_ior" value="1.0"/>'
                 f'{colour(m, "reflectance", "diffuse_reflectance")}</bsdf>')
        return f'  <bsdf type="twosided" id="bsdf-{name}">{inner}</bsdf>\n'
    if kind in ("dielectric", "thin_dielectric"):
        only(m, where, ["name", "type", "ior"])
        plugin = "dielectric" if kind == "dielectric" else "thindielectric"
        return (f'  <bsdf type="{plugin}" id="bsdf-{name}"><float name="int_ior" '
                f'value="{float(m.get("ior", 1.5))!r}"/><float name="ext_ior" value="1.0"/></bsdf>\n')
    raise Unsupported(f"{where}: type {kind!r} not supported by the converter")


def shape_xml(s, materials):
    where, kind = f"shape {s.get('type')} ({s.get('material')})", s.get("type")
    m = materials[s["material"]]
    body = f'    <ref id="bsdf-{m["name"]}"/>\n'
    if "emission" in m:
        body += f'    <emitter type="area"><rgb name="radiance" value="{rgb(m["emission"])}"/></emitter>\n'
    if kind == "quad":
        only(s, where, ["type", "material", "corner", "u", "v"])
        c, u, v = s.get("corner", [-1, -1, 0]), s.get("u", [2, 0, 0]), s.get("v", [0, 2, 0])
        n = cross(u, v)
        ln = math.sqrt(sum(x * x for x in n))
        n = [x / ln for x in n]
        centre = [c[i] + 0.5 * (u[i] + v[i]) for i in range(3)]
        rows = [[0.5 * u[i], 0.5 * v[i], n[i], centre[i]] for i in range(3)] + [[0, 0, 0, 1]]
        mat = " ".join(repr(float(x)) for r in rows for x in r)
        return (f'  <shape type="rectangle">\n    <transform name="to_world"><matrix value="{mat}"/>'
                f"</transform>\n{body}  </shape>\n")
    if kind == "box":
        only(s, where, ["type", "material", "min", "max"])
        lo, hi = s.get("min", [-1, -1, -1]), s.get("max", [1, 1, 1])
        half = [0.5 * (hi[i] - lo[i]) for i in range(3)]
        mid = [0.5 * (hi[i] + lo[i]) for i in range(3)]
        return (f'  <shape type="cube">\n    <transform name="to_world"><scale value="{vec(half)}"/>'
                f'<translate value="{vec(mid)}"/></transform>\n{body}  </shape>\n')
    if kind == "sphere":
        only(s, where, ["type", "material", "center", "radius", "subdivisions"])
        return (f'  <shape type="sphere">\n    <point name="center" value="{vec(s.get("center", [0, 0, 0]))}"/>\n'
                f'    <float name="radius" value="{float(s.get("radius", 1.0))!r}"/>\n{body}  </shape>\n')
    raise Unsupported(f"{where}: type {kind!r} not supported by the converter")


def light_xml(lt):
    where, kind = f"light {lt.get('type')}", lt.get("type")
    if kind == "point":
        only(lt, where, ["type", "position", "intensity"])
        return (f'  <emitter type="point"><point name="position" value="{vec(lt["position"])}"/>'
                f'<rgb name="intensity" value="{rgb(lt["intensity"])}"/></emitter>\n')
    if kind == "sun":
        only(lt, where, ["type", "direction", "irradiance"])
        return (f'  <emitter type="directional"><vector name="direction" value="{vec(lt["direction"])}"/>'
                f'<rgb name="irradiance" value="{rgb(lt["irradiance"])}"/></emitter>\n')
    raise Unsupported(f"{where}: type {kind!r} not supported by the converter")


def environment_xml(env):
    only(env, "[environment]", ["radiance", "map", "scale"])
    if "map" in env:
        return (f'  <emitter type="envmap"><string name="filename" value="{env["map"]}"/>'
                f'<float name="scale" value="{float(env.get("scale", 1.0))!r}"/></emitter>\n')
    return f'  <emitter type="constant"><rgb name="radiance" value="{rgb(env["radiance"])}"/></emitter>\n'


def absolute_paths(scene, base):
    for t in scene.get("textures", []):
        if "file" in t:
            t["file"] = os.path.normpath(os.path.join(base, t["file"]))
    env = scene.get("environment", {})
    if "map" in env:
        env["map"] = os.path.normpath(os.path.join(base, env["map"]))


def convert(toml_path, drop=()):
    """Mitsuba XML text of the TOML scene at toml_path, without the shapes of `drop`."""
    with open(toml_path, "rb") as f:
        scene = tomllib.load(f)
    absolute_paths(scene, os.path.dirname(os.path.abspath(toml_path)))
    only(scene, "top level", ["camera", "render", "camera_path", "materials", "textures",
                              "shapes", "lights", "environment", "portals"])
    cam = scene["camera"]
    only(cam, "[camera]", ["position", "look_at", "up", "fov_deg", "width", "height"])
    render = scene.get("render", {})
    only(render, "[render]", ["spp", "max_depth", "rr_depth", "seed"])
    materials = {m["name"]: m for m in scene.get("materials", [])}
    used = [s for s in scene.get("shapes", []) if s.get("material") not in drop]
    out = ['<scene version="3.0.0">\n',
           f'  <!-- Written by scripts/bench/toml_to_mitsuba.py from {os.path.basename(toml_path)}'
           + (f", without the shapes of {', '.join(drop)}" if drop else "") + " -->\n",
           f'  <integrator type="path"><integer name="max_depth" value="{render.get("max_depth", 8)}"/>'
           f'<integer name="rr_depth" value="{render.get("rr_depth", 5)}"/></integrator>\n',
           '  <sensor type="perspective">\n    <string name="fov_axis" value="y"/>\n'
           f'    <float name="fov" value="{float(cam["fov_deg"])!r}"/>\n'
           f'    <transform name="to_world"><lookat origin="{vec(cam["position"])}" '
           f'target="{vec(cam["look_at"])}" up="{vec(cam.get("up", [0, 1, 0]))}"/></transform>\n'
           f'    <sampler type="independent"><integer name="sample_count" value="{render.get("spp", 16)}"/></sampler>\n'
           f'    <film type="hdrfilm"><integer name="width" value="{cam["width"]}"/>'
           f'<integer name="height" value="{cam["height"]}"/><rfilter type="box"/>'
           '<string name="pixel_format" value="rgb"/></film>\n  </sensor>\n']
    out += [texture_xml(t) for t in scene.get("textures", [])]
    out += [bsdf_xml(m) for m in materials.values()]
    out += [shape_xml(s, materials) for s in used]
    out += [light_xml(lt) for lt in scene.get("lights", [])]
    if "environment" in scene:
        out.append(environment_xml(scene["environment"]))
    out.append("</scene>\n")
    return "".join(out), len(scene.get("shapes", [])) - len(used)


BLOCK = re.compile(r"^\[\[?[A-Za-z_][\w.]*\]\]?\s*(#.*)?$")


def toml_without(toml_path, drop):
    """The TOML text without the [[shapes]] tables of the materials in `drop`, with file and map
    paths made absolute (so it can be written anywhere); checked by parsing it again."""
    base = os.path.dirname(os.path.abspath(toml_path))
    with open(toml_path) as f:
        lines = f.read().splitlines(keepends=True)
    blocks, cur = [], []
    for line in lines:
        if BLOCK.match(line.strip()) and cur:
            blocks.append(cur)
            cur = []
        cur.append(line)
    blocks.append(cur)
    kept = []
    for b in blocks:
        text = "".join(b)
        if b[0].strip().startswith("[[shapes]]") and tomllib.loads(text)["shapes"][0].get("material") in drop:
            continue
        kept.append(re.sub(r'^(file|map)\s*=\s*"([^"]+)"',
                           lambda mt: f'{mt.group(1)} = "{os.path.normpath(os.path.join(base, mt.group(2)))}"',
                           text, flags=re.M))
    out = "".join(kept)
    with open(toml_path, "rb") as f:
        shapes = tomllib.load(f).get("shapes", [])
    dropped = sum(1 for s in shapes if s.get("material") in drop)
    if len(tomllib.loads(out).get("shapes", [])) != len(shapes) - dropped:
        raise Unsupported(f"{toml_path}: could not drop the shapes of {drop} cleanly")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("toml")
    ap.add_argument("out")
    ap.add_argument("--drop-material", action="append", default=[])
    a = ap.parse_args()
    try:
        xml, dropped = convert(a.toml, tuple(a.drop_material))
    except (Unsupported, KeyError) as e:
        print(f"{a.toml}: {e}", file=sys.stderr)
        return 2
    with open(a.out, "w") as f:
        f.write(xml)
    print(f"wrote {a.out} ({dropped} shapes dropped)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
