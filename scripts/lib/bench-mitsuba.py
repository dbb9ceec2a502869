#!/usr/bin/env python3
"""Mitsuba 3 (scalar_rgb, or --variant llvm_ad_rgb) on the white-sky workload of docs/bench-protocol.md, beside `cohort bench`.

The mesh is the world-space triangle soup that `cohort export` writes (binary PLY; the protocol names
Mitsuba's `obj` shape, the `ply` shape with `face_normals` is the same geometry with flat normals),
and the camera is read from the `cohort bench` JSON of the same scene, so both renderers use one
definition of each. Samples/s = res * res * spp / seconds of mi.render (scene loading excluded),
median of --reps renders; the last image is saved as EXR. --ladder renders once at each spp given
(the error-against-time chart) and records their times and images. --variant llvm_ad_rgb is the
fast CPU variant a user would pick (Dr.Jit's LLVM JIT, vectorised over samples): it needs libLLVM
(Debian libllvm19, found through DRJIT_LIBLLVM_PATH, which scripts/bench sets); its first render
includes the JIT compile, so it is rendered once untimed first. --variant cuda_ad_rgb is the GPU
variant (Dr.Jit's CUDA backend with OptiX), for a peer on the same GPU (scripts/lib/mitsuba-cuda-pack).

Run inside the venv of scripts/lib/venv.sh (scripts/bench does):
  python bench-mitsuba.py --ply MESH.ply --camera-json COHORT.json [--view exterior] [--res 512]
                          [--spp 4] [--reps 3] [--ladder 1,2,4,8] [--variant scalar_rgb|llvm_ad_rgb|cuda_ad_rgb]
                          --out DIR --name NAME [--json OUT.json]"""
import argparse
import json
import os
import statistics
import time


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ply", required=True)
    ap.add_argument("--camera-json", required=True)
    ap.add_argument("--view", default="exterior")
    ap.add_argument("--res", type=int, default=512)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--ladder", default="")
    ap.add_argument("--out", required=True)
    ap.add_argument("--name", required=True)
    ap.add_argument("--json", default="")
    ap.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb", "cuda_ad_rgb"])
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402


def camera_from(path, view):
    with open(path) as f:
        data = json.load(f)
    for scene in data["scenes"]:
        for v in scene["views"]:
            if v["view"] == view:
                return v["camera"]
    raise SystemExit(f"{path}: no view '{view}'")


def white_sky_scene(ply, camera, res, spp):
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 5, "rr_depth": 1 << 30},
        "sensor": {
            "type": "perspective",
            "fov": camera["vfov_degrees"],
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(origin=camera["eye"], target=camera["target"], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": res, "height": res, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}},
        "mesh": {
            "type": "ply",
            "filename": ply,
            "face_normals": True,
            "bsdf": {"type": "twosided", "material": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.5}}},
        },
    }


def timed_render(scene, spp, seed):
    """The image, its wall seconds and the process's CPU seconds (every thread, as `cohort bench`'s
    msamples_per_cpu_second: less disturbed by other programs on a loaded machine)."""
    start, cpu_start = time.perf_counter(), time.process_time()
    image = mi.render(scene, spp=spp, seed=seed)
    dr.eval(image)  # the JIT variants evaluate lazily: the render ends when its kernel has run
    dr.sync_thread()
    return image, time.perf_counter() - start, time.process_time() - cpu_start


def main():
    args = ARGS
    mi.set_variant(args.variant)
    os.makedirs(args.out, exist_ok=True)
    camera = camera_from(args.camera_json, args.view)
    start = time.perf_counter()
    scene = mi.load_dict(white_sky_scene(args.ply, camera, args.res, args.spp))
    load_seconds = time.perf_counter() - start
    rates, cpu_rates, image = [], [], None
    if args.variant != "scalar_rgb":
        timed_render(scene, args.spp, 999)  # JIT compile and kernel cache, not timed
    for rep in range(args.reps):
        image, seconds, cpu_seconds = timed_render(scene, args.spp, rep)
        rates.append(args.res * args.res * args.spp / seconds * 1e-6)
        cpu_rates.append(args.res * args.res * args.spp / cpu_seconds * 1e-6)
    exr = os.path.join(args.out, f"{args.name}-mitsuba{'' if args.variant == 'scalar_rgb' else '-' + args.variant}.exr")
    mi.util.write_bitmap(exr, image)
    report = {"peer": "mitsuba", "mitsuba": {"version": mi.__version__, "variant": mi.variant(),
                                             "threads": dr.thread_count()},
              "scene": args.ply, "view": args.view, "camera": camera, "res": args.res, "spp": args.spp,
              "reps": args.reps, "load_seconds": load_seconds,
              "msamples_per_second": {"median": statistics.median(rates), "best": max(rates), "runs": rates},
              "msamples_per_cpu_second": {"median": statistics.median(cpu_rates), "best": max(cpu_rates),
                                          "runs": cpu_rates},
              "exr": exr, "ladder": []}
    for spp in [int(s) for s in args.ladder.split(",") if s]:
        image, seconds, _ = timed_render(scene, spp, 1000 + spp)
        path = os.path.join(args.out, f"{args.name}-mitsuba-{spp}spp.exr")
        mi.util.write_bitmap(path, image)
        report["ladder"].append({"spp": spp, "seconds": seconds, "exr": path})
    print(f"mitsuba {mi.__version__} {args.variant}, {report['mitsuba']['threads']} threads: {args.name} [{args.view}] "
          f"{args.res}x{args.res} {args.spp} spp: {statistics.median(rates):.3f} M samples/s median "
          f"({max(rates):.3f} best), load {load_seconds:.2f}s")
    if args.json:
        tmp = args.json + ".tmp"
        with open(tmp, "w") as f:
            json.dump(report, f, indent=2)
        os.replace(tmp, args.json)


if __name__ == "__main__":
    main()
