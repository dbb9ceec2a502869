#!/usr/bin/env python3
"""Mitsuba 3 reference render of the Cornell box (docs/decisions.md: Cohort's cornell-box.gltf must match
Mitsuba's render of cbox-rgb.xml at the same resolution, spp and max_depth 6).

Renders the external model cornell-box-mitsuba/cbox-rgb.xml (scenes/external.json) with the scalar_rgb variant in passes of
--pass-spp samples (each pass its own seed) until --seconds have passed or --max-spp is reached, and
averages the passes (each is an unbiased estimate, so the mean is too). Writes
test/reference/cornell-box-mitsuba-rgb.exr (float RGB) and a JSON file with the settings beside it.
Run through scripts/reference, which provides mitsuba and numpy."""
import argparse
import json
import os
import platform
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import ROOT, accumulate_passes


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--max-depth", type=int, default=6)
    ap.add_argument("--seconds", type=float, default=300.0, help="render time budget (default 5 minutes)")
    ap.add_argument("--pass-spp", type=int, default=64)
    ap.add_argument("--max-spp", type=int, default=1 << 16)
    ap.add_argument("--out", default=os.path.join(ROOT, "test", "reference", "cornell-box-mitsuba-rgb.exr"))
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402


MODELS = os.environ.get("COHORT_SHARED_SCENES") or os.path.join(os.path.dirname(ROOT), "shared", "scenes")  # scenes/external.json
SCENE = os.path.join(MODELS, "cornell-box-mitsuba", "cbox-rgb.xml")


def main():
    args = ARGS

    mi.set_variant("scalar_rgb")
    scene = mi.load_file(SCENE, res=args.res, spp=args.pass_spp, max_depth=args.max_depth)
    mean, spp, passes, elapsed = accumulate_passes(
        lambda seed: np.array(mi.render(scene, spp=args.pass_spp, seed=seed), dtype=np.float64), args.pass_spp,
        args.max_spp, args.seconds)
    mean = mean.astype(np.float32)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    mi.Bitmap(mean, pixel_format=mi.Bitmap.PixelFormat.RGB).write(args.out)
    settings = {
        "scene": "external model " + os.path.relpath(SCENE, MODELS),  # scenes/external.json
        "mitsuba_version": mi.__version__,
        "variant": "scalar_rgb",
        "integrator": "path",
        "max_depth": args.max_depth,
        "resolution": [args.res, args.res],
        "spp": spp,
        "passes": passes,
        "seeds": f"0..{passes - 1} (one per pass of {args.pass_spp} spp)",
        "sampler": "independent",
        "reconstruction_filter": "box (fragments/base.xml)",
        "render_seconds": round(elapsed, 1),
        "machine": f"{platform.machine()}, {os.cpu_count()} logical CPUs",
        "mean_rgb": [float(v) for v in mean.reshape(-1, 3).mean(axis=0)],
    }
    with open(os.path.splitext(args.out)[0] + ".json", "w") as f:
        json.dump(settings, f, indent=2)
        f.write("\n")
    print(f"{args.out}: {args.res}x{args.res}, {spp} spp in {passes} passes, {elapsed:.1f} s, "
          f"mean rgb {settings['mean_rgb']}")


if __name__ == "__main__":
    main()
