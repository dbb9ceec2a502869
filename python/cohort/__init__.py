"""Cohort from Python: load a scene once, render it many times, images as NumPy arrays.

    import cohort
    scene = cohort.Scene("scenes/cornell-box.gltf")
    r = scene.render(spp=64, res=(256, 256))
    r.image            # float32 (256, 256, 3), linear RGB

Every render option is `cohort render`'s, parsed and checked by the same code, so a render equals
the command line's with the same options bit for bit (docs/python.md).
"""

import json
import os
import sys

from ._cohort import DenoiseError, DeviceError, InputError
from . import _cohort
from ._cohort import read_exr, read_exr_channel

__all__ = ["devices", "Scene", "Render", "read_exr", "read_exr_channel", "InputError", "DeviceError", "DenoiseError"]

_AOVS = ("albedo", "normal", "depth")


def devices():
    """Every OpenCL device (and CUDA GPU), with its limits and what Cohort does there: a list of
    dicts with the figures `cohort devices` prints ("runs", "refusal", "work_group", "pth_levels",
    "sorts", ...)."""
    return json.loads(_cohort.devices_json())


def _option(name):
    return "--" + name.replace("_", "-")


def _number(name, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{name}: expected a number, got {value!r}")
    return repr(value) if isinstance(value, float) else str(value)


class Render:
    """One render: `image` (H, W, 3) float32 linear RGB, `aovs` (a dict of the AOVs asked for:
    "albedo" and "normal" (H, W, 3), "depth" (H, W)), `denoised` (with denoise=True, else None),
    `stats` (the dict `cohort render --stats` writes)."""

    def __init__(self, image, aovs, denoised, stats):
        self.image = image
        self.aovs = aovs
        self.denoised = denoised
        self.stats = stats

    def __repr__(self):
        h, w, _ = self.image.shape
        return f"<cohort.Render {w}x{h}, {self.stats['image']['spp']} spp, method {self.stats['method']}>"


class Scene:
    """A scene loaded once: the file is read, the devices opened and, at the first render, the tree
    built and the scene uploaded; later renders (other cameras, sample counts, seeds, methods)
    reuse all of it and the compiled kernels.

    device: an index or a name substring, "all", or a comma list, as `--device`; backend: "opencl"
    or "cuda"; tree: "auto", "bvh4", "bvh8", "deep" or "compact"; tree_budget and memory_limit in MiB;
    cache=False does not read or write the kernel binary cache."""

    def __init__(self, path, device=None, backend="opencl", tree="auto", tree_budget=None, memory_limit=None,
                 cache=True):
        self.path = os.fspath(path)
        base = [self.path, "--backend", backend, "--tree", tree]
        if device is not None:
            base += ["--device", str(device)]
        if tree_budget is not None:
            base += ["--tree-budget", _number("tree_budget", tree_budget)]
        if memory_limit is not None:
            base += ["--memory-limit", _number("memory_limit", memory_limit)]
        if not cache:
            base.append("--no-cache")
        self._base = base
        self._loaded = _cohort.LoadedScene(base)
        self._info = None

    @property
    def info(self):
        """What `cohort info` prints, as a dict: triangles, bounds, materials, lights, camera, the
        tree and the device bytes."""
        if self._info is None:
            self._info = json.loads(self._loaded.info())
        return self._info

    def render(self, spp=None, res=None, method="auto", seed=None, max_depth=None, camera=None, white_sky=False,
               env=None, aov=(), target_error=None, time=None, denoise=False, progress=None, **options):
        """Renders and returns a Render.

        spp, seed, max_depth, method, target_error, time: as `cohort render`'s options; res: (width,
        height); camera: a dict with "eye", "target", optional "up" (default +Y) and "fov" (degrees,
        default the scene's), or None for the scene's camera; env: a radiance (one number or
        (r, g, b)) or an equirectangular EXR's path; aov: names among "albedo", "normal", "depth";
        progress: called with a dict (samples, target, rays, seconds) while the render runs.
        Any other `cohort render` option goes by its name with underscores (camera_bounds=
        "0.5,0.5,0.5,1,0.5,0.5", fov=40, pass_spp=4, no_rr=True, code="paper", pth_levels=6).
        Ctrl-C stops the render after its current pass and raises KeyboardInterrupt; the scene
        stays usable."""
        args = list(self._base)
        if spp is not None:
            args += ["--spp", _number("spp", spp)]
        if res is not None:
            if len(res) != 2:
                raise InputError(f"res: expected (width, height), got {res!r}")
            args += ["--res", f"{int(res[0])}x{int(res[1])}"]
        args += ["--method", str(method)]
        if seed is not None:
            args += ["--seed", _number("seed", seed)]
        if max_depth is not None:
            args += ["--max-depth", _number("max_depth", max_depth)]
        if white_sky:
            args.append("--white-sky")
        if env is not None:
            if isinstance(env, (str, os.PathLike)):
                args += ["--env", os.fspath(env)]
            elif isinstance(env, (int, float)):
                args += ["--env", _number("env", env)]
            else:
                args += ["--env", ",".join(_number("env", float(v)) for v in env)]
        aov = (aov,) if isinstance(aov, str) else tuple(aov)
        for name in aov:
            if name not in _AOVS:
                raise InputError(f"aov: {name!r} is not one of {', '.join(_AOVS)}")
        if aov:
            args += ["--aov", ",".join(aov)]
        if target_error is not None:
            args += ["--target-error", _number("target_error", target_error)]
        if time is not None:
            args += ["--time", _number("time", time)]
        if denoise:
            args.append("--denoise")
        for name, value in options.items():
            if value is True:
                args.append(_option(name))
            elif value is not False and value is not None:
                args += [_option(name), str(value)]
        cam = None
        if camera is not None:
            try:
                eye, target = camera["eye"], camera["target"]
                up = camera.get("up", (0.0, 1.0, 0.0))
                fov = camera.get("fov", self.info["camera"]["fov"])
                cam = [float(v) for v in (*eye, *target, *up)] + [float(fov)]
            except (KeyError, TypeError, ValueError) as e:
                raise InputError(f"camera: expected a dict with eye, target (3 numbers each), up, fov: {e}") from None
            if len(cam) != 10:
                raise InputError("camera: eye, target and up take 3 numbers each")
        out = self._loaded.render(args, cam, progress, [sys.prefix])
        aovs = {name: out["aovs"][name] for name in aov} if out["aovs"] else {}
        return Render(out["image"], aovs, out["denoised"], json.loads(out["stats"]))
