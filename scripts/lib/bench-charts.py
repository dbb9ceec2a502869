#!/usr/bin/env python3
"""Charts from a scripts/bench output directory (matplotlib, PNG):
  bench-rays-per-method.png  path-tracing rays/s per method per scene (the paper's Figure 5)
  bench-error-vs-time.png    relative error to a reference image against render time, per method, and Mitsuba 3
  bench-pth-parameters.png   PTH subtree levels and code layouts against rays/s, with the time breakdown stacked
  bench-simd.png             SIMD efficiency of traversal per method
  bench-scaling.png          rays/s and build time against triangle count (Cohort and Embree)
  bench-large-scenes.png     path-tracing rays/s per method against triangle count (--large of scripts/bench)
The reference of the error chart is a long Cohort `naive` render; its agreement with Mitsuba 3's
render at the same spp is printed and written in the chart (relative RMSE and mean ratio).
Usage (in the venv of scripts/lib/venv.sh): bench-charts.py DIR [--out docs]"""
import argparse
import glob
import json
import os

from bench_data import METHODS, STAGES, load, views


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--out", default="docs")
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402
from image_error import read_exr, rel_rmse  # noqa: E402

mi.set_variant("scalar_rgb")
COLORS = dict(zip(METHODS + ["mitsuba"], plt.get_cmap("tab10").colors))


def device_label(cohort):
    doc = next(iter(cohort.values()))
    s = doc["settings"]
    return f"{doc['device']['name']}, {s['res']}x{s['res']} {s['spp']} spp white sky, median of {s['reps']}"


def method_bars(cohort, methods, value, whisker, ylabel, title, path, ylim=None):
    """Grouped bars: one group per scene and view, one bar per method; whisker(pt, m) adds an
    upward whisker (the best repetition) when given."""
    rows = [(f"{name}\n{v['view']}", v["path_tracing"]) for name, doc in cohort.items() for _, v in views(doc)
            if v["path_tracing"]]
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(max(8, 1.3 * len(rows)), 4.5))
    width = 0.8 / len(methods)
    for i, m in enumerate(methods):
        heights = np.array([value(pt, m) if m in pt else 0 for _, pt in rows])
        x = np.arange(len(rows)) + (i - len(methods) / 2 + 0.5) * width
        ax.bar(x, heights, width, label=m, color=COLORS[m])
        if whisker:
            tops = np.array([whisker(pt, m) if m in pt else 0 for _, pt in rows])
            ax.errorbar(x, heights, yerr=[np.zeros(len(rows)), tops - heights], fmt="none", ecolor="k", lw=0.6)
    ax.set_xticks(np.arange(len(rows)), [r[0] for r in rows], fontsize=8)
    if ylim:
        ax.set_ylim(*ylim)
    ax.set_ylabel(ylabel)
    ax.set_title(f"{title} ({device_label(cohort)})", fontsize=9)
    ax.legend(ncol=len(methods), fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def rays_per_method(cohort, out):
    method_bars(cohort, METHODS, lambda pt, m: pt[m]["mrays_per_second"]["median"],
                lambda pt, m: pt[m]["mrays_per_second"]["best"], "path-tracing Mrays/s (median, whisker to best)",
                "Rays/s per method", os.path.join(out, "bench-rays-per-method.png"))


def simd(cohort, out):
    method_bars(cohort, [m for m in METHODS if m != "naive"], lambda pt, m: pt[m]["simd_efficiency"], None,
                "SIMD efficiency of traversal\n(mean / max steps per 32 rays)",
                "SIMD efficiency per method; naive not instrumented", os.path.join(out, "bench-simd.png"), (0, 1))


def error_vs_time(root, out):
    dirs = sorted(d for d in glob.glob(os.path.join(root, "convergence", "*")) if os.path.isdir(d))
    if not dirs:
        return
    fig, axes = plt.subplots(1, len(dirs), figsize=(6 * len(dirs), 4.5), squeeze=False)
    for ax, d in zip(axes[0], dirs):
        reference = read_exr(os.path.join(d, "reference.exr"))
        with open(os.path.join(d, "reference.json")) as f:
            ref_spp = json.load(f)["image"]["spp"]
        for m in METHODS:
            points = []
            for stats in glob.glob(os.path.join(d, f"{m}-*.json")):
                with open(stats) as f:
                    s = json.load(f)
                points.append((s["timings"]["render_seconds"], rel_rmse(read_exr(stats[:-5] + ".exr"), reference)))
            if points:
                points.sort()
                ax.plot(*zip(*points), "o-", label=m, color=COLORS[m], ms=3, lw=1)
        note = ""
        mpath = os.path.join(d, "mitsuba.json")
        if os.path.exists(mpath):
            with open(mpath) as f:
                mj = json.load(f)
            points = sorted((p["seconds"], rel_rmse(read_exr(p["exr"]), reference)) for p in mj["ladder"])
            ax.plot(*zip(*points), "s--", label="Mitsuba 3 scalar_rgb", color=COLORS["mitsuba"], ms=3, lw=1)
            mref = read_exr(mj["exr"])
            note = (f"\nreference check: Mitsuba at {mj['spp']} spp vs Cohort at {ref_spp} spp: relative RMSE "
                    f"{rel_rmse(mref, reference):.3f}, mean ratio {np.mean(mref) / np.mean(reference):.4f}")
            print(f"{os.path.basename(d)}:{note.strip()}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time, s (load, build, compile excluded)")
        ax.set_ylabel("relative RMSE to the reference")
        ax.set_title(f"{os.path.basename(d)}: reference = Cohort naive, {ref_spp} spp{note}", fontsize=8)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bench-error-vs-time.png"), dpi=120)


def pth_parameters(root, out):
    sweep = load(os.path.join(root, "sweep", "*.json"))
    if not sweep:
        return
    groups = {"levels": [], "code": []}
    for key, doc in sweep.items():
        scene, v = next(views(doc))
        p = v["path_tracing"]["pth"]
        label = f"L={p['coherence']['pth_levels']}" if key.startswith("levels") else p["coherence"]["code"].replace(
            ",", "\n")
        order = p["coherence"]["pth_levels"] if key.startswith("levels") else 0
        groups["levels" if key.startswith("levels") else "code"].append((order, label, p))
        title = f"{scene['name']} [{v['view']}]"
    fig, axes = plt.subplots(2, 2, figsize=(12, 7), sharex="col")
    for col, (kind, rows) in enumerate(groups.items()):
        rows.sort(key=lambda r: r[0])
        x = np.arange(len(rows))
        axes[0][col].bar(x, [r[2]["mrays_per_second"]["median"] for r in rows], color=COLORS["pth"])
        axes[0][col].set_ylabel("path-tracing Mrays/s")
        axes[0][col].set_title(f"pth on {title}: {'subtree levels' if kind == 'levels' else 'code layout'}",
                               fontsize=9)
        bottom = np.zeros(len(rows))
        for stage in STAGES:
            ms = np.array([r[2]["breakdown_seconds"].get(stage, 0) * 1e3 for r in rows])
            if ms.any():
                axes[1][col].bar(x, ms, bottom=bottom, label=stage)
                bottom += ms
        axes[1][col].set_ylabel("device ms per render")
        axes[1][col].set_xticks(x, [r[1] for r in rows], fontsize=7)
        axes[1][col].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bench-pth-parameters.png"), dpi=120)


def scaling(root, out):
    data = load(os.path.join(root, "scaling", "*.json"))
    if not data:
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    for peer, style in (("cohort", "o-"), ("embree", "s--")):
        rows = sorted((next(views(doc))[0]["triangles"], next(views(doc))[1], doc["scenes"][0])
                      for k, doc in data.items() if k.startswith(peer))
        if not rows:
            continue
        tris = [r[0] for r in rows]
        for wl in ("primary", "diffuse"):
            a.plot(tris, [r[1][wl]["mrays_per_second"]["median"] for r in rows], style, label=f"{peer} {wl}")
        key = "kdtree" if peer == "cohort" else "bvh"
        b.plot(tris, [r[2][key]["build_seconds"] for r in rows], style, label=f"{peer} {key} build")
    for ax, label in ((a, "protocol Mrays/s (median)"), (b, "build seconds")):
        ax.set_xscale("log")
        ax.set_xlabel("triangles (midpoint subdivision of one model)")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
    b.set_yscale("log")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bench-scaling.png"), dpi=120)


def large_scenes(root, out):
    path = os.path.join(root, "large", "large-scenes.json")
    if not os.path.exists(path):
        return
    with open(path) as f:
        doc = json.load(f)
    scenes = sorted(doc["scenes"], key=lambda s: s["triangles"])
    if not scenes:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    methods = [m for m in METHODS if any(m in s["methods"] for s in scenes)]
    for m in methods:
        rows = [(s["triangles"], s["methods"][m]["mrays_per_s"]) for s in scenes if m in s["methods"]]
        ax.plot([r[0] for r in rows], [r[1] for r in rows], "o-", color=COLORS.get(m), label=m)
    ax.set_xscale("log")
    ax.set_xlabel("triangles (" + ", ".join(s["name"] for s in scenes) + ")")
    ax.set_ylabel("path-tracing Mrays/s")
    setting = f", {doc['res']}x{doc['res']} {doc['spp']} spp" if "res" in doc else ""
    ax.set_title(f"{doc.get('device') or 'device'} ({doc.get('backend')}){setting}, white sky, interior view",
                 fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bench-large-scenes.png"), dpi=120)


def main():
    args = ARGS
    os.makedirs(args.out, exist_ok=True)
    cohort = load(os.path.join(args.dir, "cohort", "*.json"))
    if cohort:
        rays_per_method(cohort, args.out)
        simd(cohort, args.out)
    error_vs_time(args.dir, args.out)
    pth_parameters(args.dir, args.out)
    scaling(args.dir, args.out)
    large_scenes(args.dir, args.out)
    print(f"charts in {args.out}: " + ", ".join(sorted(os.path.basename(p) for p in glob.glob(os.path.join(
        args.out, "bench-*.png")))))


if __name__ == "__main__":
    main()
