"""A Mitsuba XML scene with the settings the benchmark suite varies made into parameters.

patch(path) reads the scene and, recursively, the files it <include>s (inlined in place, so
the sampler of cbox-rgb.xml's fragments/base.xml can be changed too), drops comments, and
makes these `$bench_*` parameters with a <default> each:
  bench_sampler   the sampler's type (default: the file's)
  bench_spp       the sampler's sample_count;  bench_seed: its seed (0)
  bench_width     the film's width and height (default: the file's, `$name` defaults resolved)
  bench_height
  bench_max_depth the path integrator's max_depth and rr_depth (default: the file's, -1 / 5)
  bench_rr_depth
A scene without exactly one sampler, film and `path` integrator is an error. The result is
written elsewhere than the scene, so relative paths in it need the scene's directories in
Mitsuba's file resolver: patch() returns them (`mitsuba -a`, or FileResolver.prepend).
"""
import os
import re

INCLUDE = re.compile(r'<include\s+filename="([^"]+)"\s*/>')
COMMENT = re.compile(r"<!--.*?-->", re.S)


class PatchError(Exception):
    pass


def flatten(path, dirs):
    base = os.path.dirname(os.path.abspath(path))
    if base not in dirs:
        dirs.append(base)
    with open(path, encoding="utf-8") as f:
        text = COMMENT.sub("", f.read())

    def inline(m):
        name = m.group(1)
        inc = os.path.join(base, name)
        if not os.path.exists(inc):
            inc = os.path.join(dirs[0], name)
        inner = re.sub(r"<\?xml[^>]*\?>", "", flatten(inc, dirs))
        inner = re.sub(r"<scene\b[^>]*>", "", inner, count=1)
        return inner[: inner.rindex("</scene>")]

    return INCLUDE.sub(inline, text)


def element(text, tag, path):
    """(start, end, attributes, body) of the one <tag ...>...</tag> or <tag .../> in text."""
    found = list(re.finditer(rf"<{tag}\b([^>]*?)(/>|>(.*?)</{tag}>)", text, re.S))
    if len(found) != 1:
        raise PatchError(f"{path}: {len(found)} <{tag}> elements, the suite needs exactly one")
    m = found[0]
    return m.start(), m.end(), m.group(1), m.group(3) or ""


def value_of(body, name, text, default=None):
    """The value of <integer name="NAME" value="..."/> in body, a `$param` resolved by its
    <default> in text."""
    m = re.search(rf'<integer\s+name="{name}"\s+value="([^"]+)"\s*/>', body)
    if not m:
        return default
    return resolve(m.group(1), text, default)


def resolve(v, text, default=None):
    """v, or the value of the <default> of the `$param` it names."""
    if v.startswith("$"):
        d = re.search(rf'<default\s+name="{v[1:]}"\s+value="([^"]+)"\s*/>', text)
        return d.group(1) if d else default
    return v


def without(body, *names):
    for n in names:
        body = re.sub(rf'<integer\s+name="{n}"\s+value="[^"]*"\s*/>', "", body)
    return body


def patch(path):
    """(patched XML text, directories for the file resolver, the file's film (width, height))."""
    dirs = []
    text = flatten(path, dirs)
    s0, s1, attrs, body = element(text, "sampler", path)
    kind = resolve(re.search(r'type="([^"]+)"', attrs).group(1), text, "independent")
    sampler = (f'<sampler type="$bench_sampler"><integer name="sample_count" value="$bench_spp"/>'
               f'<integer name="seed" value="$bench_seed"/>{without(body, "sample_count", "seed")}</sampler>')
    text = text[:s0] + sampler + text[s1:]
    f0, f1, attrs, body = element(text, "film", path)
    wh = (int(value_of(body, "width", text, 768)), int(value_of(body, "height", text, 576)))
    film = (f'<film{attrs}><integer name="width" value="$bench_width"/>'
            f'<integer name="height" value="$bench_height"/>{without(body, "width", "height")}</film>')
    text = text[:f0] + film + text[f1:]
    i0, i1, attrs, body = element(text, "integrator", path)
    if 'type="path"' not in attrs:
        raise PatchError(f"{path}: the integrator is not `path` ({attrs.strip()})")
    depth = value_of(body, "max_depth", text, -1)
    rr = value_of(body, "rr_depth", text, 5)
    integ = (f'<integrator{attrs}><integer name="max_depth" value="$bench_max_depth"/>'
             f'<integer name="rr_depth" value="$bench_rr_depth"/>{without(body, "max_depth", "rr_depth")}'
             "</integrator>")
    text = text[:i0] + integ + text[i1:]
    defaults = {"bench_sampler": kind, "bench_spp": 16, "bench_seed": 0, "bench_width": wh[0],
                "bench_height": wh[1], "bench_max_depth": depth, "bench_rr_depth": rr}
    head = re.search(r"<scene\b[^>]*>", text)
    text = (text[: head.end()] + "".join(f'\n    <default name="{k}" value="{v}"/>'
                                        for k, v in defaults.items()) + text[head.end():])
    return text, dirs, wh
