#!/usr/bin/env python3
"""Small scenes, one per material and light type, written for both renderers from one description,
and their Mitsuba 3 reference renders (docs/lights.md, "Reference scenes").

For each scene this writes scenes/reference/NAME.gltf (what Cohort renders) and renders the same
triangles with Mitsuba 3 (scalar_rgb): the meshes go to Mitsuba as PLY files with face normals
(Cohort shades with flat normals), the materials as the Mitsuba plugins docs/bsdf.md maps them to,
the camera through look_at, a box filter, max_depth 6. Passes of --pass-spp samples with seeds
0, 1, ... run until --seconds per scene; the mean goes to test/reference/NAME.exr with a JSON file
of the settings beside it, which test/render/reference_scenes_test.cpp reads.

Scenes (64 x 64): conductor (rough GGX conductor, F0 = 1, glTF roughness 0.3), rough-dielectric
(glass of IOR 1.5, roughness 0.3), plastic (smooth plastic over a coloured base), envmap (a
Lambertian sphere under scenes/reference/sky.exr), punctual (a point and a spot light), and two
scenes of the kinds the scale-free ray offset was checked on: on-ground (plastic and metal resting on, and 0.03 above, a 400-wide
ground under a constant sky) and nave (an interior lit only by emissive windows).
Run through scripts/reference, which provides mitsuba and numpy."""
import base64
import json
import math
import os
import platform
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import accumulate_passes, reference_arguments


# --help answers before the imports below, which need the venv's packages
ARGS = reference_arguments(__doc__, "the glTF files and sky.exr") if __name__ == "__main__" else None

import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "scenes", "reference")
REFERENCES = os.path.join(ROOT, "test", "reference")
RES = 64
MAX_DEPTH = 6
CAMERA = {"eye": [0.0, 2.2, 5.5], "target": [0.0, 0.9, 0.0], "up": [0.0, 1.0, 0.0], "fov": 40.0}


# ---- geometry ---------------------------------------------------------------------------------

def quad(o, u, v):
    """Two triangles o, o+u, o+u+v, o+v; the front (and the emitting side) is u x v."""
    o, u, v = (np.array(a, dtype=np.float64) for a in (o, u, v))
    p = np.array([o, o + u, o + u + v, o + v])
    return p, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)


def cuboid(lo, hi):
    """A closed axis-aligned box, front faces outwards."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    p = np.array([[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)], dtype=np.float64)
    # corners indexed 4x + 2y + z; each face counter-clockwise seen from outside
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    f = [[a, b, c] for a, b, c, d in faces] + [[a, c, d] for a, b, c, d in faces]
    return p, np.array(f, dtype=np.uint32)


def icosphere(centre, radius, levels=3):
    t = (1 + math.sqrt(5)) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    v = [list(np.array(p) / np.linalg.norm(p)) for p in v]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
         [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    for _ in range(levels):
        mid = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = np.array(v[a]) + np.array(v[b])
                v.append(list(p / np.linalg.norm(p)))
                mid[key] = len(v) - 1
            return mid[key]

        nf = []
        for a, b, c in f:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        f = nf
    p = np.array(centre) + radius * np.array(v)
    f = np.array(f, dtype=np.uint32)
    # front faces outwards
    for i, (a, b, c) in enumerate(f):
        n = np.cross(p[b] - p[a], p[c] - p[a])
        if np.dot(n, p[a] + p[b] + p[c] - 3 * np.array(centre)) < 0:
            f[i] = [a, c, b]
    return p, f


# ---- materials: one description, both renderers (docs/bsdf.md) ----------------------------------

def diffuse(rgb):
    return {"gltf": {"baseColorFactor": rgb + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "mitsuba": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb_value(rgb)}}}


def rough_conductor(roughness):
    # F0 = 1: Schlick's Fresnel is 1 everywhere, as Mitsuba's material "none"
    return {"gltf": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 1.0, "roughnessFactor": roughness},
            "mitsuba": {"type": "twosided", "bsdf": {"type": "roughconductor", "material": "none",
                                                     "distribution": "ggx", "alpha": roughness ** 2,
                                                     "sample_visible": True}}}


def rough_dielectric(roughness, ior):
    return {"gltf": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": roughness},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                           "KHR_materials_ior": {"ior": ior}},
            "mitsuba": {"type": "roughdielectric", "distribution": "ggx", "alpha": roughness ** 2,
                        "int_ior": ior, "ext_ior": 1.0, "sample_visible": True}}


def smooth_plastic(rgb, ior):
    return {"gltf": {"baseColorFactor": rgb + [1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_ior": {"ior": ior}},
            "mitsuba": {"type": "twosided", "bsdf": {"type": "plastic", "diffuse_reflectance": rgb_value(rgb),
                                                     "int_ior": ior, "ext_ior": 1.0, "nonlinear": False}}}


def emitter(radiance):
    return {"gltf": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "emission": radiance,
            "mitsuba": {"type": "diffuse", "reflectance": rgb_value([0.0, 0.0, 0.0])}}


def rgb_value(rgb):
    return {"type": "rgb", "value": list(rgb)}


# ---- scenes -----------------------------------------------------------------------------------

def room(sphere_material, light=True):
    """Ground, a back wall, a sphere, and (optionally) a square area light facing down."""
    shapes = [("ground", quad([-4, 0, 4], [8, 0, 0], [0, 0, -8]), diffuse([0.5, 0.5, 0.5])),
              ("wall", quad([-4, 0, -3], [8, 0, 0], [0, 5, 0]), diffuse([0.2, 0.4, 0.7])),
              ("sphere", icosphere([0, 1, 0], 1.0), sphere_material)]
    if light:
        shapes.append(("light", quad([-0.75, 3.5, -0.75], [1.5, 0, 0], [0, 0, 1.5]), emitter([8.0, 8.0, 8.0])))
    return shapes


def on_ground():
    """A car's worth of contact (the scale-free ray offset): a smooth plastic body 0.03 above a ground 400 wide and rough
    metal wheels touching it, under a constant sky. An offset of 1e-4 of the diagonal (0.057) is
    wider than the slot under the body."""
    return [("ground", quad([-200, 0, 200], [400, 0, 0], [0, 0, -400]), diffuse([0.5, 0.5, 0.5])),
            ("body", cuboid([-1.2, 0.03, -0.6], [1.2, 0.7, 0.6]), smooth_plastic([0.7, 0.1, 0.1], 1.5)),
            ("wheel-left", icosphere([-0.9, 0.3, 0.75], 0.3, 2), rough_conductor(0.3)),
            ("wheel-right", icosphere([0.9, 0.3, 0.75], 0.3, 2), rough_conductor(0.3))]


def nave():
    """An interior lit only by emissive windows a millimetre inside its wall, with a pillar on the floor."""
    white, warm = diffuse([0.7, 0.7, 0.7]), diffuse([0.7, 0.5, 0.3])
    shapes = [("room", cuboid([-4, 0, -3], [4, 4, 3]), white),
              ("pillar", cuboid([1.2, 0, -1.4], [2.0, 4, -0.6]), warm)]
    for i, z in enumerate((-2.0, 0.5)):
        shapes.append((f"window{i}", quad([-3.999, 1.0, z], [0, 2, 0], [0, 0, 1.5]), emitter([6.0, 5.5, 4.5])))
    return shapes


def spot_to_world(position, direction):
    d = np.array(direction, dtype=np.float64)
    d /= np.linalg.norm(d)
    return np.array(position, dtype=np.float64), d


def scene_list():
    sky = os.path.join(SCENES, "sky.exr")
    return {
        "conductor": {"shapes": room(rough_conductor(0.3)), "environment": [0.1, 0.1, 0.1]},
        "rough-dielectric": {"shapes": room(rough_dielectric(0.3, 1.5)), "environment": [0.1, 0.1, 0.1]},
        "plastic": {"shapes": room(smooth_plastic([0.8, 0.3, 0.2], 1.5)), "environment": [0.1, 0.1, 0.1]},
        "envmap": {"shapes": room(diffuse([0.8, 0.6, 0.3]), light=False), "environment_map": sky},
        "punctual": {"shapes": room(diffuse([0.8, 0.6, 0.3]), light=False),
                     "lights": [{"type": "point", "position": [-1.8, 2.5, 1.5], "intensity": [6.0, 5.0, 4.0]},
                                {"type": "spot", "position": [2.0, 3.5, 1.0], "direction": [-0.5, -1.0, -0.3],
                                 "intensity": [20.0, 14.0, 8.0],
                                 # a narrow transition: glTF's falloff and Mitsuba's differ only there
                                 "inner_cone": math.radians(29.8), "outer_cone": math.radians(30.0)}]},
        "on-ground": {"shapes": on_ground(), "environment": [1.0, 1.0, 1.0],
                      "camera": {"eye": [0.0, 0.8, 5.0], "target": [0.0, 0.35, 0.0], "up": [0.0, 1.0, 0.0],
                                 "fov": 40.0}},
        "nave": {"shapes": nave(),
                 "camera": {"eye": [0.5, 1.6, 2.8], "target": [-0.5, 1.5, -3.0], "up": [0.0, 1.0, 0.0], "fov": 60.0}},
    }


def write_sky(path, w=64, h=32):
    """Sky gradient, a warm sun and a dark ground half: a map the sampler has to follow."""
    img = np.zeros((h, w, 3), dtype=np.float32)
    for y in range(h):
        t = 1.0 - y / (h - 1)
        img[y, :, :] = [0.3 + 0.5 * t, 0.4 + 0.6 * t, 0.6 + 0.9 * t] if y < h // 2 else [0.15, 0.12, 0.1]
    sx, sy = w // 3, h // 5
    img[sy - 1:sy + 2, sx - 1:sx + 2, :] = [40.0, 32.0, 24.0]
    mi.Bitmap(img, pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


# ---- glTF for Cohort --------------------------------------------------------------------------

def write_gltf(path, desc):
    blob = bytearray()
    doc = {"asset": {"version": "2.0", "generator": "scripts/reference --scenes"}, "buffers": [],
           "bufferViews": [], "accessors": [], "meshes": [], "materials": [], "nodes": [], "scenes": [{"nodes": []}],
           "scene": 0, "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior",
                                          "KHR_materials_emissive_strength", "KHR_lights_punctual"]}

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(doc["bufferViews"]) - 1

    for name, (p, f), mat in desc["shapes"]:
        pos = p.astype(np.float32)
        pv = add_view(pos.tobytes(), 34962)
        doc["accessors"].append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3",
                                 "min": pos.min(axis=0).tolist(), "max": pos.max(axis=0).tolist()})
        iv = add_view(f.astype(np.uint32).tobytes(), 34963)
        doc["accessors"].append({"bufferView": iv, "componentType": 5125, "count": int(f.size), "type": "SCALAR"})
        m = {"name": name, "pbrMetallicRoughness": mat["gltf"]}
        ext = dict(mat.get("extensions", {}))
        if "emission" in mat:
            # glTF splits the radiance into a colour in [0, 1] and a strength
            peak = max(mat["emission"])
            m["emissiveFactor"] = [c / peak for c in mat["emission"]]
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": peak}
        if ext:
            m["extensions"] = ext
        doc["materials"].append(m)
        doc["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": len(doc["accessors"]) - 2},
                                                            "indices": len(doc["accessors"]) - 1,
                                                            "material": len(doc["materials"]) - 1}]})
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
    # camera: glTF cameras look down their local -Z with +Y up
    camera = desc.get("camera", CAMERA)
    eye, target, up = (np.array(camera[k], dtype=np.float64) for k in ("eye", "target", "up"))
    back = eye - target
    back /= np.linalg.norm(back)
    right = np.cross(up, back)
    right /= np.linalg.norm(right)
    true_up = np.cross(back, right)
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": math.radians(camera["fov"]),
                                                               "aspectRatio": 1.0, "znear": 0.01}}]
    doc["nodes"].append({"name": "camera", "camera": 0, "matrix": column_major(right, true_up, back, eye)})
    lights = []
    for light in desc.get("lights", []):
        # glTF splits the rgb intensity into a colour in [0, 1] and a scalar intensity
        peak = max(light["intensity"])
        entry = {"type": light["type"], "color": [c / peak for c in light["intensity"]], "intensity": peak}
        node = {"name": light["type"], "extensions": {"KHR_lights_punctual": {"light": len(lights)}}}
        if light["type"] == "spot":
            entry["spot"] = {"innerConeAngle": light["inner_cone"], "outerConeAngle": light["outer_cone"]}
            pos, d = spot_to_world(light["position"], light["direction"])
            z = -d  # the spot shines down its local -Z
            x = np.cross([0.0, 1.0, 0.0] if abs(z[1]) < 0.9 else [1.0, 0.0, 0.0], z)
            x /= np.linalg.norm(x)
            y = np.cross(z, x)
            node["matrix"] = column_major(x, y, z, pos)
        else:
            node["translation"] = list(light["position"])
        lights.append(entry)
        doc["nodes"].append(node)
    if lights:
        doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
    write_gltf_file(path, doc, blob)


def write_gltf_file(path, doc, blob):
    """Every node in the scene, `blob` as the one embedded buffer, and the document written to `path`."""
    doc["scenes"][0]["nodes"] = list(range(len(doc["nodes"])))
    doc["buffers"].append({"byteLength": len(blob),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()})
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def column_major(x, y, z, t):
    return [float(v) for v in (*x, 0.0, *y, 0.0, *z, 0.0, *t, 1.0)]


# ---- Mitsuba ----------------------------------------------------------------------------------

def write_ply(path, p, f, uv=None):
    """An ASCII PLY of positions `p`, triangles `f` and, when given, texture coordinates `uv`."""
    with open(path, "w") as out:
        out.write(f"ply\nformat ascii 1.0\nelement vertex {len(p)}\nproperty float x\nproperty float y\n"
                  "property float z\n" + ("property float u\nproperty float v\n" if uv is not None else "") +
                  f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n")
        for i, v in enumerate(p.astype(np.float32)):
            extra = f" {float(uv[i][0]):.9g} {float(uv[i][1]):.9g}" if uv is not None else ""
            out.write(f"{float(v[0]):.9g} {float(v[1]):.9g} {float(v[2]):.9g}{extra}\n")
        for t in f:
            out.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def look_at(origin, target, up):
    try:
        return mi.ScalarTransform4f().look_at(origin=origin, target=target, up=up)
    except TypeError:
        return mi.ScalarTransform4f.look_at(origin=origin, target=target, up=up)


def mitsuba_scene(desc, tmp):
    camera = desc.get("camera", CAMERA)
    scene = {"type": "scene",
             "integrator": {"type": "path", "max_depth": MAX_DEPTH},
             "sensor": {"type": "perspective", "fov": camera["fov"], "fov_axis": "y", "near_clip": 0.01,
                        "to_world": look_at(camera["eye"], camera["target"], camera["up"]),
                        "sampler": {"type": "independent"},
                        "film": {"type": "hdrfilm", "width": RES, "height": RES, "pixel_format": "rgb",
                                 "rfilter": {"type": "box"}}}}
    for name, (p, f), mat in desc["shapes"]:
        path = os.path.join(tmp, name + ".ply")
        write_ply(path, p, f)
        shape = {"type": "ply", "filename": path, "face_normals": True, "bsdf": mat["mitsuba"]}
        if "emission" in mat:
            shape["emitter"] = {"type": "area", "radiance": rgb_value(mat["emission"])}
        scene[name] = shape
    if "environment" in desc:
        scene["environment"] = {"type": "constant", "radiance": rgb_value(desc["environment"])}
    if "environment_map" in desc:
        scene["environment"] = {"type": "envmap", "filename": desc["environment_map"]}
    for i, light in enumerate(desc.get("lights", [])):
        if light["type"] == "point":
            scene[f"light{i}"] = {"type": "point", "position": light["position"],
                                  "intensity": rgb_value(light["intensity"])}
        else:
            pos, d = spot_to_world(light["position"], light["direction"])
            scene[f"light{i}"] = {"type": "spot", "intensity": rgb_value(light["intensity"]),
                                  "cutoff_angle": math.degrees(light["outer_cone"]),
                                  "beam_width": math.degrees(light["inner_cone"]),
                                  "to_world": look_at(pos.tolist(), (pos + d).tolist(),
                                                      [0, 1, 0] if abs(d[1]) < 0.9 else [1, 0, 0])}
    return mi.load_dict(scene)


def render_reference(name, scene, args, integrator, max_depth, extra):
    """Renders a loaded Mitsuba scene in passes (accumulate_passes) into test/reference/reference-NAME.exr
    and writes the settings beside it (.json): what every reference records, then `extra`."""
    mean, spp, passes, elapsed = accumulate_passes(
        lambda seed: np.array(mi.render(scene, spp=args.pass_spp, seed=seed), dtype=np.float64),
        args.pass_spp, args.max_spp, args.seconds)
    mean = mean.astype(np.float32)
    out = os.path.join(REFERENCES, f"reference-{name}.exr")
    mi.Bitmap(mean, pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)
    meta = {"scene": f"scenes/reference/{name}.gltf", "mitsuba_version": mi.__version__, "variant": mi.variant(),
            "integrator": integrator, "max_depth": max_depth, "resolution": [RES, RES], "spp": spp, "passes": passes,
            "seeds": f"0..{passes - 1} (one per pass of {args.pass_spp} spp)", "sampler": "independent",
            "reconstruction_filter": "box", "render_seconds": round(elapsed, 1),
            "machine": f"{platform.machine()}, {os.cpu_count()} logical CPUs",
            "mean_rgb": [float(v) for v in mean.reshape(-1, 3).mean(axis=0)], **extra}
    with open(os.path.splitext(out)[0] + ".json", "w") as f:
        json.dump(meta, f, indent=2)
        f.write("\n")
    print(f"{out}: {RES}x{RES}, {spp} spp in {passes} passes, {elapsed:.1f} s, mean rgb {meta['mean_rgb']}")


def render(name, desc, args):
    extra = {"materials": {n: m["mitsuba"] for n, _, m in desc["shapes"]}}
    if "environment" in desc:
        extra["environment"] = desc["environment"]
    if "environment_map" in desc:
        extra["environment_map"] = os.path.relpath(desc["environment_map"], ROOT)
    if "lights" in desc:
        extra["lights"] = desc["lights"]
    with tempfile.TemporaryDirectory() as tmp:
        render_reference(name, mitsuba_scene(desc, tmp), args, "path", MAX_DEPTH, extra)


def main():
    args = ARGS
    mi.set_variant("scalar_rgb")
    os.makedirs(SCENES, exist_ok=True)
    os.makedirs(REFERENCES, exist_ok=True)
    write_sky(os.path.join(SCENES, "sky.exr"))
    for name, desc in scene_list().items():
        if args.only and name not in args.only:
            continue
        write_gltf(os.path.join(SCENES, f"{name}.gltf"), desc)
        if not args.scenes_only:
            render(name, desc, args)


if __name__ == "__main__":
    main()
