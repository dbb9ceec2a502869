#!/usr/bin/env python3
"""Writes the scenes shipped in scenes/ (Python 3 standard library only).

    scripts/make-scenes.py [--shared DIR] [--out scenes]

The outputs are committed, so the project works without the external models (scenes/external.json); rerun this script only to
change them. The Cornell box needs the external model cornell-box-mitsuba (its geometry is Mitsuba's);
without it the other scenes are still written.
"""

import argparse
import base64
import json
import math
import pathlib
import struct
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Mitsuba cbox, fragments/bsdfs-rgb.xml and cbox-rgb.xml (docs/decisions.md).
CBOX_ALBEDO = {
    "white": (0.885809, 0.698859, 0.666422),
    "red": (0.570068, 0.0430135, 0.0443706),
    "green": (0.105421, 0.37798, 0.076425),
    "box": (0.45, 0.30, 0.90),
    "light": (0.936461, 0.740433, 0.705267),
}
CBOX_RADIANCE = (18.387, 10.9873, 2.75357)
# shapes.xml: mesh file -> material; the luminaire is translated by y -0.5.
CBOX_SHAPES = [
    ("cbox_luminaire.obj", "light"),
    ("cbox_floor.obj", "white"),
    ("cbox_ceiling.obj", "white"),
    ("cbox_back.obj", "white"),
    ("cbox_greenwall.obj", "green"),
    ("cbox_redwall.obj", "red"),
    ("cbox_smallbox.obj", "box"),
    ("cbox_largebox.obj", "box"),
]
CBOX_ROOM_CENTRE = (278.0, 274.4, 279.6)


# ---------------------------------------------------------------- vector helpers
def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def centroid(points):
    return tuple(sum(c) / len(points) for c in zip(*points))


def normal(tri):
    return cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]))


# ---------------------------------------------------------------- glTF writer
class Gltf:
    """Accumulates one embedded buffer and the JSON that indexes it."""

    def __init__(self, generator_note):
        self.blob = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "cohort scripts/make-scenes.py",
                      "extras": {"note": generator_note}},
            "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
            "accessors": [], "bufferViews": [], "buffers": [],
        }
        self.extensions = set()

    def _view(self, data, target):
        while len(self.blob) % 4:
            self.blob.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob),
                                        "byteLength": len(data), "target": target})
        self.blob.extend(data)
        return len(self.doc["bufferViews"]) - 1

    def positions(self, points):
        data = b"".join(struct.pack("<3f", *p) for p in points)
        view = self._view(data, 34962)
        lo = [min(p[i] for p in points) for i in range(3)]
        hi = [max(p[i] for p in points) for i in range(3)]
        # min/max must be the float32 values actually stored.
        lo = [struct.unpack("<f", struct.pack("<f", x))[0] for x in lo]
        hi = [struct.unpack("<f", struct.pack("<f", x))[0] for x in hi]
        return self._accessor(view, 5126, len(points), "VEC3", min=lo, max=hi)

    def indices(self, values, component=5123):
        fmt = {5121: "B", 5123: "H", 5125: "I"}[component]
        view = self._view(struct.pack("<%d%s" % (len(values), fmt), *values), 34963)
        return self._accessor(view, component, len(values), "SCALAR")

    def _accessor(self, view, component, count, kind, **extra):
        self.doc["accessors"].append(dict(bufferView=view, componentType=component, count=count,
                                          type=kind, **extra))
        return len(self.doc["accessors"]) - 1

    def material(self, name, base, emission=None, strength=1.0, double_sided=False):
        m = {"name": name, "doubleSided": double_sided,
             "pbrMetallicRoughness": {"baseColorFactor": list(base) + [1.0], "metallicFactor": 0.0,
                                      "roughnessFactor": 1.0}}
        if emission is not None:
            m["emissiveFactor"] = list(emission)
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
            self.extensions.add("KHR_materials_emissive_strength")
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def mesh(self, name, triangles, material, index_component=5123, indexed=True):
        """Adds a mesh node from a list of triangles (counter-clockwise front faces)."""
        points, idx, seen = [], [], {}
        for tri in triangles:
            for p in tri:
                if not indexed or p not in seen:
                    seen[p] = len(points)
                    points.append(p)
                idx.append(seen[p] if indexed else len(points) - 1)
        primitive = {"attributes": {"POSITION": self.positions(points)}, "material": material, "mode": 4}
        if indexed:
            primitive["indices"] = self.indices(idx, index_component)
        self.doc["meshes"].append({"name": name, "primitives": [primitive]})
        self.node({"name": name, "mesh": len(self.doc["meshes"]) - 1})

    def camera(self, name, yfov_degrees, translation=None, rotation=None, znear=0.01, zfar=None):
        cam = {"type": "perspective",
               "perspective": {"yfov": math.radians(yfov_degrees), "aspectRatio": 1.0, "znear": znear}}
        if zfar is not None:
            cam["perspective"]["zfar"] = zfar
        self.doc.setdefault("cameras", []).append(cam)
        node = {"name": name, "camera": len(self.doc["cameras"]) - 1}
        if translation is not None:
            node["translation"] = list(translation)
        if rotation is not None:
            node["rotation"] = list(rotation)
        self.node(node)

    def node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.blob), "uri": "data:application/octet-stream;base64,"
                                + base64.b64encode(bytes(self.blob)).decode("ascii")}]
        if self.extensions:
            self.doc["extensionsUsed"] = sorted(self.extensions)
        path.write_text(json.dumps(self.doc, indent=1) + "\n")
        print("wrote %s" % path)


# ---------------------------------------------------------------- Cornell box
def read_obj_polygons(path):
    verts, faces = [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            verts.append(tuple(float(x) for x in parts[1:4]))
        elif parts[0] == "f":
            faces.append([verts[int(tok.split("/")[0]) - 1] for tok in parts[1:]])
    return faces


def fan(polygon):
    # Mitsuba's OBJ reader fans from the first corner; the red wall is not planar, so the
    # diagonal matters for matching its render.
    return [(polygon[0], polygon[k], polygon[k + 1]) for k in range(1, len(polygon) - 1)]


def orient(tri, direction):
    """Returns tri, rewound if its normal points against `direction`, and whether it was."""
    if dot(normal(tri), direction) < 0:
        return (tri[0], tri[2], tri[1]), True
    return tri, False


def cornell_triangles(mesh_dir, filename, material):
    triangles = [t for poly in read_obj_polygons(mesh_dir / filename) for t in fan(poly)]
    if material == "light":
        triangles = [tuple((p[0], p[1] - 0.5, p[2]) for p in t) for t in triangles]
    box_centre = centroid([p for t in triangles for p in t]) if material == "box" else None
    out, flips = [], 0
    for tri in triangles:
        c = centroid(tri)
        if material == "light":
            want = (0.0, -1.0, 0.0)  # emits down into the box
        elif material == "box":
            want = sub(c, box_centre)  # block faces point out of the block, into the room
        else:
            # Walls face into the room. Only the ceiling's second quad (the hidden patch above the
            # luminaire) faces up in Mitsuba's data, so rewinding it cannot change a render.
            want = sub(CBOX_ROOM_CENTRE, c)
        tri, flipped = orient(tri, want)
        flips += flipped
        out.append(tri)
    return out, flips


def cornell_box(shared, out_dir):
    mesh_dir = shared / "cornell-box-mitsuba" / "meshes"
    if not mesh_dir.is_dir():
        print("skipping cornell-box.gltf: %s not found" % mesh_dir, file=sys.stderr)
        return
    g = Gltf("Geometry of Mitsuba's cbox (mitsuba-renderer/mitsuba-data scenes/cbox), RGB albedos of "
             "its bsdfs-rgb.xml, area light radiance of cbox-rgb.xml, camera of base.xml.")
    materials = {}
    for name, albedo in CBOX_ALBEDO.items():
        if name == "light":
            peak = max(CBOX_RADIANCE)
            materials[name] = g.material(name, albedo, [c / peak for c in CBOX_RADIANCE], peak)
        else:
            materials[name] = g.material(name, albedo)
    for filename, material in CBOX_SHAPES:
        triangles, flips = cornell_triangles(mesh_dir, filename, material)
        if flips:
            print("  %s: %d triangle(s) rewound to face %s" % (filename, flips,
                  "down" if material == "light" else "into the room"))
        g.mesh(filename[:-4], triangles, materials[material])
    # glTF cameras look down -Z; a half turn about Y looks down +Z as Mitsuba's lookat does.
    g.camera("camera", 39.3077, translation=(278.0, 273.0, -800.0), rotation=(0.0, 1.0, 0.0, 0.0),
             znear=10.0, zfar=2800.0)
    g.write(out_dir / "cornell-box.gltf")


# ---------------------------------------------------------------- furnace sphere
def furnace_sphere(out_dir, segments=64, rings=32):
    """A closed unit UV sphere seen from inside: emission 1, albedo 0.5, so L = 1 / (1 - 0.5) = 2."""
    def point(ring, seg):
        theta = math.pi * ring / rings
        phi = 2.0 * math.pi * (seg % segments) / segments
        if ring == 0:
            return (0.0, 1.0, 0.0)
        if ring == rings:
            return (0.0, -1.0, 0.0)
        return (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))

    triangles = []
    for r in range(rings):
        for s in range(segments):
            a, b = point(r, s), point(r, s + 1)
            c, d = point(r + 1, s), point(r + 1, s + 1)
            if r > 0:
                triangles.append((a, b, d))
            if r < rings - 1:
                triangles.append((a, d, c))
    # Front faces must point at the centre.
    triangles = [orient(t, tuple(-x for x in centroid(t)))[0] for t in triangles]
    g = Gltf("Furnace test: closed unit sphere facing inward, albedo 0.5, emission 1.")
    m = g.material("furnace", (0.5, 0.5, 0.5), (1.0, 1.0, 1.0), 1.0)
    g.mesh("sphere", triangles, m)
    g.camera("camera", 60.0)
    g.write(out_dir / "furnace-sphere.gltf")


# ---------------------------------------------------------------- small test scenes
def single_triangle(out_dir):
    g = Gltf("One emissive triangle facing +Z, camera on +Z looking at it.")
    m = g.material("emitter", (0.8, 0.8, 0.8), (1.0, 1.0, 1.0), 1.0)
    g.mesh("triangle", [((-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 1.0, 0.0))], m, indexed=False)
    g.camera("camera", 45.0, translation=(0.0, 0.0, 4.0))
    g.write(out_dir / "single-triangle.gltf")


def voxel_heights(size=12, seed=3):
    """Column heights 1-5 of a size x size terrain, from a 32-bit LCG (deterministic)."""
    state, heights = seed, []
    for _ in range(size * size):
        state = (state * 1664525 + 1013904223) % 2**32
        heights.append(1 + (state >> 16) % 5)
    return [heights[z * size:(z + 1) * size] for z in range(size)]


def voxel_terrain(out_dir, size=12):
    """Unit blocks stacked on a size x size grid: only the faces open to the air, two triangles each,
    every one in an integer plane, so the KD-tree's split planes hold flat triangles and paths bounce
    off concave corners with origins on those planes (the case the split-plane tests cover)."""
    h = voxel_heights(size)
    top, side = [], []

    def quad(a, b, c, d, into):
        into.append((a, b, c))
        into.append((a, c, d))

    def height(x, z):
        return h[z][x] if 0 <= x < size and 0 <= z < size else 0

    for z in range(size):
        for x in range(size):
            y = float(h[z][x])
            quad((x, y, z + 1.0), (x + 1.0, y, z + 1.0), (x + 1.0, y, float(z)), (float(x), y, float(z)), top)
            # side faces above the lower neighbour, one unit block at a time
            for dx, dz in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                for level in range(height(x + dx, z + dz), h[z][x]):
                    y0, y1 = float(level), float(level + 1)
                    if dx == 1:
                        quad((x + 1.0, y0, z + 1.0), (x + 1.0, y0, float(z)), (x + 1.0, y1, float(z)), (x + 1.0, y1, z + 1.0), side)
                    elif dx == -1:
                        quad((float(x), y0, float(z)), (float(x), y0, z + 1.0), (float(x), y1, z + 1.0), (float(x), y1, float(z)), side)
                    elif dz == 1:
                        quad((float(x), y0, z + 1.0), (x + 1.0, y0, z + 1.0), (x + 1.0, y1, z + 1.0), (float(x), y1, z + 1.0), side)
                    else:
                        quad((x + 1.0, y0, float(z)), (float(x), y0, float(z)), (float(x), y1, float(z)), (x + 1.0, y1, float(z)), side)
    g = Gltf("Voxel terrain: %dx%d unit columns 1-5 high (LCG heights), open faces only, lit by a square "
             "emitter above; every triangle lies in an integer plane." % (size, size))
    grass = g.material("grass", (0.35, 0.6, 0.25))
    dirt = g.material("dirt", (0.55, 0.4, 0.3))
    light = g.material("light", (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), 20.0)
    g.mesh("tops", top, grass)
    g.mesh("sides", side, dirt)
    c = size / 2.0
    quad_light = []
    quad((c - 2.0, 12.0, c - 2.0), (c + 2.0, 12.0, c - 2.0), (c + 2.0, 12.0, c + 2.0), (c - 2.0, 12.0, c + 2.0), quad_light)
    g.mesh("light", quad_light, light)
    # from the -z, +x corner, looking at the centre and down: a quarter turn about Y, then a tilt
    yaw, pitch = math.radians(-35.0), math.radians(-35.0)
    qy = (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))
    q = (qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
         qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
         qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
         qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2])
    dist = 19.0
    fwd = (-math.sin(yaw) * math.cos(pitch), math.sin(pitch), -math.cos(yaw) * math.cos(pitch))
    eye = (c - dist * fwd[0], 2.0 - dist * fwd[1], c - dist * fwd[2])
    g.camera("camera", 45.0, translation=eye, rotation=q)
    g.write(out_dir / "voxel-terrain.gltf")
    return len(top) + len(side) + 2


QUAD_LIGHT_OBJ = """\
# Floor quad facing up and a smaller emissive quad one unit above it facing down.
# Written by scripts/make-scenes.py.
mtllib quad-light.mtl

o floor
v -1.0 0.0  1.0
v  1.0 0.0  1.0
v  1.0 0.0 -1.0
v -1.0 0.0 -1.0
usemtl floor
f 1 2 3 4

o light
v -0.25 1.0 -0.25
v  0.25 1.0 -0.25
v  0.25 1.0  0.25
v -0.25 1.0  0.25
usemtl light
f 5 6 7 8
"""

QUAD_LIGHT_MTL = """\
# Written by scripts/make-scenes.py.
newmtl floor
Kd 0.8 0.8 0.8
Ke 0 0 0

newmtl light
Kd 0 0 0
Ke 10 10 10
"""


def quad_light(out_dir):
    (out_dir / "quad-light.obj").write_text(QUAD_LIGHT_OBJ)
    (out_dir / "quad-light.mtl").write_text(QUAD_LIGHT_MTL)
    print("wrote %s and %s" % (out_dir / "quad-light.obj", out_dir / "quad-light.mtl"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", type=pathlib.Path, default=ROOT.parent / "shared" / "scenes")
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "scenes")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    cornell_box(args.shared, args.out)
    furnace_sphere(args.out)
    single_triangle(args.out)
    quad_light(args.out)
    voxel_terrain(args.out)


if __name__ == "__main__":
    main()
