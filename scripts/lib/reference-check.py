#!/usr/bin/env python3
"""Cohort against every stored Mitsuba 3 reference (test/reference/), with two figures per scene:
the relative L1 error sum|cohort - ref| / sum(ref), and the mean FLIP error (NVIDIA's perceptual
metric, PyPI flip-evaluator, HDR mode at its default 67 pixels per degree). Cohort renders each
scene with the CLI at --spp samples per pixel. Fails (exit 1) when a scene's FLIP passes
--max-flip or its relative error passes --max-relative; thresholds are documented in
docs/lights.md. Run through scripts/reference --check, which provides the venv."""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import ROOT, references, render_cohort


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--max-flip", type=float, default=0.08)
    ap.add_argument("--max-relative", type=float, default=0.1)
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import flip_evaluator as flip  # noqa: E402
import numpy as np  # noqa: E402


def main():
    args = ARGS
    failed = []
    print(f"{'scene':28} {'spp':>5} {'rel. L1':>8} {'FLIP':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, meta, exr, scene in references():
            out = os.path.join(tmp, name + ".exr")
            render_cohort(args.cohort, scene, meta, args.spp, 1, out)
            ref, img = flip.load(exr), flip.load(out)
            rel = float(np.abs(img - ref).sum() / ref.sum())
            _, mean_flip, _ = flip.evaluate(ref, img, "HDR", applyMagma=False)
            ok = mean_flip <= args.max_flip and rel <= args.max_relative
            print(f"{name:28} {args.spp:5d} {rel:8.4f} {mean_flip:7.4f} {'ok' if ok else 'FAIL'}")
            if not ok:
                failed.append(name)
    if failed:
        print(f"above the thresholds (FLIP {args.max_flip}, relative L1 {args.max_relative}): {', '.join(failed)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
