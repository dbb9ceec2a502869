#!/usr/bin/env python3
"""Error against time for uniform sampling, adaptive sampling (--target-error) and adaptive +
denoised (--denoise), written to docs/adaptive-error-vs-time.png and docs/adaptive.json.

Scenes: the Cornell box against the Mitsuba 3 reference (test/reference/cornell-box-mitsuba-rgb,
128x128, depth 6) and the Crytek Sponza interior (the benchmark protocol's interior view, white
sky) against a long Cohort render (there is no Mitsuba reference of Sponza in the repo;
bench-charts.py does the same); --scenes sponza-roof adds a crop looking up at the open roof,
where the sky's clean tiles make any stopping rule win.
Uniform renders take 16, 32, ... --max-spp samples per pixel; adaptive renders --target-error E for
E in --targets with --spp --adaptive-spp as each pixel's most. Every render runs --repeats times
(the image is the same bits each time: only its time varies) and a point's time is the median of
the render loop's seconds (--stats render_seconds and render_cpu_seconds; load, build and compile
excluded; the chart's x axis is the CPU seconds); a denoised
point adds the median first-hit AOV render and denoiser seconds that `render --denoise` prints.
Error: relative MSE (per pixel and channel (x - ref)^2 / (ref^2 + 0.01)) and mean FLIP (HDR).
Equal-time ratios: an adaptive point's error over uniform's at the same seconds, interpolated
(log-log) between the uniform points of the same run; the same at equal CPU seconds (--stats
render_cpu_seconds: the process's CPU time over the render loop, every thread's), which a loaded
machine disturbs less than the wall time.

The Sponza references are Cohort renders with seed 1, the measured renders seed 2: independent,
so the reference's own noise adds a constant to every curve's expected relative MSE. The script
estimates that floor by fitting uniform's relative MSE to a / spp + floor and reports it beside
a / --reference-spp (what the reference's noise should be); ratios are of the raw figures.
Run through scripts/reference --adaptive, which provides the venv (numpy, matplotlib, flip)."""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import ROOT, references, relative_mse, render_cohort


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    ap.add_argument("--max-spp", type=int, default=512, help="uniform renders: 16, 32, ... this")
    ap.add_argument("--adaptive-spp", type=int, default=2048, help="adaptive renders: each pixel's most")
    ap.add_argument("--targets", type=float, nargs="+", default=[0.14, 0.1, 0.07, 0.05, 0.035])
    ap.add_argument("--repeats", type=int, default=3, help="renders per point; its time is their median")
    ap.add_argument("--scenes", nargs="+", default=["cornell-box", "sponza-interior"],
                    help="of cornell-box sponza-interior sponza-roof")
    ap.add_argument("--reference-cache", default=os.path.join(ROOT, "build", "adaptive-references"),
                    help="where the Sponza references are kept between runs")
    ap.add_argument("--sponza-res", type=int, nargs=2, default=[64, 48])
    ap.add_argument("--reference-spp", type=int, default=4096, help="Sponza's Cohort reference (seed 1)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "adaptive-error-vs-time.png"))
    ap.add_argument("--json", default=os.path.join(ROOT, "docs", "adaptive.json"))
    ap.add_argument("--redraw", action="store_true", help="only draw the chart again from --json")
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import flip_evaluator as flip  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402


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
    if "cornell-box" in args.scenes:
        out.append(("cornell-box", meta, scene, [], exr, f"Cornell box 128x128 vs Mitsuba 3 ({meta['spp']} spp)"))
    if os.path.exists(SPONZA):
        w, h = args.sponza_res
        for view, options in SPONZA_VIEWS.items():
            if view not in args.scenes:
                continue
            meta = {"resolution": [w, h], "max_depth": 5}  # --white-sky's 5 segments
            out.append((view, meta, SPONZA, ["--white-sky"] + options, None,
                        f"{view} {w}x{h}, white sky, vs Cohort at {args.reference_spp} spp (other seed)"))
    else:
        print(f"{SPONZA} is absent: the Cornell box only")
    return out


def render_once(args, scene, meta, spp, seed, out, extra):
    """Renders with --stats; returns (stats, denoise seconds or None, the EXR's bytes)."""
    stats_path = out[: -len(".exr")] + ".json"
    render_cohort(args.cohort, scene, meta, spp, seed, out, list(extra) + ["--stats", stats_path])
    with open(stats_path) as f:
        stats = json.load(f)
    denoise = stats.get("denoise")
    with open(out, "rb") as f:
        return stats, denoise["seconds"] + denoise["aov_seconds"] if denoise else None, f.read()


def render_points(args, scene, meta, extra, jobs):
    """Renders every (out, spp, extra options) job --repeats times, the repeats in turn (one round
    of every job, then the next), so that the machine's load drifts over all of them alike.
    Returns per job (stats, median render seconds, median render CPU seconds, median denoise seconds
    or None)."""
    seconds = [[] for _ in jobs]
    cpu = [[] for _ in jobs]
    denoise = [[] for _ in jobs]
    stats, images = [None] * len(jobs), [None] * len(jobs)
    for _ in range(args.repeats):
        for i, (out, spp, options) in enumerate(jobs):
            stats[i], d, image = render_once(args, scene, meta, spp, 2, out, list(extra) + options)
            if images[i] is not None and image != images[i]:
                raise RuntimeError(f"{out}: a repeat gave other bits")
            images[i] = image
            seconds[i].append(stats[i]["timings"]["render_seconds"])
            cpu[i].append(stats[i]["timings"]["render_cpu_seconds"])
            if d is not None:
                denoise[i].append(d)
    return [(stats[i], float(np.median(seconds[i])), float(np.median(cpu[i])),
             float(np.median(denoise[i])) if denoise[i] else None) for i in range(len(jobs))]


def uniform_at(points, seconds, key, clock="seconds"):
    """Uniform's `key` at `seconds` of `clock` (seconds: wall, cpu_seconds: CPU), interpolated
    log-log between its points; None outside them."""
    pts = sorted((p[clock], p[key]) for p in points)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= seconds <= t1 and t1 > t0:
            w = np.log(seconds / t0) / np.log(t1 / t0)
            return float(np.exp((1 - w) * np.log(e0) + w * np.log(e1)))
    return None


def reference_floor(points):
    """Least-squares fit of relative MSE = a / spp + floor over the uniform points: (a, floor)."""
    x = np.array([1.0 / p["spp"] for p in points])
    y = np.array([p["relative_mse"] for p in points])
    a, floor = np.polyfit(x, y, 1)
    return float(a), float(floor)


def errors(image, reference):
    _, mean_flip, _ = flip.evaluate(reference.astype(np.float32), image.astype(np.float32), "HDR", applyMagma=False)
    return relative_mse(image, reference), float(mean_flip)


def measure(args, tmp, entry):
    name, meta, scene, extra, ref_exr, title = entry
    if ref_exr is None:
        # kept in --reference-cache (a render of minutes): the same bits every time
        os.makedirs(args.reference_cache, exist_ok=True)
        ref_exr = os.path.join(args.reference_cache, f"{name}-{meta['resolution'][0]}x{meta['resolution'][1]}-"
                                                     f"{args.reference_spp}spp-seed1.exr")
        if not os.path.exists(ref_exr):
            render_cohort(args.cohort, scene, meta, args.reference_spp, 1, ref_exr, extra)
    reference = flip.load(ref_exr).astype(np.float64)
    rows = {"uniform": [], "adaptive": [], "adaptive+denoised": []}
    load = [os.getloadavg()[0]]
    uniform_spp = [16 * 2 ** k for k in range(16) if 16 * 2 ** k <= args.max_spp]
    jobs = [(os.path.join(tmp, f"{name}-uniform-{spp}.exr"), spp, []) for spp in uniform_spp]
    jobs += [(os.path.join(tmp, f"{name}-adaptive-{target}.exr"), args.adaptive_spp,
              ["--target-error", str(target), "--denoise"]) for target in args.targets]
    results = render_points(args, scene, meta, extra, jobs)
    for (out, spp, options), (stats, seconds, cpu, denoise) in zip(jobs, results):
        rel, fl = errors(flip.load(out).astype(np.float64), reference)
        if not options:
            rows["uniform"].append({"spp": spp, "seconds": seconds, "cpu_seconds": cpu, "relative_mse": rel, "flip": fl})
            print(f"{name} uniform {spp:5d} spp: {seconds:7.3f}s ({cpu:.3f}s CPU) relMSE {rel:.5f} FLIP {fl:.4f}")
            continue
        target = float(options[1])
        a = stats["adaptive"]
        point = {"target_error": target, "seconds": seconds, "cpu_seconds": cpu, "mean_spp": a["mean_spp"],
                 "estimated_error": a["estimated_error"], "tiles_stopped_early": a["tiles_stopped_early"],
                 "tiles": a["tiles"], "relative_mse": rel, "flip": fl}
        rows["adaptive"].append(point)
        print(f"{name} adaptive E={target}: {seconds:7.3f}s ({cpu:.3f}s CPU) mean {a['mean_spp']:.1f} spp, estimated error "
              f"{a['estimated_error']:.4f}, {a['tiles_stopped_early']}/{a['tiles']} tiles stopped early, "
              f"relMSE {rel:.5f} FLIP {fl:.4f}")
        if denoise is not None:
            rel, fl = errors(flip.load(out[: -len(".exr")] + ".denoised.exr").astype(np.float64), reference)
            # the denoiser's and AOVs' seconds are wall time (they run after the render loop)
            rows["adaptive+denoised"].append(dict(point, seconds=seconds + denoise, cpu_seconds=cpu + denoise,
                                                  denoise_seconds=denoise, relative_mse=rel, flip=fl))
            print(f"{name} adaptive+denoised E={target}: {seconds + denoise:7.3f}s relMSE {rel:.5f} FLIP {fl:.4f}")
    load.append(os.getloadavg()[0])
    for series in ("adaptive", "adaptive+denoised"):
        for p in rows[series]:
            for key in ("relative_mse", "flip"):
                u = uniform_at(rows["uniform"], p["seconds"], key)
                p[f"{key}_vs_uniform_at_equal_time"] = p[key] / u if u else None
                u = uniform_at(rows["uniform"], p["cpu_seconds"], key, "cpu_seconds")
                p[f"{key}_vs_uniform_at_equal_cpu_time"] = p[key] / u if u else None
            show = lambda k: "%.3fx" % p[k] if p[k] else "n/a"  # noqa: E731
            print(f"{name} {series} E={p['target_error']}: {p['seconds']:.2f}s, relative MSE "
                  f"{show('relative_mse_vs_uniform_at_equal_time')} uniform's at that time "
                  f"({show('relative_mse_vs_uniform_at_equal_cpu_time')} at that CPU time), FLIP "
                  f"{show('flip_vs_uniform_at_equal_time')} ({show('flip_vs_uniform_at_equal_cpu_time')})")
    fit = {}
    if ref_exr.startswith(args.reference_cache):
        a, floor = reference_floor(rows["uniform"])
        fit = {"uniform_fit_a": a, "reference_floor_fit": floor, "reference_floor_expected": a / args.reference_spp}
        print(f"{name}: uniform relative MSE ~ {a:.4f} / spp + {floor:.6f}; the reference's own noise should be "
              f"{a / args.reference_spp:.6f}")
    return {"title": title, "load_average": load, **fit,
            "reference": os.path.relpath(ref_exr, ROOT) if ref_exr.startswith(ROOT) and not fit else
            f"Cohort {args.reference_spp} spp seed 1 (the measured renders: seed 2)", "series": rows}


def chart(results, path):
    fig, axes = plt.subplots(2, len(results), figsize=(4.6 * len(results), 7.5), squeeze=False)
    styles = {"uniform": "o-", "adaptive": "s-", "adaptive+denoised": "^--"}
    for col, (name, r) in enumerate(results.items()):
        for row, (key, label) in enumerate([("relative_mse", "relative MSE"), ("flip", "mean FLIP")]):
            ax = axes[row][col]
            for series, points in r["series"].items():
                if points:
                    pts = sorted((p.get("cpu_seconds", p["seconds"]), p[key]) for p in points)
                    ax.plot(*zip(*pts), styles[series], label=series, ms=4, lw=1)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_xlabel("CPU seconds of the render loop (+ AOVs and denoiser)", fontsize=8)
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
            if row == 0:
                ax.set_title(r["title"], fontsize=8)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    args = ARGS
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
