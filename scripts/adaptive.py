#!/usr/bin/env python3
"""Error against time for uniform sampling, adaptive sampling (--target-error) and adaptive +
denoised (--denoise), written to docs/adaptive-error-vs-time.png and docs/adaptive.json.

Scenes: the Cornell box against the Mitsuba 3 reference (test/reference/cornell-box-mitsuba-rgb,
128x128, depth 6); the Crytek Sponza interior (the benchmark protocol's interior view, white sky)
and a crop of it looking up at the open roof (the view of the adaptive test), each against a long
Cohort render (there is no Mitsuba reference of Sponza in the repo; bench-charts.py does the same).
Uniform renders take 16, 32, ... --max-spp samples per pixel; adaptive renders --target-error E for
E in --targets with --spp --adaptive-spp as each pixel's most. Time is the render loop's seconds
(--stats render_seconds; load, build and compile excluded); a denoised point adds the first-hit
AOV render and the denoiser's seconds that `render --denoise` prints. Error: relative MSE (per
pixel and channel (x - ref)^2 / (ref^2 + 0.01)) and mean FLIP (HDR).
Run through scripts/reference --adaptive, which provides the venv (numpy, matplotlib, flip)."""
import argparse
import json
import os
import re
import sys
import tempfile

import flip_evaluator as flip
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import ROOT, references, relative_mse, render_cohort  # noqa: E402

SPONZA = os.path.join(ROOT, "..", "shared", "scenes", "crytek-sponza", "sponza.obj.gz")
SPONZA_VIEWS = {
    # the benchmark protocol's interior view (runtime/bench/scene_bench.cpp)
    "sponza-interior": ["--camera-bounds", "0.25,0.2,0.5,0.75,0.35,0.5", "--fov", "60"],
    # the adaptive test's crop: the atrium's upper walls against the sky
    "sponza-roof": ["--camera-bounds", "0.3,0.3,0.5,0.5,1.3,0.5", "--fov", "30"],
}


def scenes(args):
    """(name, metadata, scene path, extra render options, reference exr or None, title)"""
    out = []
    name, meta, exr, scene = next(r for r in references() if r[0] == "cornell-box-mitsuba-rgb")
    out.append(("cornell-box", meta, scene, [], exr, f"Cornell box 128x128 vs Mitsuba 3 ({meta['spp']} spp)"))
    if os.path.exists(SPONZA):
        w, h = args.sponza_res
        for view, options in SPONZA_VIEWS.items():
            meta = {"resolution": [w, h], "max_depth": 5}  # --white-sky's 5 segments
            out.append((view, meta, SPONZA, ["--white-sky"] + options, None,
                        f"{view} {w}x{h}, white sky, vs Cohort at {args.reference_spp} spp"))
    else:
        print(f"{SPONZA} is absent: the Cornell box only")
    return out


def render(args, scene, meta, spp, seed, out, extra):
    """Renders with --stats; returns (image, seconds, stats, denoise seconds or None)."""
    stats_path = out[: -len(".exr")] + ".json"
    stdout = render_cohort(args.cohort, scene, meta, spp, seed, out, list(extra) + ["--stats", stats_path])
    with open(stats_path) as f:
        stats = json.load(f)
    m = re.search(r"denoised with .* in ([0-9.]+)s \(first-hit AOVs ([0-9.]+)s\)", stdout)
    denoise = float(m.group(1)) + float(m.group(2)) if m else None
    return flip.load(out).astype(np.float64), stats["timings"]["render_seconds"], stats, denoise


def errors(image, reference):
    _, mean_flip, _ = flip.evaluate(reference.astype(np.float32), image.astype(np.float32), "HDR", applyMagma=False)
    return relative_mse(image, reference), float(mean_flip)


def measure(args, tmp, entry):
    name, meta, scene, extra, ref_exr, title = entry
    if ref_exr is None:
        ref_exr = os.path.join(tmp, f"{name}-reference.exr")
        render(args, scene, meta, args.reference_spp, 1, ref_exr, extra)
    reference = flip.load(ref_exr).astype(np.float64)
    rows = {"uniform": [], "adaptive": [], "adaptive+denoised": []}
    spp = 16
    while spp <= args.max_spp:
        out = os.path.join(tmp, f"{name}-uniform-{spp}.exr")
        image, seconds, stats, _ = render(args, scene, meta, spp, 2, out, extra)
        rel, fl = errors(image, reference)
        rows["uniform"].append({"spp": spp, "seconds": seconds, "relative_mse": rel, "flip": fl})
        print(f"{name} uniform {spp:5d} spp: {seconds:7.3f}s relMSE {rel:.5f} FLIP {fl:.4f}")
        spp *= 2
    for target in args.targets:
        out = os.path.join(tmp, f"{name}-adaptive-{target}.exr")
        image, seconds, stats, denoise = render(args, scene, meta, args.adaptive_spp, 2, out,
                                                extra + ["--target-error", str(target), "--denoise"])
        a = stats["adaptive"]
        rel, fl = errors(image, reference)
        point = {"target_error": target, "seconds": seconds, "mean_spp": a["mean_spp"],
                 "tiles_stopped_early": a["tiles_stopped_early"], "tiles": a["tiles"], "relative_mse": rel, "flip": fl}
        rows["adaptive"].append(point)
        print(f"{name} adaptive E={target}: {seconds:7.3f}s mean {a['mean_spp']:.1f} spp, "
              f"{a['tiles_stopped_early']}/{a['tiles']} tiles stopped early, relMSE {rel:.5f} FLIP {fl:.4f}")
        if denoise is not None:
            rel, fl = errors(flip.load(out[: -len(".exr")] + ".denoised.exr").astype(np.float64), reference)
            rows["adaptive+denoised"].append(dict(point, seconds=seconds + denoise, denoise_seconds=denoise,
                                                  relative_mse=rel, flip=fl))
            print(f"{name} adaptive+denoised E={target}: {seconds + denoise:7.3f}s relMSE {rel:.5f} FLIP {fl:.4f}")
    return {"title": title, "reference": os.path.relpath(ref_exr, ROOT) if ref_exr.startswith(ROOT) else
            f"Cohort naive {args.reference_spp} spp seed 1", "series": rows}


def chart(results, path):
    fig, axes = plt.subplots(2, len(results), figsize=(4.6 * len(results), 7.5), squeeze=False)
    styles = {"uniform": "o-", "adaptive": "s-", "adaptive+denoised": "^--"}
    for col, (name, r) in enumerate(results.items()):
        for row, (key, label) in enumerate([("relative_mse", "relative MSE"), ("flip", "mean FLIP")]):
            ax = axes[row][col]
            for series, points in r["series"].items():
                if points:
                    pts = sorted((p["seconds"], p[key]) for p in points)
                    ax.plot(*zip(*pts), styles[series], label=series, ms=4, lw=1)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_xlabel("seconds (render loop; + AOVs and denoiser when denoised)")
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
            if row == 0:
                ax.set_title(r["title"], fontsize=8)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    ap.add_argument("--max-spp", type=int, default=256, help="uniform renders: 16, 32, ... this")
    ap.add_argument("--adaptive-spp", type=int, default=1024, help="adaptive renders: each pixel's most")
    ap.add_argument("--targets", type=float, nargs="+", default=[0.2, 0.1, 0.05, 0.025])
    ap.add_argument("--sponza-res", type=int, nargs=2, default=[64, 48])
    ap.add_argument("--reference-spp", type=int, default=1024, help="Sponza's Cohort reference")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "adaptive-error-vs-time.png"))
    ap.add_argument("--json", default=os.path.join(ROOT, "docs", "adaptive.json"))
    ap.add_argument("--redraw", action="store_true", help="only draw the chart again from --json")
    args = ap.parse_args()
    if args.redraw:
        with open(args.json) as f:
            chart(json.load(f)["scenes"], args.out)
        print(f"wrote {args.out}")
        return 0
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for entry in scenes(args):
            results[entry[0]] = measure(args, tmp, entry)
    chart(results, args.out)
    with open(args.json, "w") as f:
        json.dump({"command": "scripts/reference --adaptive " + " ".join(sys.argv[1:]), "scenes": results}, f, indent=1)
        f.write("\n")
    print(f"wrote {args.out}\nwrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
