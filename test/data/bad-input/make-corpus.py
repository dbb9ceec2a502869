#!/usr/bin/env python3
"""Writes the malformed-input corpus of test/data/bad-input/ (Python 3 standard library only).

    test/data/bad-input/make-corpus.py [--out DIR]

Every file is small (well under 100 KB) and deterministic: rerunning the script rewrites the same
bytes. The generated files and expected.json are committed; test/robustness/bad_input_test.cpp runs
`cohort info` and `cohort render` on each entry of expected.json and checks the outcome it states,
and fuzz_replay (test/fuzz/) feeds every file here through the loaders.

expected.json lists, for each entry:
  file       the name under this directory (or created at run time, see `create`)
  exit       2: bad input, rejected with a message that names the file and contains `message`;
             0: legal but odd, loaded with a warning containing `warning` (both commands print it)
  message    (exit 2) a substring of the error message besides the file name
  warning    (exit 0) a substring of what `info` and `render` print
  image      (exit 0) "black": the render must be all zeros (a scene without light);
             {"same_as": FILE}: bit for bit the render of FILE (an input whose bad parts are dropped)
  create     made by the test, not stored: "directory" (a directory named like a scene),
             "unreadable" (a valid OBJ with mode 000), "missing" (no such file)
"""

import argparse
import base64
import gzip
import json
import math
import pathlib
import random
import struct
import zlib

HERE = pathlib.Path(__file__).resolve().parent

ENTRIES = []  # manifest entries, in the order written
FILES = {}    # name -> bytes


def put(name, data, **expect):
    if isinstance(data, str):
        data = data.encode("utf-8")
    assert name not in FILES, name
    assert len(data) < 100_000, (name, len(data))
    FILES[name] = data
    if expect:
        ENTRIES.append(dict(file=name, **expect))


def bad(name, data, message):
    put(name, data, exit=2, message=message)


def odd(name, data, warning, image=None):
    entry = dict(exit=0, warning=warning)
    if image is not None:
        entry["image"] = image
    put(name, data, **entry)


def runtime(name, create, exit, message):
    ENTRIES.append(dict(file=name, create=create, exit=exit, message=message))


def garbage(seed, size):
    rng = random.Random(seed)
    return bytes(rng.getrandbits(8) for _ in range(size))


# ---------------------------------------------------------------- glTF
class Gltf:
    """One buffer and the JSON that indexes it; triangles are lists of three (x, y, z)."""

    def __init__(self):
        self.blob = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "cohort make-corpus.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": [], "buffers": []}

    def view(self, data, stride=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        v = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.doc["bufferViews"].append(v)
        self.blob.extend(data)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, view, component, count, kind):
        self.doc["accessors"].append({"bufferView": view, "componentType": component,
                                      "count": count, "type": kind})
        return len(self.doc["accessors"]) - 1

    def positions(self, points):
        data = b"".join(struct.pack("<3f", *p) for p in points)
        return self.accessor(self.view(data), 5126, len(points), "VEC3")

    def indices(self, values):
        return self.accessor(self.view(struct.pack("<%dH" % len(values), *values)), 5123,
                             len(values), "SCALAR")

    def material(self, base=(0.8, 0.8, 0.8), emission=None):
        m = {"pbrMetallicRoughness": {"baseColorFactor": list(base) + [1.0],
                                      "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if emission:
            m["emissiveFactor"] = list(emission)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def mesh(self, triangles, material=None, mode=4, indexed=False):
        points = [p for t in triangles for p in t]
        prim = {"attributes": {"POSITION": self.positions(points)}, "mode": mode}
        if indexed:
            prim["indices"] = self.indices(list(range(len(points))))
        if material is not None:
            prim["material"] = material
        self.doc["meshes"].append({"name": "mesh%d" % len(self.doc["meshes"]), "primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def finish_buffer(self, uri=True):
        b = {"byteLength": len(self.blob)}
        if uri:
            b["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode()
        self.doc["buffers"] = [b]

    def gltf(self):
        self.finish_buffer()
        return json.dumps(self.doc, indent=1) + "\n"

    def glb(self, json_override=None, bin_chunk=True):
        self.finish_buffer(uri=False)
        text = json_override if json_override is not None else json.dumps(self.doc).encode()
        text += b" " * (-len(text) % 4)
        body = struct.pack("<II", len(text), 0x4E4F534A) + text
        if bin_chunk:
            blob = bytes(self.blob) + b"\0" * (-len(self.blob) % 4)
            body += struct.pack("<II", len(blob), 0x004E4942) + blob
        return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


# A lit test scene seen by the framing camera (which looks down -Z): an emissive triangle in
# front of a grey wall, both facing +Z.
LIGHT = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.0, 0.5, 0.0)]
WALL = [[(-1, -1, -0.5), (1, -1, -0.5), (1, 1, -0.5)], [(-1, -1, -0.5), (1, 1, -0.5), (-1, 1, -0.5)]]
NAN = float("nan")
INF = float("inf")


def lit_gltf(extra_triangles=(), extra_mode_primitives=()):
    """Wall + light; extra triangles are appended last to the wall mesh so the kept triangles keep
    their order (and the render stays bit-identical to the plain scene)."""
    g = Gltf()
    wall, light = g.material(), g.material((0, 0, 0), (4.0, 4.0, 4.0))
    g.node({"mesh": g.mesh([LIGHT], light)})
    g.node({"mesh": g.mesh(WALL + list(extra_triangles), wall)})
    for mode, tris in extra_mode_primitives:
        g.doc["meshes"][-1]["primitives"].append(
            {"attributes": {"POSITION": g.positions([p for t in tris for p in t])}, "mode": mode})
    return g


def unlit_gltf():
    g = Gltf()
    g.node({"mesh": g.mesh(WALL, g.material())})
    return g


def make_gltf():
    valid = lit_gltf().gltf()
    bad("gltf-not-json.gltf", "{ this is not json", "invalid glTF")
    bad("gltf-empty-file.gltf", "", "invalid glTF")
    bad("gltf-truncated.gltf", valid[: len(valid) // 2], "invalid glTF")
    bad("gltf-json-array.gltf", "[1, 2, 3]\n", "invalid glTF")
    bad("gltf-binary-garbage.gltf", garbage(1, 4096), "invalid glTF")
    bad("gltf-deep-json.gltf", '{"asset": {"version": "2.0"}, "extras": ' + "[" * 30000 + "]" * 30000 + "}",
        "nested deeper")
    bad("gltf-empty-scene.gltf", json.dumps({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}]}),
        "no triangles")

    g = lit_gltf()
    g.doc["meshes"][1]["primitives"][0]["indices"] = g.indices([0, 1, 2, 0, 2, 9])
    bad("gltf-index-out-of-range.gltf", g.gltf(), "out of range")

    g = lit_gltf()
    g.doc["scenes"][0]["nodes"] = [0, -1]
    bad("gltf-negative-node.gltf", g.gltf(), "node -1")

    g = lit_gltf()
    g.doc["meshes"][1]["primitives"][0]["attributes"]["POSITION"] = 40
    bad("gltf-accessor-missing.gltf", g.gltf(), "accessor")

    g = lit_gltf()
    g.doc["accessors"][1]["count"] = 1000000
    bad("gltf-accessor-overrun.gltf", g.gltf(), "overruns")

    g = lit_gltf()
    g.doc["accessors"][1]["count"] = 1 << 40
    bad("gltf-count-2pow40.gltf", g.gltf(), "overruns")

    g = lit_gltf()
    g.doc["accessors"][1]["byteOffset"] = (1 << 32) - 4
    bad("gltf-offset-huge.gltf", g.gltf(), "")

    g = lit_gltf()
    g.doc["bufferViews"][1]["byteStride"] = 4
    bad("gltf-stride-too-small.gltf", g.gltf(), "")

    g = lit_gltf()
    g.doc["accessors"][1]["type"] = "VEC2"
    bad("gltf-position-vec2.gltf", g.gltf(), "")

    g = lit_gltf()
    g.doc["accessors"][1]["componentType"] = 5130  # double: not a glTF component type
    bad("gltf-component-double.gltf", g.gltf(), "")

    g = lit_gltf()
    g.doc["bufferViews"][1]["buffer"] = 3
    bad("gltf-buffer-view-bad-buffer.gltf", g.gltf(), "")

    g = lit_gltf()
    g.doc["accessors"][1]["bufferView"] = 17
    bad("gltf-accessor-bad-view.gltf", g.gltf(), "")

    g = lit_gltf()
    g.finish_buffer()
    g.doc["buffers"][0]["uri"] = "missing-buffer.bin"
    bad("gltf-missing-buffer.gltf", json.dumps(g.doc), "missing-buffer.bin")

    g = lit_gltf()
    g.finish_buffer()
    g.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,@@@not base64@@@"
    bad("gltf-bad-data-uri.gltf", json.dumps(g.doc), "invalid glTF")

    g = lit_gltf()
    g.finish_buffer()
    g.doc["buffers"][0]["byteLength"] = len(g.blob) * 4
    bad("gltf-buffer-short.gltf", json.dumps(g.doc), "invalid glTF")

    g = lit_gltf()
    g.doc["meshes"][1]["primitives"][0]["material"] = 7
    bad("gltf-bad-material.gltf", g.gltf(), "material 7")

    g = lit_gltf()
    g.doc["nodes"][0]["children"] = [1]
    g.doc["nodes"][1]["children"] = [0]
    bad("gltf-cyclic-nodes.gltf", g.gltf(), "cyclic")

    g = lit_gltf()
    g.doc["nodes"][1]["children"] = [1]
    bad("gltf-self-child.gltf", g.gltf(), "cyclic")

    g = lit_gltf()
    below = 1
    for _ in range(1000):
        below = g.node({"children": [below]}, root=False)
    g.doc["scenes"][0]["nodes"] = [0, below]
    bad("gltf-deep-nodes.gltf", g.gltf(), "deeper")

    g = lit_gltf()
    below = 1
    for _ in range(40):
        below = g.node({"children": [below, below]}, root=False)
    g.doc["scenes"][0]["nodes"] = [0, below]
    bad("gltf-node-dag-2pow40.gltf", g.gltf(), "node instances")

    g = lit_gltf()
    g.doc["nodes"][1]["mesh"] = 9
    bad("gltf-bad-mesh.gltf", g.gltf(), "mesh 9")

    g = Gltf()
    g.node({"mesh": g.mesh(WALL, g.material(), mode=0)})
    g.node({"mesh": g.mesh(WALL, None, mode=1)})
    bad("gltf-points-and-lines-only.gltf", g.gltf(), "no triangles")

    # Legal but odd.
    odd("gltf-no-light.gltf", unlit_gltf().gltf(), "no light", "black")
    put("gltf-lit-reference.gltf", lit_gltf().gltf())
    odd("gltf-nan-vertices.gltf", lit_gltf([[(NAN, NAN, NAN)] * 3, [(0, 0, 0), (NAN, 1, 0), (1, 0, 0)]]).gltf(),
        "non-finite", {"same_as": "gltf-lit-reference.gltf"})
    odd("gltf-inf-vertices.gltf", lit_gltf([[(INF, 0, 0), (0, INF, 0), (0, 0, -INF)]]).gltf(),
        "non-finite", {"same_as": "gltf-lit-reference.gltf"})
    odd("gltf-lines-skipped.gltf", lit_gltf(extra_mode_primitives=[(1, WALL), (0, WALL)]).gltf(),
        "point or line primitives skipped", {"same_as": "gltf-lit-reference.gltf"})

    g = lit_gltf()
    g.doc["images"] = [{"uri": "missing-texture.png"}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    odd("gltf-missing-texture.gltf", g.gltf(), "missing-texture.png", {"same_as": "gltf-lit-reference.gltf"})

    g = lit_gltf()
    g.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(b"\x89PNG\r\n\x1a\n" + garbage(2, 64)).decode()}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    bad("gltf-corrupt-texture.gltf", g.gltf(), "cannot be decoded")

    # What a loader must not read as some other scene (docs/input.md).
    for name, version in [("gltf-version-1.gltf", "1.0"), ("gltf-version-3.gltf", "3.0"),
                          ("gltf-version-garbage.gltf", "2.0beta")]:
        g = lit_gltf()
        g.doc["asset"]["version"] = version
        bad(name, g.gltf(), "asset.version")
    g = lit_gltf()
    g.doc["asset"]["minVersion"] = "2.1"
    bad("gltf-min-version-2-1.gltf", g.gltf(), "minVersion")
    g = lit_gltf()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    bad("gltf-required-extension.gltf", g.gltf(), "KHR_draco_mesh_compression")

    g = lit_gltf()
    g.doc["nodes"][1]["translation"] = [0, 0]
    bad("gltf-translation-2-numbers.gltf", g.gltf(), "translation has 2 numbers")
    g = lit_gltf()
    g.doc["nodes"][1]["rotation"] = [0, 0, 0, 0]
    bad("gltf-zero-quaternion.gltf", g.gltf(), "unit quaternion")
    g = lit_gltf()
    g.doc["nodes"][1]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1]
    bad("gltf-projective-matrix.gltf", g.gltf(), "not affine")
    g = lit_gltf()
    g.doc["nodes"][1]["scale"] = [1e200, 1e200, 1e200]
    g.doc["nodes"][1]["children"] = [g.node({"scale": [1e200, 1e200, 1e200], "mesh": 0}, root=False)]
    bad("gltf-scale-overflow.gltf", g.gltf(), "overflows")

    g = lit_gltf()
    g.doc["meshes"][1]["primitives"][0]["mode"] = 9
    bad("gltf-unknown-mode.gltf", g.gltf(), "mode 9")
    g = lit_gltf()
    g.doc["meshes"][1]["primitives"][0]["indices"] = g.indices([0, 0, 1, 0, 2, 0, 0, 0, 2, 0, 3, 0])
    g.doc["accessors"][-1]["count"] = 6
    g.doc["bufferViews"][-1]["byteStride"] = 4
    bad("gltf-index-view-stride.gltf", g.gltf(), "byteStride")

    g = lit_gltf()
    g.doc["scene"] = 4
    bad("gltf-default-scene-missing.gltf", g.gltf(), "scene 4 does not exist")
    g = lit_gltf()
    g.doc["extensionsUsed"] = ["EXT_texture_webp"]
    odd("gltf-optional-extension.gltf", g.gltf(), "EXT_texture_webp", {"same_as": "gltf-lit-reference.gltf"})

    def sparse_gltf(index_type=5123, indices=(1,), count=None):
        g = lit_gltf()
        fmt = {5121: "B", 5123: "H", 5125: "I", 5126: "f"}[index_type]
        iv = g.view(struct.pack("<%d%s" % (len(indices), fmt), *indices))
        vv = g.view(struct.pack("<%df" % (3 * len(indices)), *([0.0] * 3 * len(indices))))
        g.doc["accessors"][1]["sparse"] = {
            "count": len(indices) if count is None else count,
            "indices": {"bufferView": iv, "componentType": index_type}, "values": {"bufferView": vv}}
        return g
    bad("gltf-sparse-index-outside.gltf", sparse_gltf(indices=(1, 60)).gltf(), "substitutes element 60")
    bad("gltf-sparse-float-indices.gltf", sparse_gltf(index_type=5126, indices=(1.0,)).gltf(),
        "not unsigned integers")
    g = sparse_gltf(indices=tuple(range(7)))
    bad("gltf-sparse-count-over.gltf", g.gltf(), "substitutes 7 of its 6")

    g = lit_gltf()
    g.doc["materials"][1]["emissiveFactor"] = [1e39, 4, 4]  # beyond float: infinite once loaded
    bad("gltf-emission-infinite.gltf", g.gltf(), "emission (inf")
    g = lit_gltf()
    g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = [-1, 0.5, 0.5, 1]
    bad("gltf-base-color-negative.gltf", g.gltf(), "base colour")
    g = lit_gltf()
    g.doc["materials"][1]["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": -3}}
    bad("gltf-emissive-strength-negative.gltf", g.gltf(), "emission")

    # KHR_materials_volume outside its schema: the loader names the material and the value.
    def volume_gltf(volume):
        g = lit_gltf()
        g.doc["materials"][0]["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                               "KHR_materials_volume": volume}
        g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_materials_transmission", "KHR_materials_volume"]
        return g.gltf()
    bad("gltf-volume-distance-negative.gltf", volume_gltf({"attenuationDistance": -2.0}),
        "material 0: KHR_materials_volume attenuationDistance -2 is not positive")
    bad("gltf-volume-colour-above-1.gltf",
        volume_gltf({"attenuationColor": [0.5, 1.2, 0.5], "attenuationDistance": 1.0}),
        "attenuationColor (0.5, 1.2, 0.5) is outside [0, 1]")
    bad("gltf-volume-colour-string.gltf", volume_gltf({"attenuationColor": "red"}),
        "attenuationColor is not an array of three numbers")
    bad("gltf-volume-thickness-negative.gltf", volume_gltf({"thicknessFactor": -1.0}), "thicknessFactor is negative")

    g = Gltf()
    g.node({"mesh": g.mesh([[(0, 0, 0), (1, 0, 0), (2, 0, 0)], [(0, 1, 0), (0, 1, 0), (0, 1, 0)]],
                           g.material((0, 0, 0), (4.0, 4.0, 4.0)))})
    bad("gltf-all-degenerate.gltf", g.gltf(), "nothing to render")
    g = Gltf()
    g.node({"mesh": g.mesh([[(NAN, 0, 0), (1, 0, 0), (0, 1, 0)]], g.material((0, 0, 0), (4.0, 4.0, 4.0)))})
    bad("gltf-all-nan.gltf", g.gltf(), "nothing to render")

    # A scale of 0 is legal (it hides a node), but said: the wall vanishes, the light stays.
    light_only = lit_gltf()
    light_only.doc["scenes"][0]["nodes"] = [0]
    put("gltf-light-only-reference.gltf", light_only.gltf())
    g = lit_gltf()
    g.doc["nodes"][1]["scale"] = [0, 0, 0]
    odd("gltf-zero-scale.gltf", g.gltf(), "singular transform", {"same_as": "gltf-light-only-reference.gltf"})


def make_glb():
    valid = lit_gltf().glb()
    bad("glb-wrong-magic.glb", b"gLTF" + valid[4:], "bad header")
    bad("glb-version-1.glb", valid[:4] + struct.pack("<I", 1) + valid[8:], "version 1")
    bad("glb-header-only.glb", valid[:12], "bad header")
    bad("glb-truncated.glb", valid[: len(valid) * 2 // 3], "truncated")
    lying = bytearray(valid)
    json_length = struct.unpack_from("<I", valid, 12)[0]
    struct.pack_into("<I", lying, 20 + json_length, 0x7FFFFFF0)
    bad("glb-chunk-overrun.glb", bytes(lying), "runs past the end")
    big = bytearray(valid)
    struct.pack_into("<I", big, 8, 0xFFFFFFFF)
    bad("glb-length-4gib.glb", bytes(big), "truncated")
    bad("glb-json-garbage.glb", lit_gltf().glb(json_override=b"{ not json ]"), "invalid glTF")
    bad("glb-no-bin-chunk.glb", lit_gltf().glb(bin_chunk=False), "")
    g = lit_gltf()
    g.doc["accessors"][1]["count"] = 1 << 40
    bad("glb-count-2pow40.glb", g.glb(), "overruns")
    bad("glb-binary-garbage.glb", garbage(3, 4096), "bad header")
    odd("glb-no-light.glb", unlit_gltf().glb(), "no light", "black")


# ---------------------------------------------------------------- OBJ
QUAD_LIGHT = """v -1 -1 -0.5
v 1 -1 -0.5
v 1 1 -0.5
v -1 1 -0.5
f 1 2 3 4
"""


def make_obj():
    bad("obj-index-out-of-range.obj", QUAD_LIGHT + "f 1 2 9\n", "out of range")
    bad("obj-negative-index.obj", QUAD_LIGHT + "f -1 -2 -9\n", "out of range")
    bad("obj-zero-index.obj", QUAD_LIGHT + "f 0 1 2\n", "")
    bad("obj-texcoord-out-of-range.obj", QUAD_LIGHT + "vt 0 0\nf 1/1 2/5 3/1\n", "texture coordinate")
    bad("obj-empty.obj", "", "no triangles")
    bad("obj-comments-only.obj", "# nothing here\n" * 20, "no triangles")
    bad("obj-lines-and-points-only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\np 1 2\n", "no triangles")
    bad("obj-binary-garbage.obj", garbage(4, 4096), "")
    bad("obj-huge-indices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "face index")
    odd("obj-no-light.obj", QUAD_LIGHT, "no light", "black")
    odd("obj-missing-mtl.obj", "mtllib missing-library.mtl\nusemtl light\n" + QUAD_LIGHT,
        "missing-library.mtl", "black")
    put("obj-missing-texture.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nmap_Kd missing-texture.png\n")
    odd("obj-missing-texture.obj", "mtllib obj-missing-texture.mtl\nusemtl wall\n" + QUAD_LIGHT,
        "missing-texture.png", "black")
    odd("obj-two-vertex-faces.obj", QUAD_LIGHT + "f 1 2\nf 3\n", "Degenerated face", "black")
    odd("obj-nan-vertices.obj", QUAD_LIGHT + "v nan nan nan\nv inf 0 0\nf 5 6 1\n", "non-finite", "black")
    # Numbers are read whole (docs/input.md): each of these once loaded as some other scene.
    bad("obj-bad-number.obj", QUAD_LIGHT.replace("v 1 1 -0.5", "v 1 1.5abc -0.5"), "line 3: '1.5abc'")
    bad("obj-decimal-comma.obj", QUAD_LIGHT.replace("v 1 -1 -0.5", "v 1,25 -1 -0.5"), "line 2: '1,25'")
    bad("obj-hex-number.obj", QUAD_LIGHT.replace("v -1 1 -0.5", "v 0x10 1 -0.5"), "not a number")
    bad("obj-two-coordinates.obj", QUAD_LIGHT.replace("v -1 -1 -0.5", "v -1 -1"), "needs at least 3")
    bad("obj-bad-texcoord.obj", QUAD_LIGHT + "vt 0.5 half\n", "'half'")
    bad("obj-bad-face-token.obj", QUAD_LIGHT + "f 1 2x 3\n", "'2x'")
    bad("obj-face-float-index.obj", QUAD_LIGHT + "f 1 2.0 3\n", "'2.0'")
    bad("obj-all-nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "nothing to render")
    bad("obj-all-degenerate.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n", "nothing to render")
    put("obj-infinite-colour.mtl", "newmtl wall\nKd 1e39 0.5 0.5\n")
    bad("obj-infinite-colour.obj", "mtllib obj-infinite-colour.mtl\nusemtl wall\n" + QUAD_LIGHT, "base colour")
    put("obj-bad-mtl-number.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nKe 4 4 4x\n")
    bad("obj-bad-mtl-number.obj", "mtllib obj-bad-mtl-number.mtl\nusemtl wall\n" + QUAD_LIGHT,
        "obj-bad-mtl-number.mtl: line 3: '4x' in Ke")
    put("obj-corrupt-texture.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nmap_Kd obj-corrupt-texture.png\n")
    put("obj-corrupt-texture.png", b"\x89PNG\r\n\x1a\n" + garbage(10, 64))
    bad("obj-corrupt-texture.obj", "mtllib obj-corrupt-texture.mtl\nusemtl wall\nvt 0 0\n" +
        QUAD_LIGHT.replace("f 1 2 3 4", "f 1/1 2/1 3/1 4/1"), "cannot be decoded")
    odd("obj-inline-comment.obj", QUAD_LIGHT.replace("v 1 1 -0.5", "v 1 1 -0.5 # corner"), "no light", "black")


# ---------------------------------------------------------------- PLY
def ply_header(fmt, vertices, faces, vertex_props="property float x\nproperty float y\nproperty float z\n",
               face_prop="property list uchar int vertex_indices\n"):
    h = "ply\nformat %s 1.0\n" % fmt
    if vertices is not None:
        h += "element vertex %d\n%s" % (vertices, vertex_props)
    if faces is not None:
        h += "element face %d\n%s" % (faces, face_prop)
    return h + "end_header\n"


PLY_VERTS = [(-1, -1, -0.5), (1, -1, -0.5), (1, 1, -0.5), (-1, 1, -0.5)]


def ply_ascii(verts, faces, header=None):
    body = "".join(" ".join(str(x) for x in v) + "\n" for v in verts) + "".join(
        "%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces)
    return (header or ply_header("ascii", len(verts), len(faces))) + body


def ply_binary(verts, faces, big=False, count_format="B"):
    e = ">" if big else "<"
    count_type = {"B": "uchar", "b": "char"}[count_format]
    body = b"".join(struct.pack(e + "3f", *v) for v in verts)
    for f in faces:
        body += struct.pack(e + count_format, len(f)) + struct.pack(e + "%di" % len(f), *f)
    fmt = "binary_big_endian" if big else "binary_little_endian"
    face_prop = "property list %s int vertex_indices\n" % count_type
    return ply_header(fmt, len(verts), len(faces), face_prop=face_prop).encode() + body


def make_ply():
    quad = [[0, 1, 2, 3]]
    bad("ply-wrong-magic.ply", "plx\n" + ply_ascii(PLY_VERTS, quad)[4:], "no 'ply' magic")
    bad("ply-no-end-header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "end_header")
    bad("ply-no-format.ply", "ply\nelement vertex 0\nend_header\n", "no format line")
    bad("ply-unknown-format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown PLY format")
    bad("ply-unknown-type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
        "unknown property type")
    bad("ply-bad-element-count.ply", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "bad element line")
    bad("ply-faces-2pow40-ascii.ply",
        ply_ascii(PLY_VERTS, quad, ply_header("ascii", 4, 1 << 40)), "header claims")
    bin_quad = ply_binary(PLY_VERTS, quad)
    bad("ply-faces-2pow40-binary.ply",
        bin_quad.replace(b"element face 1\n", b"element face %d\n" % (1 << 40)), "header claims")
    bad("ply-vertices-2pow64.ply",
        ply_ascii(PLY_VERTS, quad, ply_header("ascii", 0, 1)).replace("element vertex 0", "element vertex 18446744073709551616"),
        "bad element line")
    bad("ply-truncated-binary.ply", bin_quad[: len(bin_quad) - 7], "file ends inside")
    bad("ply-index-out-of-range.ply", ply_ascii(PLY_VERTS, [[0, 1, 7]]), "refers to vertex 7")
    bad("ply-negative-index.ply", ply_ascii(PLY_VERTS, [[0, 1, -1]]), "invalid vertex index")
    bad("ply-negative-index-binary.ply", ply_binary(PLY_VERTS, [[0, -5, 2]], big=True), "invalid vertex index")
    bad("ply-fractional-index.ply", ply_ascii(PLY_VERTS, [[0, 1, 2.5]]), "'2.5' is not a 4-byte signed integer")
    bad("ply-bad-number.ply", ply_ascii(PLY_VERTS, quad).replace("-0.5", "abc", 1), "line 10: bad number 'abc'")
    bad("ply-missing-xyz.ply",
        ply_ascii(PLY_VERTS, quad, ply_header("ascii", 4, 1, "property float x\nproperty float y\nproperty float w\n")),
        "lacks scalar x, y and z")
    bad("ply-no-face-list.ply",
        ply_ascii(PLY_VERTS, quad, ply_header("ascii", 4, 1, face_prop="property int vertex_indices\n")),
        "lacks a vertex_indices list")
    neg = ply_binary(PLY_VERTS, [[0, 1, 2]], count_format="b")
    bad("ply-negative-list-length.ply", neg[:-13] + struct.pack("<b", -3) + neg[-12:], "bad list length")
    bad("ply-vertices-only.ply", ply_ascii(PLY_VERTS, [], ply_header("ascii", 4, None)), "no triangles")
    bad("ply-edges-only.ply", ply_ascii(PLY_VERTS, [[0, 1], [1, 2], [2]]), "no triangles")
    bad("ply-binary-garbage.ply", garbage(5, 4096), "no 'ply' magic")
    bad("ply-garbage-after-header.ply", ply_header("binary_little_endian", 4, 1).encode() + garbage(6, 20),
        "")
    odd("ply-no-light.ply", ply_ascii(PLY_VERTS, quad), "no light", "black")
    # Headers that lie (docs/input.md): each item is one line, and nothing may follow the last one.
    bad("ply-number-suffix.ply", ply_ascii(PLY_VERTS, quad).replace("-0.5", "-0.5f", 1), "bad number '-0.5f'")
    bad("ply-extra-values.ply", ply_ascii([v + (7,) for v in PLY_VERTS], quad), "line 10: more values")
    bad("ply-missing-values.ply", ply_ascii([v[:2] for v in PLY_VERTS], quad), "line 10: the line ends")
    bad("ply-fewer-faces-declared.ply", ply_ascii(PLY_VERTS, [[0, 1, 2], [0, 2, 3]],
                                                  ply_header("ascii", 4, 1)), "data after the last element")
    bad("ply-fewer-faces-declared-binary.ply",
        ply_binary(PLY_VERTS, [[0, 1, 2], [0, 2, 3]]).replace(b"element face 2\n", b"element face 1\n"),
        "bytes after the last element")
    bad("ply-list-count-overflow.ply", ply_ascii(PLY_VERTS, quad).replace("\n4 0 1 2 3", "\n260 0 1 2 3"),
        "'260' is not a 1-byte unsigned integer")
    bad("ply-version-2.ply", ply_ascii(PLY_VERTS, quad).replace("ascii 1.0", "ascii 2.0"), "PLY version '2.0'")
    bad("ply-two-vertex-elements.ply",
        ply_ascii(PLY_VERTS, quad).replace("element face", "element vertex 0\nproperty float x\nelement face"),
        "element 'vertex' declared twice")
    bad("ply-all-nan.ply", ply_ascii([("nan", 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 2]]), "nothing to render")
    odd("ply-nan-vertices.ply", ply_ascii(PLY_VERTS + [("nan", "nan", "nan"), ("inf", "-inf", 0)], quad + [[4, 5, 0]]),
        "non-finite", "black")


# ---------------------------------------------------------------- gzip
def gz(data):
    return gzip.compress(data.encode() if isinstance(data, str) else data, mtime=0)


def make_gzip():
    good = gz(QUAD_LIGHT)
    bad("gz-corrupt.obj.gz", good[:10] + garbage(7, len(good) - 10), "gzip")
    bad("gz-truncated.ply.gz", gz(ply_ascii(PLY_VERTS, [[0, 1, 2, 3]]))[:-12], "truncated")
    # Cut inside the deflate stream, as a download stopped half way: the first half inflates fine.
    many = QUAD_LIGHT + "".join("v %d %d 0\n" % (i, i * 7 % 13) for i in range(4000))
    long_gz = gz(many)
    bad("gz-cut-half.obj.gz", long_gz[: len(long_gz) // 2], "truncated")
    bad("gz-cut-trailer.obj.gz", long_gz[:-8], "truncated")
    bad("gz-cut-second-member.obj.gz", gz(QUAD_LIGHT) + long_gz[: len(long_gz) // 2], "truncated")
    wrong_length = bytearray(long_gz)
    wrong_length[-1] ^= 0x10
    bad("gz-bad-length.obj.gz", bytes(wrong_length), "corrupt")
    odd("gz-two-members.obj.gz", gz(QUAD_LIGHT[:30]) + gz(QUAD_LIGHT[30:]), "no light", "black")
    bad("gz-not-gzip.gltf.gz", lit_gltf().gltf()[:2000], "gzip")
    bad("gz-empty.glb.gz", b"", "gzip")
    crc = bytearray(good)
    crc[-8] ^= 0xFF
    bad("gz-bad-crc.obj.gz", bytes(crc), "corrupt")
    bad("gz-trailing-garbage.obj.gz", good + b"\x01\x02garbage", "gzip")
    bad("gz-inner-garbage.glb.gz", gz(garbage(8, 2048)), "bad header")
    bad("gz-inner-empty.ply.gz", gz(b""), "no 'ply' magic")
    # 10 MB of comment lines in 10 KB: inflates fine, holds no triangles.
    bad("gz-comment-bomb.obj.gz", gz("#" * 10_000_000 + "\n"), "no triangles")
    odd("gz-no-light.obj.gz", good, "no light", "black")


# ---------------------------------------------------------------- anything else
def make_other():
    bad("unknown-extension.fbx", "Kaydara FBX Binary  \0\x1a\0", "unknown scene format")
    bad("no-extension", QUAD_LIGHT, "unknown scene format")
    bad("gltf-really-obj.gltf", QUAD_LIGHT, "invalid glTF")
    bad("obj-really-png.obj", b"\x89PNG\r\n\x1a\n" + garbage(9, 200), "")
    runtime("directory.gltf", "directory", 2, "not a regular file")
    runtime("unreadable.obj", "unreadable", 2, "cannot open")
    runtime("does-not-exist.ply", "missing", 2, "no such file")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=HERE)
    args = parser.parse_args()
    make_gltf()
    make_glb()
    make_obj()
    make_ply()
    make_gzip()
    make_other()
    args.out.mkdir(parents=True, exist_ok=True)
    for name, data in FILES.items():
        (args.out / name).write_bytes(data)
    manifest = {"note": "Written by make-corpus.py; its docstring describes the fields.", "entries": ENTRIES}
    (args.out / "expected.json").write_text(json.dumps(manifest, indent=1) + "\n")
    print("wrote %d files, %d manifest entries to %s" % (len(FILES), len(ENTRIES), args.out))


if __name__ == "__main__":
    main()
