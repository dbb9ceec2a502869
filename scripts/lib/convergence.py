#!/usr/bin/env python3
"""Convergence of Cohort to Mitsuba 3 on the Cornell box: renders scenes/cornell-box.gltf at
1, 2, 4, ... --max-spp samples per pixel (each with its own seed), measures the relative RMS error
against test/reference/cornell-box-mitsuba-rgb.exr, fits the slope of log(error) against log(spp)
and plots both to docs/convergence.png. An unbiased estimator's error falls as spp^(-1/2); the
script fails (exit 1) when the fitted slope leaves -0.5 +- --tolerance. The reference's own noise
(10,368 spp) is subtracted from the squared error (its variance per pixel is estimated as the
Cohort variance scaled by the spp ratio), so it does not flatten the tail.
Run through scripts/reference --convergence, which provides the venv (matplotlib, flip-evaluator)."""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import ROOT, references, render_cohort


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    ap.add_argument("--max-spp", type=int, default=1024)
    ap.add_argument("--tolerance", type=float, default=0.05)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "convergence.png"))
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import flip_evaluator as flip  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    args = ARGS
    name, meta, exr, scene = next(r for r in references() if r[0] == "cornell-box-mitsuba-rgb")
    ref = flip.load(exr).astype(np.float64)
    ref_spp = meta["spp"]
    spps, errors = [], []
    with tempfile.TemporaryDirectory() as tmp:
        spp = 1
        while spp <= args.max_spp:
            out = os.path.join(tmp, f"cbox-{spp}.exr")
            render_cohort(args.cohort, scene, meta, spp, 1000 + spp, out)
            img = flip.load(out).astype(np.float64)
            mse = np.mean((img - ref) ** 2)
            # E[mse] = var_cohort / spp + var_ref / ref_spp with the same per-sample variance
            # (the same estimator, up to the filter): remove the reference's share
            mse_cohort = mse / (1 + spp / ref_spp)
            errors.append(float(np.sqrt(mse_cohort) / np.sqrt(np.mean(ref ** 2))))
            spps.append(spp)
            print(f"{spp:6d} spp: relative RMS error {errors[-1]:.5f}")
            spp *= 2
    slope, intercept = np.polyfit(np.log(spps), np.log(errors), 1)
    print(f"fitted slope {slope:.3f} (unbiased: -0.5)")
    fig, ax = plt.subplots(figsize=(5, 4), dpi=120)
    ax.loglog(spps, errors, "o-", label="Cohort vs Mitsuba 3 reference")
    fit = np.exp(intercept) * np.array(spps, dtype=np.float64) ** slope
    ax.loglog(spps, fit, "--", label=f"fit: slope {slope:.3f}")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel("relative RMS error")
    ax.set_title("Cornell box 128x128, max depth 6")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out)
    print(f"wrote {args.out}")
    if abs(slope + 0.5) > args.tolerance:
        print(f"slope {slope:.3f} is outside -0.5 +- {args.tolerance}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
