#!/usr/bin/env python3
"""Small scenes, one per glTF material feature, and their Mitsuba 3 reference renders (docs/bsdf.md,
"Reference scenes of the glTF material").

The sibling of scripts/reference-scenes.py (same room, camera, light, film and passes; its geometry and
glTF camera helpers are reused): each scene goes to scenes/reference/NAME.gltf with its textures as
PNG data URIs, and the same triangles, with texture coordinates, to Mitsuba 3 (scalar_rgb; the clearcoat,
sheen and specular scenes llvm_ad_rgb, with DRJIT_LIBLLVM_PATH found below) with the matching plugins. Texels reach Mitsuba already decoded to linear floats (raw bitmaps), as Cohort
decodes them (sRGB for colour, byte / 255 for data), so the filters and wrap modes compare alone.

  textured-mr    a panel whose metallic-roughness texture (NEAREST) makes a checker of rough metal
                 (B = 255, G = 77: roughness 0.302) and a coloured Lambertian (B = 0, G = 255); Mitsuba:
                 blendbsdf with the blue channel as weight between diffuse and roughconductor
  sampler-wrap   three panels with coordinates from -0.75 to 1.75 and one 4x4 texture: NEAREST with
                 CLAMP_TO_EDGE, LINEAR with MIRRORED_REPEAT, LINEAR with REPEAT (Mitsuba's bitmap
                 filter_type and wrap_mode)
  alpha-mask     a slanted panel between the light and the ground, alphaMode MASK with alphaCutoff 0.3 and a
                 NEAREST texture whose alpha (40 or 120 of 255) cuts a checker of holes: the ground is
                 lit through the holes and the wall seen through them; Mitsuba: the mask plugin with
                 the cut-out as a 0/1 opacity bitmap around a two-sided diffuse
  alpha-blend    the same panel with alphaMode BLEND: baseColorFactor alpha 0.9 times a LINEAR alpha
                 ramp (stochastic transparency in Cohort); Mitsuba: mask with that alpha as opacity
  texture-transform  the sampler-wrap texture (LINEAR, REPEAT) on one panel through KHR_texture_transform
                 (offset, rotation and scale); Mitsuba: the bitmap's to_uv with glTF's T * R * S
  glass-volume   a closed block of smooth glass (IOR 1.5) whose interior absorbs a colour
                 (KHR_materials_volume attenuationColor and attenuationDistance); Mitsuba: volpath with
                 a dielectric and an interior homogeneous medium of albedo 0 and sigma_t = sigma_a
  clearcoat      three panels under KHR_materials_clearcoat: a smooth coat over a red Lambertian, a coat of
                 clearcoatRoughness 0.3 over a white rough metal, and a smooth coat whose factor comes from a
                 NEAREST texture's R channel over a green Lambertian; Mitsuba (llvm_ad_rgb, where a Python BSDF
                 is traced into the JIT): ClearcoatBSDF below, which mixes Mitsuba's own lobes as Cohort
                 does, (1 - c F(cos_i)) base + c coat, with the coat plastic / roughplastic (GGX) of
                 diffuse_reflectance 0 and int_ior 1.5
  sheen          three panels of a dark-blue Lambertian under glTF's KHR_materials_sheen: sheen colour
                 (0.9, 0.5, 0.3) at sheenRoughness 0.3 (upright) and 0.8 (tilted back, seen at a grazing
                 angle), and a sheenColorTexture (a NEAREST checker of two sRGB colours) at 0.5; Mitsuba has
                 no Charlie sheen, so a Python BSDF (gltf_sheen below, llvm_ad_rgb) written from the
                 specification's formulas, with its own albedo table integrated here, layers it over
                 Mitsuba's own diffuse plugin
  specular       three panels under glTF's KHR_materials_specular: a grey Lambertian base at roughness 0.3
                 with specularFactor 0.3 and specularColor (3, 1.5, 0.5), a smooth blue one with specular 1
                 and colour (6, 3, 1.5) (f0 tinted up to 0.24), and a green one at roughness 0.5 whose factor
                 (A) and colour (RGB, sRGB) come from NEAREST checker textures; Mitsuba has no glTF
                 specular, so a Python BSDF (gltf_specular below, llvm_ad_rgb) written from the
                 specification with the exact Fresnel's shape mixes Mitsuba's own diffuse plugin and a GGX
                 reflection of Mitsuba's MicrofacetDistribution
  (Mitsuba's path integrator counts a pass through a mask as a path segment where Cohort's does not,
  and its shadow rays stop at masks: the alpha scenes use max_depth 24, where both have converged to
  the unbounded answer of this open room)
  (normal maps: Mitsuba 3.9's normalmap plugin was checked with bump_map() below and loses about 2 %
  more light than the analytic expectation under a uniform sky, which Cohort meets within 0.1 %;
  test/render/gltf_material_test.cpp checks normal maps against analytic values instead)

Run through scripts/reference --materials, which provides mitsuba and numpy."""
import base64
import importlib.util
import math
import os
import struct
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from reference_common import reference_arguments  # noqa: E402


# --help answers before the imports below, which need the venv's packages
ARGS = reference_arguments(__doc__, "the glTF files") if __name__ == "__main__" else None

# llvm_ad_rgb (the clearcoat, sheen and specular scenes) needs Dr.Jit to find libLLVM: the newest libLLVM-N.so installed
if "DRJIT_LIBLLVM_PATH" not in os.environ:
    import glob
    import re
    found = glob.glob("/usr/lib/*/libLLVM-*.so")
    if found:
        os.environ["DRJIT_LIBLLVM_PATH"] = max(found, key=lambda f: int(re.search(r"libLLVM-(\d+)", f).group(1)))

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402

_spec = importlib.util.spec_from_file_location("reference_scenes", os.path.join(HERE, "reference-scenes.py"))
rs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(rs)

NEAREST, LINEAR = 9728, 9729
REPEAT, CLAMP, MIRROR = 10497, 33071, 33648
MI_WRAP = {REPEAT: "repeat", CLAMP: "clamp", MIRROR: "mirror"}


# ---- textures ---------------------------------------------------------------------------------

def srgb_to_linear(byte):
    c = np.asarray(byte, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def png(rgba):
    """RGBA8 PNG bytes of an (h, w, 4) uint8 array."""
    h, w, _ = rgba.shape
    raw = b"".join(b"\x00" + rgba[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker_mr(n=4):
    """Base colour and metallic-roughness texels of a checker: rough white metal and a coloured base."""
    base = np.zeros((n, n, 4), dtype=np.uint8)
    mr = np.zeros((n, n, 4), dtype=np.uint8)
    colours = [(220, 90, 40), (60, 170, 90), (70, 90, 210), (200, 200, 60)]
    for y in range(n):
        for x in range(n):
            metal = (x + y) % 2 == 0
            base[y, x] = (255, 255, 255, 255) if metal else (*colours[(x + 2 * y) % 4], 255)
            mr[y, x] = (0, 77, 255, 255) if metal else (0, 255, 0, 255)
    return base, mr


def coat_checker(n=4):
    """Clearcoat factor texels (R, linear data): a checker of 255 and 64 (full and a quarter coat)."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            t[y, x] = (255 if (x + y) % 2 == 0 else 64, 0, 0, 255)
    return t


def wrap_texture():
    """4x4 texels, every one different, so that any misplaced texel shows."""
    t = np.zeros((4, 4, 4), dtype=np.uint8)
    for y in range(4):
        for x in range(4):
            t[y, x] = (40 + 60 * x, 30 + 70 * y, 230 - 50 * x - 10 * y, 255)
    return t


def alpha_checker(n=8):
    """Coloured texels whose alpha is 40 (below the cutoff 0.3: a hole) or 120 in a checker of 2x2 blocks."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            hole = (x // 2 + y // 2) % 2 == 0
            t[y, x] = (200 - 15 * x, 80 + 20 * y, 60 + 10 * (x + y), 40 if hole else 120)
    return t


def alpha_ramp(n=8):
    """Coloured texels whose alpha runs from 20 to 250 along u and a little along v."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            t[y, x] = (90 + 20 * y, 160, 220 - 20 * x, 20 + 28 * x + 2 * y)
    return t


def bump_map(n=16):
    """A tangent-space normal map of bumps tilting the normal by up to about 20 degrees."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            dx = 0.35 * math.sin(2 * math.pi * (x + 0.5) / n * 2)
            dy = 0.35 * math.cos(2 * math.pi * (y + 0.5) / n * 3)
            v = np.array([dx, dy, 1.0])
            v /= np.linalg.norm(v)
            t[y, x, :3] = np.round((v * 0.5 + 0.5) * 255)
            t[y, x, 3] = 255
    return t


# ---- scenes: shapes carry (name, (points, faces, uvs), material) ---------------------------------

def panel(o, u, v, uv0=(0.0, 0.0), uv1=(1.0, 1.0)):
    """A quad o, o+u, o+u+v, o+v with u along the texture's u and v up the image (glTF v decreasing)."""
    p, f = rs.quad(o, u, v)
    (a, b), (c, d) = uv0, uv1
    uv = np.array([[a, d], [c, d], [c, b], [a, b]], dtype=np.float64)
    return p, f, uv


def textured_diffuse(texels, sampler):
    return {"kind": "textured_diffuse", "texels": texels, "sampler": sampler}


def glass_volume(colour, distance, ior):
    """Smooth glass whose interior absorbs sigma_a = -ln(colour) / distance per channel (Beer-Lambert)."""
    sigma = [-math.log(c) / distance for c in colour]
    return {"gltf": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                           "KHR_materials_ior": {"ior": ior},
                           "KHR_materials_volume": {"attenuationColor": list(colour),
                                                    "attenuationDistance": distance, "thicknessFactor": 1.0}},
            "mitsuba": {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0},
            # Mitsuba's rgb value is a reflectance in [0, 1]: sigma_t = scale * a colour of peak 1
            "interior": {"type": "homogeneous", "albedo": 0.0, "sigma_t": rs.rgb_value([v / max(sigma) for v in sigma]),
                         "scale": max(sigma)}}


def clearcoat(base, factor, roughness, texture=None):
    """glTF KHR_materials_clearcoat over a base material of reference-scenes.py (its gltf and its mitsuba
    BSDF without the twosided wrapper); `texture` (texels, sampler) multiplies the factor by its R channel."""
    coat = {"clearcoatFactor": factor, "clearcoatRoughnessFactor": roughness}
    mi_base = base["mitsuba"]["bsdf"]
    if roughness > 0:
        mi_coat = {"type": "roughplastic", "diffuse_reflectance": rs.rgb_value([0.0, 0.0, 0.0]), "int_ior": 1.5,
                   "ext_ior": 1.0, "distribution": "ggx", "alpha": roughness ** 2, "nonlinear": False}
    else:
        mi_coat = {"type": "plastic", "diffuse_reflectance": rs.rgb_value([0.0, 0.0, 0.0]), "int_ior": 1.5,
                   "ext_ior": 1.0, "nonlinear": False}
    out = {"kind": "clearcoat", "gltf": base["gltf"], "coat": coat, "mi_base": mi_base, "mi_coat": mi_coat}
    if texture:
        out["texels"], out["sampler"] = texture
    return out


def sheen_checker(n=4):
    """sRGB texels of a checker of two colours for the sheen colour texture."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            t[y, x] = (240, 200, 90, 255) if (x + y) % 2 == 0 else (90, 220, 230, 255)
    return t


def sheen(base, colour, roughness, texels=None, sampler=None):
    """A Lambertian of colour `base` under KHR_materials_sheen (sheenColorFactor `colour` times the
    texture's RGB, where there is one)."""
    return {"kind": "sheen", "base": base, "colour": colour, "roughness": roughness, "texels": texels,
            "sampler": sampler}


def specular_checker(n=4):
    """Texels of the specular panel: RGB an sRGB checker of two colours (specularColorTexture), A a checker
    of 255 and 64 (specularTexture), offset by one texel so that the two do not coincide."""
    t = np.zeros((n, n, 4), dtype=np.uint8)
    for y in range(n):
        for x in range(n):
            t[y, x, :3] = (255, 140, 40) if (x + y) % 2 == 0 else (60, 170, 255)
            t[y, x, 3] = 255 if (x + y // 2) % 2 == 0 else 64
    return t


def specular(base, roughness, factor, colour, texels=None, sampler=None):
    """A Lambertian of colour `base` (not metal, `roughness`) under KHR_materials_specular: specularFactor
    `factor` (times the texture's A) and specularColorFactor `colour` (times its RGB), where there is one."""
    return {"kind": "specular", "base": base, "roughness": roughness, "factor": factor, "colour": colour,
            "texels": texels, "sampler": sampler}


def room_with(panels, light=True):
    shapes = [("ground", (*rs.quad([-4, 0, 4], [8, 0, 0], [0, 0, -8]), None), rs.diffuse([0.5, 0.5, 0.5])),
              ("wall", (*rs.quad([-4, 0, -3], [8, 0, 0], [0, 5, 0]), None), rs.diffuse([0.2, 0.4, 0.7]))]
    shapes += panels
    if light:
        shapes.append(("light", (*rs.quad([-0.75, 3.5, -0.75], [1.5, 0, 0], [0, 0, 1.5]), None), rs.emitter([8.0, 8.0, 8.0])))
    return shapes


ALPHA_PANEL = ([-1.3, 0.6, 1.2], [2.6, 0, 0], [0, 1.4, -2.2])  # between the light and the ground, facing the camera


def scene_list():
    base, mr = checker_mr()
    wrap = wrap_texture()
    blue = [0.03, 0.05, 0.25]
    return {
        "clearcoat": {"environment": [0.1, 0.1, 0.1], "llvm": True, "shapes": room_with([
            ("smooth", panel([-2.1, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             clearcoat(rs.diffuse([0.8, 0.1, 0.1]), 1.0, 0.0)),
            ("rough", panel([-0.65, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             clearcoat(rs.rough_conductor(0.3), 1.0, 0.3)),
            ("textured", panel([0.8, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             clearcoat(rs.diffuse([0.1, 0.6, 0.2]), 1.0, 0.0,
                       (coat_checker(), {"magFilter": NEAREST, "minFilter": NEAREST})))])},
        "sheen": {"environment": [0.1, 0.1, 0.1], "llvm": True, "shapes": room_with([
            ("sheen_03", panel([-2.2, 0.2, 0.2], [1.3, 0, 0], [0, 2.0, -0.3]), sheen(blue, [0.9, 0.5, 0.3], 0.3)),
            ("sheen_08", panel([-0.65, 0.1, 0.9], [1.3, 0, 0], [0, 1.0, -2.2]), sheen(blue, [0.9, 0.5, 0.3], 0.8)),
            ("sheen_tex", panel([0.9, 0.2, 0.2], [1.3, 0, 0], [0, 2.0, -0.3]),
             sheen(blue, [1.0, 1.0, 1.0], 0.5, sheen_checker(), {"magFilter": NEAREST, "minFilter": NEAREST}))])},
        "specular": {"environment": [0.1, 0.1, 0.1], "llvm": True, "shapes": room_with([
            ("tinted", panel([-2.1, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             specular([0.5, 0.5, 0.5], 0.3, 0.3, [3.0, 1.5, 0.5])),
            ("smooth", panel([-0.65, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             specular([0.1, 0.2, 0.5], 0.0, 1.0, [6.0, 3.0, 1.5])),
            ("textured", panel([0.8, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3]),
             specular([0.2, 0.5, 0.2], 0.5, 1.0, [2.0, 2.0, 2.0], specular_checker(),
                      {"magFilter": NEAREST, "minFilter": NEAREST}))])},
        "glass-volume": {"environment": [0.1, 0.1, 0.1], "integrator": "volpath", "shapes": room_with([
            ("block", (*rs.cuboid([-0.9, 0.02, -0.5], [0.9, 1.3, 0.5]), None),
             glass_volume([0.85, 0.55, 0.25], 0.6, 1.5))])},
        "texture-transform": {"environment": [0.1, 0.1, 0.1], "shapes": room_with([
            ("panel", panel([-1.2, 0.2, 0.0], [2.4, 0, 0], [0, 2.0, -0.6]),
             dict(textured_diffuse(wrap, {"magFilter": LINEAR, "minFilter": LINEAR}),
                  transform={"offset": [0.3, -0.2], "rotation": 0.6, "scale": [1.8, 1.3]}))])},
        "alpha-mask": {"environment": [0.1, 0.1, 0.1], "max_depth": 24, "shapes": room_with([
            ("panel", panel(*ALPHA_PANEL),
             {"kind": "alpha", "texels": alpha_checker(), "mode": "MASK", "cutoff": 0.3, "factor": 1.0,
              "sampler": {"magFilter": NEAREST, "minFilter": NEAREST}})])},
        "alpha-blend": {"environment": [0.1, 0.1, 0.1], "max_depth": 24, "shapes": room_with([
            ("panel", panel(*ALPHA_PANEL),
             {"kind": "alpha", "texels": alpha_ramp(), "mode": "BLEND", "factor": 0.9,
              "sampler": {"magFilter": LINEAR, "minFilter": LINEAR}})])},
        "textured-mr": {"environment": [0.1, 0.1, 0.1], "shapes": room_with([
            ("panel", panel([-1.2, 0.2, 0.0], [2.4, 0, 0], [0, 2.0, -0.6]),
             {"kind": "textured_mr", "base": base, "mr": mr, "sampler": {"magFilter": NEAREST, "minFilter": NEAREST}})])},
        "sampler-wrap": {"environment": [0.1, 0.1, 0.1], "shapes": room_with([
            ("clamp", panel([-2.1, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3], (-0.75, -0.75), (1.75, 1.75)),
             textured_diffuse(wrap, {"magFilter": NEAREST, "minFilter": NEAREST, "wrapS": CLAMP, "wrapT": CLAMP})),
            ("mirror", panel([-0.65, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3], (-0.75, -0.75), (1.75, 1.75)),
             textured_diffuse(wrap, {"magFilter": LINEAR, "minFilter": LINEAR, "wrapS": MIRROR, "wrapT": MIRROR})),
            ("repeat", panel([0.8, 0.3, 0.0], [1.3, 0, 0], [0, 1.3, -0.3], (-0.75, -0.75), (1.75, 1.75)),
             textured_diffuse(wrap, {"magFilter": LINEAR, "minFilter": LINEAR}))])},
    }


# ---- glTF for Cohort --------------------------------------------------------------------------

def write_gltf(path, desc):
    blob = bytearray()
    doc = {"asset": {"version": "2.0", "generator": "scripts/reference --materials"}, "buffers": [],
           "bufferViews": [], "accessors": [], "meshes": [], "materials": [], "nodes": [], "images": [],
           "samplers": [], "textures": [], "scenes": [{"nodes": []}], "scene": 0,
           "extensionsUsed": ["KHR_materials_emissive_strength"]}

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        doc["bufferViews"].append(view)
        blob.extend(data)
        return len(doc["bufferViews"]) - 1

    def add_accessor(array, kind, target=34962):
        a = np.ascontiguousarray(array, dtype=np.float32)
        acc = {"bufferView": add_view(a.tobytes(), target), "componentType": 5126, "count": len(a), "type": kind}
        if kind == "VEC3":
            acc["min"], acc["max"] = a.min(axis=0).tolist(), a.max(axis=0).tolist()
        doc["accessors"].append(acc)
        return len(doc["accessors"]) - 1

    def add_texture(texels, sampler):
        doc["images"].append({"uri": "data:image/png;base64," + base64.b64encode(png(texels)).decode()})
        doc["samplers"].append(sampler)
        doc["textures"].append({"source": len(doc["images"]) - 1, "sampler": len(doc["samplers"]) - 1})
        return {"index": len(doc["textures"]) - 1}

    for name, (p, f, uv), mat in desc["shapes"]:
        attributes = {"POSITION": add_accessor(p, "VEC3")}
        if uv is not None:
            attributes["TEXCOORD_0"] = add_accessor(uv, "VEC2")
        kind = mat.get("kind")
        if kind == "textured_mr":
            m = {"pbrMetallicRoughness": {"baseColorTexture": add_texture(mat["base"], mat["sampler"]),
                                          "metallicRoughnessTexture": add_texture(mat["mr"], mat["sampler"]),
                                          "metallicFactor": 1.0, "roughnessFactor": 1.0}}
        elif kind == "textured_diffuse":
            m = {"pbrMetallicRoughness": {"baseColorTexture": add_texture(mat["texels"], mat["sampler"]),
                                          "metallicFactor": 0.0, "roughnessFactor": 1.0}}
            if "transform" in mat:
                m["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {"KHR_texture_transform": mat["transform"]}
                if "KHR_texture_transform" not in doc["extensionsUsed"]:
                    doc["extensionsUsed"].append("KHR_texture_transform")
        elif kind == "alpha":
            m = {"pbrMetallicRoughness": {"baseColorTexture": add_texture(mat["texels"], mat["sampler"]),
                                          "baseColorFactor": [1.0, 1.0, 1.0, mat["factor"]],
                                          "metallicFactor": 0.0, "roughnessFactor": 1.0},
                 "alphaMode": mat["mode"], "doubleSided": True}
            if "cutoff" in mat:
                m["alphaCutoff"] = mat["cutoff"]
        elif kind == "sheen":
            ext = {"sheenColorFactor": mat["colour"], "sheenRoughnessFactor": mat["roughness"]}
            if mat["texels"] is not None:
                ext["sheenColorTexture"] = add_texture(mat["texels"], mat["sampler"])
            m = {"pbrMetallicRoughness": {"baseColorFactor": mat["base"] + [1.0], "metallicFactor": 0.0,
                                          "roughnessFactor": 1.0},
                 "extensions": {"KHR_materials_sheen": ext}}
            if "KHR_materials_sheen" not in doc["extensionsUsed"]:
                doc["extensionsUsed"].append("KHR_materials_sheen")
        elif kind == "specular":
            ext = {"specularFactor": mat["factor"], "specularColorFactor": mat["colour"]}
            if mat["texels"] is not None:
                ext["specularTexture"] = add_texture(mat["texels"], mat["sampler"])
                ext["specularColorTexture"] = add_texture(mat["texels"], mat["sampler"])
            m = {"pbrMetallicRoughness": {"baseColorFactor": mat["base"] + [1.0], "metallicFactor": 0.0,
                                          "roughnessFactor": mat["roughness"]},
                 "extensions": {"KHR_materials_specular": ext}}
            if "KHR_materials_specular" not in doc["extensionsUsed"]:
                doc["extensionsUsed"].append("KHR_materials_specular")
        elif kind == "normal_map":
            m = {"pbrMetallicRoughness": {"baseColorFactor": mat["albedo"] + [1.0], "metallicFactor": 0.0,
                                          "roughnessFactor": 1.0},
                 "normalTexture": dict(add_texture(mat["normals"], mat["sampler"]), scale=1.0)}
            # the panel's frame: normal u x v, tangent along u (the texture's u), bitangent up the image
            e1, e2 = p[1] - p[0], p[3] - p[0]
            n = np.cross(e1, e2)
            n /= np.linalg.norm(n)
            t = e1 / np.linalg.norm(e1)
            attributes["NORMAL"] = add_accessor(np.tile(n, (len(p), 1)), "VEC3")
            attributes["TANGENT"] = add_accessor(np.tile(np.append(t, 1.0), (len(p), 1)), "VEC4")
        elif kind == "clearcoat":
            coat = dict(mat["coat"])
            if "texels" in mat:
                coat["clearcoatTexture"] = add_texture(mat["texels"], mat["sampler"])
            m = {"pbrMetallicRoughness": mat["gltf"], "extensions": {"KHR_materials_clearcoat": coat}}
            if "KHR_materials_clearcoat" not in doc["extensionsUsed"]:
                doc["extensionsUsed"].append("KHR_materials_clearcoat")
        else:
            m = {"pbrMetallicRoughness": mat["gltf"]}
            if "extensions" in mat:
                m["extensions"] = dict(mat["extensions"])
                doc["extensionsUsed"] += [e for e in mat["extensions"] if e not in doc["extensionsUsed"]]
        m["name"] = name
        if "emission" in mat:
            peak = max(mat["emission"])
            m["emissiveFactor"] = [c / peak for c in mat["emission"]]
            m.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {"emissiveStrength": peak}
        doc["materials"].append(m)
        iv = add_view(f.astype(np.uint32).tobytes(), 34963)
        doc["accessors"].append({"bufferView": iv, "componentType": 5125, "count": int(f.size), "type": "SCALAR"})
        doc["meshes"].append({"name": name, "primitives": [{"attributes": attributes,
                                                            "indices": len(doc["accessors"]) - 1,
                                                            "material": len(doc["materials"]) - 1}]})
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
    camera = rs.CAMERA
    eye, target, up = (np.array(camera[k], dtype=np.float64) for k in ("eye", "target", "up"))
    back = eye - target
    back /= np.linalg.norm(back)
    right = np.cross(up, back)
    right /= np.linalg.norm(right)
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": math.radians(camera["fov"]),
                                                               "aspectRatio": 1.0, "znear": 0.01}}]
    doc["nodes"].append({"name": "camera", "camera": 0,
                         "matrix": rs.column_major(right, np.cross(back, right), back, eye)})
    rs.write_gltf_file(path, doc, blob)


# ---- Mitsuba ----------------------------------------------------------------------------------

def uv_transform(t):
    """glTF KHR_texture_transform (T * R * S) as Mitsuba's to_uv."""
    c, s = math.cos(t.get("rotation", 0.0)), math.sin(t.get("rotation", 0.0))
    (ox, oy), (sx, sy) = t.get("offset", [0.0, 0.0]), t.get("scale", [1.0, 1.0])
    return mi.ScalarTransform3f(mi.ScalarMatrix3f([[c * sx, s * sy, ox], [-s * sx, c * sy, oy], [0.0, 0.0, 1.0]]))


def bitmap(values, sampler, transform=None):
    """A raw (already linear) bitmap texture with the glTF sampler's filter and wrap mode (one for
    both axes: Mitsuba's bitmap has one wrap_mode), and a KHR_texture_transform as to_uv."""
    filt = "nearest" if sampler.get("magFilter") == NEAREST else "bilinear"
    wrap = MI_WRAP[sampler.get("wrapS", REPEAT)]
    assert wrap == MI_WRAP[sampler.get("wrapT", REPEAT)]
    channels = values.shape[2] if values.ndim == 3 else 1
    fmt = mi.Bitmap.PixelFormat.RGB if channels == 3 else mi.Bitmap.PixelFormat.Y
    out = {"type": "bitmap", "bitmap": mi.Bitmap(np.ascontiguousarray(values, dtype=np.float32), pixel_format=fmt),
           "raw": True, "filter_type": filt, "wrap_mode": wrap}
    if transform:
        out["to_uv"] = uv_transform(transform)
    return out


def register_clearcoat():
    """Registers the BSDF "clearcoat" with the variant set now (a Python BSDF derives from its mi.BSDF)."""

    class ClearcoatBSDF(mi.BSDF):
        """glTF's clearcoat layering as Cohort renders it, from Mitsuba's own lobes (docs/bsdf.md, "Clearcoat"):
        eval = (1 - c F(cos_i)) base + c coat, with F the exact dielectric Fresnel of IOR 1.5 about the
        normal and the coat a plastic / roughplastic of diffuse_reflectance 0 (its value is F(wi.m) D G /
        (4 cos_i), or the delta mirror of weight F). Sampling picks the coat with probability q = c F(cos_i);
        a delta coat sample weighs c / q times the coat's weight, any other sample the mixture's eval over
        its pdf (one-sample MIS). One-sided: twosided wraps it."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.base = props["base"]
            self.coat = props["coat"]
            self.factor = props["factor"]
            self.m_components = [self.base.flags(), self.coat.flags()]
            self.m_flags = self.base.flags() | self.coat.flags()

        def _weight(self, si, active):
            f = mi.fresnel(mi.Frame3f.cos_theta(si.wi), 1.5)[0]
            c = self.factor.eval_1(si, active)
            return c, c * f

        def eval_pdf(self, ctx, si, wo, active=True):
            c, q = self._weight(si, active)
            vb, pb = self.base.eval_pdf(ctx, si, wo, active)
            vc, pc = self.coat.eval_pdf(ctx, si, wo, active)
            return vb * (1 - q) + vc * c, pb * (1 - q) + pc * q

        def eval(self, ctx, si, wo, active=True):
            return self.eval_pdf(ctx, si, wo, active)[0]

        def pdf(self, ctx, si, wo, active=True):
            return self.eval_pdf(ctx, si, wo, active)[1]

        def sample(self, ctx, si, sample1, sample2, active=True):
            c, q = self._weight(si, active)
            coat = active & (sample1 < q)
            base = active & ~coat
            bs_c, w_c = self.coat.sample(ctx, si, dr.minimum(sample1 / q, 0.99999994), sample2, coat)
            bs_b, w_b = self.base.sample(ctx, si, dr.minimum((sample1 - q) / (1 - q), 0.99999994), sample2, base)
            bs = mi.BSDFSample3f(bs_b)
            bs.wo = dr.select(coat, bs_c.wo, bs_b.wo)
            bs.eta = dr.select(coat, bs_c.eta, bs_b.eta)
            bs.sampled_type = dr.select(coat, bs_c.sampled_type, bs_b.sampled_type)
            bs.sampled_component = dr.select(coat, mi.UInt32(1), mi.UInt32(0))
            delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
            value, pdf = self.eval_pdf(ctx, si, bs.wo, active & ~delta)
            delta_pdf = dr.select(coat, q * bs_c.pdf, (1 - q) * bs_b.pdf)
            delta_weight = dr.select(coat, w_c * c / q, w_b)
            bs.pdf = dr.select(delta, delta_pdf, pdf)
            weight = dr.select(delta, delta_weight, value / dr.maximum(pdf, 1e-30))
            ok = active & (bs.pdf > 0) & dr.select(coat, bs_c.pdf > 0, bs_b.pdf > 0)
            bs.pdf = dr.select(ok, bs.pdf, 0)
            return bs, dr.select(ok, weight, 0)

        def traverse(self, callback):
            pass

        def to_string(self):
            return "ClearcoatBSDF"

    mi.register_bsdf("clearcoat", lambda props: ClearcoatBSDF(props))


class SheenAlbedo:
    """E(cos theta_i) of the sheen lobe at one alpha, integrated with NumPy independently of Cohort's
    table (scripts/lib/sheen-albedo.py): the midpoint rule on N_Z x N_PHI cells of (cos theta_o, phi
    in [0, pi]), 129 values of cos theta_i on [0, 1], read linearly."""
    N_Z, N_PHI = 1024, 256

    def __init__(self, alpha, n_mu=129):
        z = (np.arange(self.N_Z) + 0.5) / self.N_Z
        phi = (np.arange(self.N_PHI) + 0.5) / self.N_PHI * np.pi
        zo, ph = np.meshgrid(z, phi, indexing="ij")
        so = np.sqrt(1.0 - zo * zo)
        cell = (1.0 / self.N_Z) * (np.pi / self.N_PHI) * 2.0
        self.mu = np.linspace(0.0, 1.0, n_mu)
        self.e = np.empty(n_mu)
        for k, mu in enumerate(np.maximum(self.mu, 1e-3)):
            si = math.sqrt(1.0 - mu * mu)
            hx, hy, hz = so * np.cos(ph) + si, so * np.sin(ph), zo + mu
            sin2 = (hx * hx + hy * hy) / (hx * hx + hy * hy + hz * hz)
            f = sheen_d_np(sin2, alpha) / ((1.0 + sheen_lambda_np(zo, alpha) + sheen_lambda_np(mu, alpha)) * 4.0 * mu)
            self.e[k] = float(np.sum(f) * cell)  # f already carries cos theta_o / (cos_i cos_o) cos_o


def sheen_d_np(sin2, alpha):
    """Charlie's D (Estevez & Kulla 2017, glTF KHR_materials_sheen)."""
    return (2.0 + 1.0 / alpha) * np.power(sin2, 0.5 / alpha) / (2.0 * np.pi)


def sheen_lambda_np(c, alpha):
    """Lambda of Estevez & Kulla's fit, interpolated in (1 - alpha)^2 as the glTF specification does."""
    t = (1.0 - alpha) ** 2
    a, b, cc, d, e = [lo + (hi - lo) * t for lo, hi in ((21.5473, 25.3245), (3.82987, 3.32435), (0.19823, 0.16801),
                                                          (-1.97760, -1.27393), (-4.32054, -4.85967))]

    def l_fit(x):
        return a / (1.0 + b * np.power(x, cc)) + d * x + e

    c = np.asarray(c, dtype=np.float64)
    return np.where(c < 0.5, np.exp(l_fit(np.minimum(c, 0.5))), np.exp(2.0 * l_fit(0.5) - l_fit(np.maximum(1.0 - c, 0.0))))


def register_gltf_sheen():
    """glTF's sheen over a nested BSDF (Mitsuba's diffuse here) as a Mitsuba Python BSDF, written from
    the KHR_materials_sheen formulas: f = sheen D V + base (1 - max3(sheen colour) E(cos theta_i)), D
    Charlie's, V = 1 / ((1 + Lambda(cos_i) + Lambda(cos_o)) 4 cos_i cos_o), alpha = max(r^2, 1e-3);
    sampled cosine-weighted (both lobes are broad). Front side only: wrap it in twosided."""

    class GltfSheen(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.base = props["base"]
            self.factor = mi.Color3f(props["sheen_color"])
            self.texture = props["sheen_texture"] if "sheen_texture" in props else None
            self.alpha = max(float(props["sheen_roughness"]) ** 2, 1e-3)
            table = SheenAlbedo(self.alpha)
            self.e = mi.Float(table.e.astype(np.float32))
            self.n = len(table.e)
            flags = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide
            self.m_components = [flags]
            self.m_flags = flags

        def albedo(self, mu):
            x = dr.clip(mu, 0.0, 1.0) * (self.n - 1)
            i = dr.minimum(mi.UInt32(dr.floor(x)), self.n - 2)
            t = x - mi.Float(i)
            return dr.gather(mi.Float, self.e, i) * (1.0 - t) + dr.gather(mi.Float, self.e, i + 1) * t

        def lam(self, c):
            t = (1.0 - self.alpha) ** 2
            a, b, cc, d, e = [lo + (hi - lo) * t for lo, hi in ((21.5473, 25.3245), (3.82987, 3.32435),
                                                                  (0.19823, 0.16801), (-1.97760, -1.27393),
                                                                  (-4.32054, -4.85967))]

            def l_fit(x):
                return a / (1.0 + b * dr.power(x, cc)) + d * x + e

            return dr.select(c < 0.5, dr.exp(l_fit(dr.minimum(c, 0.5))),
                             dr.exp(2.0 * l_fit(0.5) - l_fit(dr.maximum(1.0 - c, 0.0))))

        def eval(self, ctx, si, wo, active=True):
            ci, co = mi.Frame3f.cos_theta(si.wi), mi.Frame3f.cos_theta(wo)
            active = active & (ci > 0.0) & (co > 0.0)
            h = dr.normalize(si.wi + wo)
            sin2 = dr.maximum(h.x * h.x + h.y * h.y, 0.0)
            d = (2.0 + 1.0 / self.alpha) * dr.power(sin2, 0.5 / self.alpha) / (2.0 * dr.pi)
            v = 1.0 / ((1.0 + self.lam(ci) + self.lam(co)) * 4.0 * ci * co)
            colour = self.factor * (self.texture.eval(si, active) if self.texture is not None else 1.0)
            scale = 1.0 - dr.max(colour) * self.albedo(ci)
            value = colour * (d * v * co) + self.base.eval(ctx, si, wo, active) * scale
            return dr.select(active, value, 0.0)

        def pdf(self, ctx, si, wo, active=True):
            ci = mi.Frame3f.cos_theta(si.wi)
            return dr.select(active & (ci > 0.0), mi.warp.square_to_cosine_hemisphere_pdf(wo), 0.0)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

        def sample(self, ctx, si, sample1, sample2, active=True):
            wo = mi.warp.square_to_cosine_hemisphere(sample2)
            bs = mi.BSDFSample3f()
            bs.wo = wo
            bs.pdf = self.pdf(ctx, si, wo, active)
            bs.eta = 1.0
            bs.sampled_type = mi.UInt32(+mi.BSDFFlags.DiffuseReflection)
            bs.sampled_component = mi.UInt32(0)
            ok = active & (bs.pdf > 0.0)
            return bs, dr.select(ok, self.eval(ctx, si, wo, ok) / bs.pdf, 0.0)

        def to_string(self):
            return f"GltfSheen[alpha={self.alpha}]"

    mi.register_bsdf("gltf_sheen", lambda props: GltfSheen(props))


def register_gltf_specular():
    """glTF's KHR_materials_specular layering of the dielectric as a Mitsuba Python BSDF, written from the
    specification with the exact Fresnel's shape (docs/bsdf.md, "Specular"): f = (1 - max3 F(cos_i)) base
    + F(wi.m) D G / (4 cos_i cos_o), F = f0' + (f90' - f0') s, f0' = min(f0 specularColor, 1) specular,
    f90' = specular, s = (F_exact - f0) / (1 - f0) clamped to [0, 1], F_exact Mitsuba's fresnel; the base a
    nested BSDF (Mitsuba's diffuse here), D and G (and the visible-normal sampling) Mitsuba's GGX
    MicrofacetDistribution, or a delta mirror of weight F(cos_i) when smooth. Sampling takes the
    reflection with probability q = max3 F(cos_i), else the base; non-delta samples weigh the mixture's eval
    over its pdf (one-sample MIS). Front side only: wrap it in twosided."""

    class GltfSpecular(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.base = props["base"]
            self.specular = float(props["specular"])
            self.colour = mi.Color3f(props["specular_color"])
            self.factor_texture = props["specular_texture"] if "specular_texture" in props else None
            self.colour_texture = props["specular_color_texture"] if "specular_color_texture" in props else None
            self.eta = float(props["ior"])
            self.f0 = ((self.eta - 1.0) / (self.eta + 1.0)) ** 2
            alpha = float(props["alpha"])
            self.smooth = alpha < 1e-3  # Cohort's BSDF_SMOOTH_ALPHA
            self.distr = None if self.smooth else mi.MicrofacetDistribution(mi.MicrofacetType.GGX, alpha, True)
            lobe = mi.BSDFFlags.DeltaReflection if self.smooth else mi.BSDFFlags.GlossyReflection
            self.m_components = [self.base.flags(), lobe | mi.BSDFFlags.FrontSide]
            self.m_flags = self.base.flags() | lobe | mi.BSDFFlags.FrontSide

        def fresnel(self, si, cos, active):
            w = self.specular * (self.factor_texture.eval_1(si, active) if self.factor_texture is not None else 1.0)
            c = self.colour * (self.colour_texture.eval(si, active) if self.colour_texture is not None else 1.0)
            f0 = dr.minimum(self.f0 * c, 1.0) * w
            s = dr.clip((mi.fresnel(cos, self.eta)[0] - self.f0) / (1.0 - self.f0), 0.0, 1.0)
            return f0 + (w - f0) * s

        def eval_pdf(self, ctx, si, wo, active=True):
            ci, co = mi.Frame3f.cos_theta(si.wi), mi.Frame3f.cos_theta(wo)
            active = active & (ci > 0.0) & (co > 0.0)
            q = dr.max(self.fresnel(si, ci, active))
            vb, pb = self.base.eval_pdf(ctx, si, wo, active)
            value, pdf = vb * (1.0 - q), pb * (1.0 - q)
            if not self.smooth:
                m = dr.normalize(si.wi + wo)
                lobe = self.distr.eval(m) * self.distr.G(si.wi, wo, m) / (4.0 * ci)
                value += self.fresnel(si, dr.dot(si.wi, m), active) * lobe
                pdf += q * self.distr.pdf(si.wi, m) / (4.0 * dr.abs(dr.dot(wo, m)))
            return dr.select(active, value, 0.0), dr.select(active, pdf, 0.0)

        def eval(self, ctx, si, wo, active=True):
            return self.eval_pdf(ctx, si, wo, active)[0]

        def pdf(self, ctx, si, wo, active=True):
            return self.eval_pdf(ctx, si, wo, active)[1]

        def sample(self, ctx, si, sample1, sample2, active=True):
            ci = mi.Frame3f.cos_theta(si.wi)
            active = active & (ci > 0.0)
            f_i = self.fresnel(si, ci, active)
            q = dr.max(f_i)
            lobe = active & (sample1 < q)
            base = active & ~lobe
            bs_b, w_b = self.base.sample(ctx, si, dr.minimum((sample1 - q) / (1.0 - q), 0.99999994), sample2, base)
            bs = mi.BSDFSample3f(bs_b)
            if self.smooth:
                wo = mi.Vector3f(-si.wi.x, -si.wi.y, si.wi.z)
                lobe_type = mi.UInt32(+mi.BSDFFlags.DeltaReflection)
            else:
                m, _ = self.distr.sample(si.wi, sample2)
                wo = mi.reflect(si.wi, m)
                lobe_type = mi.UInt32(+mi.BSDFFlags.GlossyReflection)
            bs.wo = dr.select(lobe, wo, bs_b.wo)
            bs.eta = 1.0
            bs.sampled_type = dr.select(lobe, lobe_type, bs_b.sampled_type)
            bs.sampled_component = dr.select(lobe, mi.UInt32(1), mi.UInt32(0))
            delta = lobe if self.smooth else mi.Bool(False)
            value, pdf = self.eval_pdf(ctx, si, bs.wo, active & ~delta)
            bs.pdf = dr.select(delta, q, pdf)
            weight = dr.select(delta, f_i / q, value / dr.maximum(pdf, 1e-30))
            ok = active & (bs.pdf > 0.0) & (mi.Frame3f.cos_theta(bs.wo) > 0.0) & (lobe | (bs_b.pdf > 0.0))
            bs.pdf = dr.select(ok, bs.pdf, 0.0)
            return bs, dr.select(ok, weight, 0.0)

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"GltfSpecular[specular={self.specular}, smooth={self.smooth}]"

    mi.register_bsdf("gltf_specular", lambda props: GltfSpecular(props))


def mitsuba_bsdf(mat):
    kind = mat.get("kind")
    if kind == "specular":
        bsdf = {"type": "gltf_specular", "specular": mat["factor"], "specular_color": mi.ScalarColor3d(mat["colour"]),
                "ior": 1.5, "alpha": mat["roughness"] ** 2,
                "base": {"type": "diffuse", "reflectance": rs.rgb_value(mat["base"])}}
        if mat["texels"] is not None:
            bsdf["specular_texture"] = bitmap(mat["texels"][:, :, 3:4] / 255.0, mat["sampler"])
            bsdf["specular_color_texture"] = bitmap(srgb_to_linear(mat["texels"][:, :, :3]), mat["sampler"])
        return {"type": "twosided", "bsdf": bsdf}
    if kind == "clearcoat":
        factor = {"type": "uniform", "value": mat["coat"]["clearcoatFactor"]}
        if "texels" in mat:
            factor = bitmap(mat["coat"]["clearcoatFactor"] * mat["texels"][:, :, 0:1] / 255.0, mat["sampler"])
        return {"type": "twosided", "bsdf": {"type": "clearcoat", "base": mat["mi_base"], "coat": mat["mi_coat"],
                                             "factor": factor}}
    if kind == "sheen":
        bsdf = {"type": "gltf_sheen", "sheen_color": mi.ScalarColor3d(mat["colour"]),
                "sheen_roughness": mat["roughness"], "base": {"type": "diffuse", "reflectance": rs.rgb_value(mat["base"])}}
        if mat["texels"] is not None:
            bsdf["sheen_texture"] = bitmap(srgb_to_linear(mat["texels"][:, :, :3]), mat["sampler"])
        return {"type": "twosided", "bsdf": bsdf}
    if kind == "textured_mr":
        colour = srgb_to_linear(mat["base"][:, :, :3])
        metal = mat["mr"][:, :, 2:3] / 255.0
        rough = 77 / 255.0
        return {"type": "twosided", "bsdf": {
            "type": "blendbsdf", "weight": bitmap(metal, mat["sampler"]),
            "a": {"type": "diffuse", "reflectance": bitmap(colour, mat["sampler"])},
            "b": {"type": "roughconductor", "material": "none", "distribution": "ggx", "alpha": rough ** 2,
                  "sample_visible": True}}}
    if kind == "textured_diffuse":
        return {"type": "twosided", "bsdf": {"type": "diffuse",
                                             "reflectance": bitmap(srgb_to_linear(mat["texels"][:, :, :3]), mat["sampler"],
                                                                   mat.get("transform"))}}
    if kind == "alpha":
        colour = srgb_to_linear(mat["texels"][:, :, :3])
        alpha = mat["factor"] * mat["texels"][:, :, 3:4] / 255.0
        if mat["mode"] == "MASK":
            alpha = (alpha >= mat["cutoff"]).astype(np.float64)  # nearest texels: the cut-out exactly
        return {"type": "mask", "opacity": bitmap(alpha, mat["sampler"]),
                "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": bitmap(colour, mat["sampler"])}}}
    if kind == "normal_map":
        return {"type": "normalmap", "normalmap": bitmap(mat["normals"][:, :, :3] / 255.0, mat["sampler"]),
                "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rs.rgb_value(mat["albedo"])}}}
    return mat["mitsuba"]


def mitsuba_scene(desc, tmp):
    camera = rs.CAMERA
    scene = {"type": "scene", "integrator": {"type": desc.get("integrator", "path"),
                                             "max_depth": desc.get("max_depth", rs.MAX_DEPTH)},
             "sensor": {"type": "perspective", "fov": camera["fov"], "fov_axis": "y", "near_clip": 0.01,
                        "to_world": rs.look_at(camera["eye"], camera["target"], camera["up"]),
                        "sampler": {"type": "independent"},
                        "film": {"type": "hdrfilm", "width": rs.RES, "height": rs.RES, "pixel_format": "rgb",
                                 "rfilter": {"type": "box"}}},
             "environment": {"type": "constant", "radiance": rs.rgb_value(desc["environment"])}}
    for name, (p, f, uv), mat in desc["shapes"]:
        path = os.path.join(tmp, name + ".ply")
        rs.write_ply(path, p, f, uv)
        shape = {"type": "ply", "filename": path, "face_normals": True, "bsdf": mitsuba_bsdf(mat)}
        if "emission" in mat:
            shape["emitter"] = {"type": "area", "radiance": rs.rgb_value(mat["emission"])}
        if "interior" in mat:
            shape["interior"] = mat["interior"]
        scene[name] = shape
    return mi.load_dict(scene)


def render(name, desc, args):
    # Python BSDFs run fast only where they are traced into the JIT (llvm_ad_rgb); in scalar_rgb, far too slow
    mi.set_variant("llvm_ad_rgb" if desc.get("llvm") else "scalar_rgb")
    if desc.get("llvm"):
        register_clearcoat()
        register_gltf_sheen()
        register_gltf_specular()
    with tempfile.TemporaryDirectory() as tmp:
        rs.render_reference(name, mitsuba_scene(desc, tmp), args, desc.get("integrator", "path"),
                            desc.get("max_depth", rs.MAX_DEPTH),
                            {"environment": desc["environment"], "written_by": "scripts/reference --materials"})


def main():
    args = ARGS
    os.makedirs(rs.SCENES, exist_ok=True)
    os.makedirs(rs.REFERENCES, exist_ok=True)
    for name, desc in scene_list().items():
        if args.only and name not in args.only:
            continue
        write_gltf(os.path.join(rs.SCENES, f"{name}.gltf"), desc)
        if not args.scenes_only:
            render(name, desc, args)


if __name__ == "__main__":
    main()
