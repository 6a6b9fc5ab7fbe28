#!/usr/bin/env python3
"""Writes the bad-input catalogue: one file per case and format, and `expected.json`.

Every file in this directory must make `curvenet surface FILE -o OUT` exit non-zero with a
message containing the expected substring, without a panic and without writing OUT. The
catalogue is checked by `crates/curvenet-cli/tests/bad_inputs.rs`; the files are committed,
this script is how they were made (run it from anywhere: `python3 tests/data/bad/generate.py`).

Two kinds of cases:
- *malformed files*: written by hand per format (truncated, wrong types, NaN/inf, indices
  out of range, …);
- *invalid networks*: one network per case (zero normals, flipped normals, dangling curves,
  …), written in each of the three network formats (JSON, OBJ, .net) that can express it.
"""

import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
expected = {}


def put(name, text, code, message):
    """Writes one case file; `message` (a string or a list of strings) must appear in
    curvenet's error output (or, for the few hard inputs that exit 0, in its warnings)."""
    data = text.encode() if isinstance(text, str) else text
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)
    expected[name] = {"exit": code, "message": [message] if isinstance(message, str) else message}


# ---------------------------------------------------------------------------------------------
# Networks as lists of curves: dict(points, normals, closed, boundary, name).


def curve(points, normals, closed=False, boundary=False, name=None):
    return {"points": points, "normals": normals, "closed": closed, "boundary": boundary, "name": name}


def circle(n, frame):
    """A great circle of the unit sphere in the plane spanned by `frame` (two unit vectors)."""
    a, b = frame
    pts = []
    for k in range(n):
        t = 2 * math.pi * k / n
        pts.append([a[i] * math.cos(t) + b[i] * math.sin(t) for i in range(3)])
    return pts


def sphere(n=48):
    """The unit sphere traced by three great circles, outward normals."""
    frames = [((1, 0, 0), (0, 1, 0)), ((0, 1, 0), (0, 0, 1)), ((0, 0, 1), (1, 0, 0))]
    names = ["equator z=0", "meridian x=0", "meridian y=0"]
    out = []
    for f, nm in zip(frames, names):
        p = circle(n, f)
        out.append(curve(p, [list(q) for q in p], closed=True, name=nm))
    return out


def num(x):
    if isinstance(x, float) and math.isnan(x):
        return "nan"
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(float(x))


def to_json(curves, snap=None):
    def jnum(x):
        # JSON has no NaN/inf: such cases are written by hand.
        return float(x)

    doc = {
        "curves": [
            {
                **({"name": c["name"]} if c["name"] else {}),
                "closed": c["closed"],
                "boundary": c["boundary"],
                "points": [[jnum(x) for x in p] for p in c["points"]],
                "normals": [[jnum(x) for x in p] for p in c["normals"]],
            }
            for c in curves
        ]
    }
    if snap is not None:
        doc["snap"] = snap
    return json.dumps(doc, indent=1) + "\n"


def to_obj(curves):
    v, vn, groups = [], [], []
    for c in curves:
        base = len(v)
        v += c["points"]
        vn += c["normals"]
        idx = list(range(base + 1, base + len(c["points"]) + 1))
        if c["closed"]:
            idx.append(idx[0])
        groups.append(("boundary" if c["boundary"] else (c["name"] or "curve").replace(" ", "_"), idx))
    lines = ["v " + " ".join(num(x) for x in p) for p in v]
    lines += ["vn " + " ".join(num(x) for x in p) for p in vn]
    for g, idx in groups:
        lines.append(f"g {g}")
        lines.append("l " + " ".join(map(str, idx)))
    return "\n".join(lines) + "\n"


def to_net(curves):
    samples, lines = [], []
    for c in curves:
        base = len(samples)
        samples += list(zip(c["points"], c["normals"]))
        idx = list(range(base, base + len(c["points"])))
        if c["closed"]:
            idx.append(idx[0])
        lines.append("1" if c["boundary"] else "0")
        lines.append(" ".join(map(str, idx)))
    out = [str(len(samples))]
    out += [" ".join(num(x) for x in p + n) for p, n in samples]
    out += [str(len(curves))] + lines
    return "\n".join(out) + "\n"


def label(curves, i, fmt):
    """How messages name curve `i` of `curves` written as `fmt`: by its name where no other curve
    has it (`curve "rim"`), by its index beside a shared name (`curve 3 ("curve")`, an OBJ
    group), by its index alone without a name (`curve 3`, the `.net` format)."""
    names = [None if fmt == "net" else c["name"] for c in curves]
    if fmt == "obj":
        names = ["boundary" if c["boundary"] else (c["name"] or "curve").replace(" ", "_") for c in curves]
    if names[i] is None:
        return f"curve {i}"
    if names.count(names[i]) > 1:
        return f"curve {i} (\"{names[i]}\")"
    return f"curve \"{names[i]}\""


def network(name, curves, code, message, formats=("json", "obj", "net")):
    """One invalid network in every format that can express it; `{c3}` in `message` stands for
    curve 3's label in that format."""
    for fmt in formats:
        text = {"json": to_json, "obj": to_obj, "net": to_net}[fmt](curves)
        labels = {f"c{i}": label(curves, i, fmt) for i in range(len(curves))}
        msg = [m.format(**labels) for m in message] if isinstance(message, list) else message.format(**labels)
        put(f"{name}.{fmt}", text, code, msg)


# ---------------------------------------------------------------------------------------------
# Malformed files, per format.

TWO = '{"curves": [{"points": [[0,0,0],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}]}'
put("json-empty-file.json", "", 1, "json-empty-file.json:1:")
put("json-truncated.json", '{"curves": [\n  {"points": [[0,0,0],', 1, "json-truncated.json:2:")
put("json-truncated-mid-number.json", to_json(sphere(8))[:-200].rstrip() + "1.", 1, "json-truncated-mid-number.json:")
put("json-wrong-type.json", '{"curves": [{"points": [[0,0,"a"]], "normals": []}]}', 1, "invalid type")
put("json-two-coordinates.json", '{"curves": [{"points": [[0,0],[1,0]], "normals": [[0,0,1],[0,0,1]]}]}', 1,
    "json-two-coordinates.json:1:")
put("json-single-stroke-no-normals.json", '{"curves": [{"points": [[0,0,0],[1,0,0]]}]}', 1, "no curves of the network bound a patch")
put("json-not-an-object.json", "[1, 2, 3]\n", 1, "json-not-an-object.json:1:")
put("json-nan-literal.json", '{"curves": [{"points": [[0,0,NaN],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}]}', 1,
    "json-nan-literal.json:1:")
put("json-overflow.json", '{"curves": [{"points": [[0,0,1e999],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}]}', 1,
    "json-overflow.json:1:")
put("json-normal-overflow.json", '{"curves": [{"points": [[0,0,0],[1,0,0]], "normals": [[0,0,-1e400],[0,0,1]]}]}',
    1, "json-normal-overflow.json:1:")
put("json-trailing-garbage.json", TWO + "\n}\n", 1, "json-trailing-garbage.json:2:")
put("json-not-utf8.json", b"\xff\xfe\x00{", 1, "not valid UTF-8")
put("json-bad-snap.json", '{"curves": [{"points": [[0,0,0],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}], "snap": -1}',
    1, "snapping tolerance -1")
put("json-zero-snap.json", '{"curves": [{"points": [[0,0,0],[1,0,0]], "normals": [[0,0,1],[0,0,1]]}], "snap": 0}',
    1, "snapping tolerance 0")

put("obj-empty-file.obj", "", 1, "obj-empty-file.obj:1:1: no polylines")
put("obj-truncated-v.obj", "v 0 0 0\nv 1 0", 1, "obj-truncated-v.obj:2:")
_obj = to_obj(sphere(8))
_cut = _obj.index("vn ", _obj.index("vn ") + 1) + 6  # inside the second "vn" line
put("obj-truncated.obj", _obj[:_cut], 1, "obj-truncated.obj:26:")
put("obj-bad-number.obj", "v 0 0 0\nv 1 zero 0\n", 1, "obj-bad-number.obj:2:5")
put("obj-nan.obj", "v 0 0 nan\n", 1, "obj-nan.obj:1:7")
put("obj-inf-normal.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn inf 0 1\nl 1 2\n", 1, "obj-inf-normal.obj:4:4")
put("obj-bad-index.obj", "v 0 0 0\nvn 0 0 1\nl 1 x\n", 1, "obj-bad-index.obj:3:5")
put("obj-index-zero.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 0 1\n", 1, "obj-index-zero.obj:5:3")
put("obj-index-out-of-range.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1 9\n", 1, "out of range")
put("obj-negative-out-of-range.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1 -5\n", 1, "out of range")
put("obj-missing-normals.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1 2\n", 1, "2 \"v\" lines but 1 \"vn\"")
put("obj-faces-only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, "looks like a mesh")
put("obj-one-index-line.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 0 1\nl 1\n", 1, "obj-one-index-line.obj:5")
put("obj-not-utf8.obj", b"v 0 0 0\nv \xc3\x28 0 0\n", 1, "not valid UTF-8")

put("net-empty-file.net", "", 1, "number of samples")
put("net-truncated.net", "3\n0 0 0 0 0 1\n1 0 0 0 0 1\n", 1, "ends early")
put("net-truncated-indices.net", "2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\n0\n", 1, "ends early")
put("net-bad-count.net", "two\n", 1, "net-bad-count.net:1:1")
put("net-negative-count.net", "-3\n", 1, "net-negative-count.net:1:1")
put("net-huge-count.net", "99999999999999999999\n", 1, "net-huge-count.net:1:1")
put("net-huge-count-fits.net", "18446744073709551615\n0 0 0 0 0 1\n", 1, "ends early")
put("net-five-numbers.net", "1\n0 0 0 0 1\n", 1, "net-five-numbers.net:2:")
put("net-seven-numbers.net", "1\n0 0 0 0 0 1 7\n", 1, "net-seven-numbers.net:2:13")
put("net-inf.net", "1\n0 0 0 inf 0 1\n", 1, "net-inf.net:2:7")
put("net-nan.net", "1\nnan 0 0 0 0 1\n", 1, "net-nan.net:2:1")
put("net-bad-flag.net", "2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\nyes\n0 1\n", 1, "net-bad-flag.net:5:1")
put("net-index-out-of-range.net", "2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\n0\n0 2\n", 1, "net-index-out-of-range.net:6:3")
put("net-negative-index.net", "2\n0 0 0 0 0 1\n1 0 0 0 0 1\n1\n0\n0 -1\n", 1, "net-negative-index.net:6:3")
put("net-not-utf8.net", b"2\n0 0 0 0 0 1\n\xff 0 0 0 0 1\n", 1, "not valid UTF-8")
put("net-zero-curves.net", "2\n0 0 0 0 0 1\n1 0 0 0 0 1\n0\n", 1, "no curves")

# ---------------------------------------------------------------------------------------------
# Invalid networks, in every format.

sph = sphere()

network("empty-network", [], 1, "no curves", formats=("json", "net"))
network("one-sample-curve", [curve([[0, 0, 0]], [[0, 0, 1]])], 1, "1 sample", formats=("json", "net"))
put("one-sample-curve.obj", "v 0 0 0\nvn 0 0 1\nl 1\n", 1, "one-sample-curve.obj:3:1: a polyline (\"l\") needs at least 2")
network("closed-two-samples", [curve([[0, 0, 0], [1, 0, 0]], [[0, 0, 1]] * 2, closed=True)], 1,
        "a closed curve needs at least 3")
network("all-samples-coincide", [curve([[1, 2, 3]] * 5, [[0, 0, 1]] * 5)], 1, "coincide")
network("near-duplicate-samples", [curve([[0, 0, 0], [1, 0, 0], [1 + 1e-14, 0, 0]], [[0, 0, 1]] * 3),
                                   curve([[0, 5, 0], [5e-15, 5, 0]], [[0, 0, 1]] * 2)], 1,
        ["{c1}", "has 1 distinct sample"])
network("huge-extent-overflow", [curve([[-1e308, 0, 0], [1e308, 0, 0], [0, 1e308, 0]], [[0, 0, 1]] * 3, closed=True)],
        1, "outside the supported range")

# Extents that the arithmetic cannot carry (squared lengths and areas over- or underflow).
big = [dict(c, points=[[x * 1e150 for x in q] for q in c["points"]]) for c in sph]
network("huge-coordinates-1e150", big, 1, "outside the supported range")
small = [dict(c, points=[[x * 1e-300 for x in q] for q in c["points"]]) for c in sph]
network("tiny-coordinates-1e-300", small, 1, "outside the supported range")

zero = [dict(c) for c in sph]
zero[1] = dict(zero[1], normals=[list(n) for n in zero[1]["normals"]])
zero[1]["normals"][5] = [0, 0, 0]
network("zero-normal", zero, 1, ["{c1}", "sample 5: normal", "cannot be normalised"])

tiny = [dict(c) for c in sph]
tiny[2] = dict(tiny[2], normals=[list(n) for n in tiny[2]["normals"]])
tiny[2]["normals"][7] = [1e-320, 0, 0]
network("subnormal-normal", tiny, 1, "sample 7: normal")

flip = [dict(c) for c in sph]
flip[1] = dict(flip[1], normals=[[-x for x in n] for n in flip[1]["normals"]])
network("normals-flipped-on-one-curve", flip, 1, "points inward")

# Normals tangent to the curve (the curve's own direction): no surface side is defined.
tang = [dict(c) for c in sph]
p = tang[0]["points"]
tang[0] = dict(tang[0], normals=[[-q[1], q[0], 0.0] for q in p])
network("normals-tangent-to-curve", tang, 1, ["{c0}", "sample 0: normal", "tangent to the curve"])

# An extra copy of the equator (coincident curves) and a half equator lying on it (overlap).
# Handled since consolidation (issue 28: "overdraw ... includes exact duplicates"): merged into
# the equator with a warning naming the curve; `--consolidate off` refuses them as overlapping.
network("coincident-curves", sph + [dict(sph[0], name="equator again")], 0, ["{c3}", "overdrawn stretch"])
half = dict(sph[0], name="half equator", closed=False,
            points=sph[0]["points"][: len(sph[0]["points"]) // 2 + 1],
            normals=sph[0]["normals"][: len(sph[0]["points"]) // 2 + 1])
network("overlapping-curves", sph + [half], 0, ["{c3}", "overdrawn stretch"])

# A curve leaving a node and ending inside a patch: a node of valence 1.
dang = []
for k in range(21):
    t = 0.25 * math.pi * k / 20
    s = math.sin(t) * math.sqrt(0.5)
    dang.append([s, s, math.cos(t)])
# Handled since open networks are supported (issue 5): trimmed with a warning naming the curve.
network("dangling-curve", sph + [curve(dang, dang, name="whisker")], 0, ["{c3}", "left out of the surface"])

# Three half-disk pages sharing a diameter: a segment used by three patches.
book = [curve([[-1 + 2 * k / 32, 0, 0] for k in range(33)], [[0, 0, 1]] * 33, name="spine")]
for a in (-20, 0, 20):
    a = math.radians(a)
    u, nn = (0, math.cos(a), math.sin(a)), [0, -math.sin(a), math.cos(a)]
    pts = [[math.cos(math.pi * k / 32) + 0 * u[0], math.sin(math.pi * k / 32) * u[1],
            math.sin(math.pi * k / 32) * u[2]] for k in range(33)]
    book.append(curve(pts, [nn] * 33, boundary=True))
network("non-manifold-book", book, 1, "not a 2-manifold")

# A closed boundary curve that crosses itself in space: a figure eight.
eight = []
for k in range(120):
    t = 2 * math.pi * k / 120
    eight.append([math.sin(t), math.sin(t) * math.cos(t), 0.0])
network("self-intersecting-curve", [curve(eight, [[0, 0, 1]] * 120, closed=True, boundary=True, name="eight")],
        1, ["4 boundary segment ends meet", "({c0}", "not a 2-manifold"])

# A boundary loop whose planar projection crosses itself (a limaçon lifted out of its plane).
lim = []
for k in range(200):
    t = 2 * math.pi * k / 200
    r = 0.5 + math.cos(t)
    lim.append([r * math.cos(t), r * math.sin(t), 0.3 * math.sin(t)])
# Handled since the fold fallback (issue 5): surfaced on a fallback domain, with a warning.
network("self-crossing-projection", [curve(lim, [[0, 0, 1]] * 200, closed=True, boundary=True)], 0,
        ["patch 0", "folds over", "fallback domain"])

# A needle: a boundary loop 1e-4 as wide as it is long (its two sides closer than the snap).
needle = [[math.cos(2 * math.pi * k / 100), 1e-4 * math.sin(2 * math.pi * k / 100), 0.0] for k in range(100)]
network("needle-cycle", [curve(needle, [[0, 0, 1]] * 100, closed=True, boundary=True, name="needle")], 1,
        "curve \"needle\" runs within the snapping tolerance", formats=("json",))
network("needle-cycle", [curve(needle, [[0, 0, 1]] * 100, closed=True, boundary=True)], 1,
        "curve 0 runs within the snapping tolerance", formats=("net",))

# A boundary tag on a curve with patches on both sides.
tagged = [dict(c) for c in sph]
tagged[0] = dict(tagged[0], boundary=True)
network("interior-curve-tagged-boundary", tagged, 1, "tagged as boundary but has patches on both sides",
        formats=("json", "net"))

# A single open curve: it bounds nothing.
network("single-open-curve", [curve([[k / 10, 0, 0] for k in range(11)], [[0, 0, 1]] * 11, name="stick")], 1,
        ["{c0}", "no curves of the network bound a patch"])

# Cycles given with the network (docs/design.md §15) that do not fit it.
def with_cycles(curves, cycles):
    doc = json.loads(to_json(curves))
    doc["cycles"] = cycles
    return json.dumps(doc)


put("cycles-unknown-curve.json", with_cycles(sph, [[[7, 0, 12, True]]]), 1,
    ["cycle 0 of the network's \"cycles\"", "curve 7 is not in the network"])
put("cycles-empty-cycle.json", with_cycles(sph, [[]]), 1, ["cycle 0 ", "has no segments"])
put("cycles-not-a-list.json", with_cycles(sph, {"a": 1}), 1, "cycles-not-a-list.json:")

with open(os.path.join(HERE, "expected.json"), "w") as f:
    json.dump(dict(sorted(expected.items())), f, indent=1)
    f.write("\n")
print(f"{len(expected)} cases written to {HERE}")
