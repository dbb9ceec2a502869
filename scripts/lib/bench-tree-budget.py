#!/usr/bin/env python3
"""Rays/s against device bytes per triangle: the --tree-budget trade-off.

Renders each scene with a KD-tree (--tree: compact, the CPU's, by default; deep on a GPU; the
renderer's own default is the 4-wide BVH, which has no depth to trade) and with --tree-budget set
to fractions of that tree's bytes (nodes, leaf lists, triangles), so the depth limit drops until the tree fits; reads
path-tracing rays/s (the render loop's), device bytes per triangle, depth and nodes from --stats.
White sky (docs/bench-protocol.md), --method naive, medians over --reps renders. Writes OUT/tree-budget.json,
prints a markdown table and draws OUT/tree-budget.png (matplotlib: `scripts/bench tree-budget` runs this
with the venv of scripts/lib/venv.sh when it can make one).

Usage: scripts/bench tree-budget [--scenes sponza-interior,bunny] [--fractions 1,0.8,...] [--res 128]
                                 [--spp 8] [--reps 3] [--device D] [--tree compact|deep]
                                 [--cohort build/cohort] [--out DIR]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("COHORT_SHARED_SCENES", ROOT.parent / "shared" / "scenes"))
INTERIOR = ["--camera-bounds", "0.25,0.2,0.5,0.75,0.35,0.5", "--fov", "60"]
SCENES = {
    "sponza-interior": ("crytek-sponza/sponza.obj.gz", INTERIOR),
    "sponza": ("crytek-sponza/sponza.obj.gz", []),
    "bunny": ("bunny/bun_zipper.ply", []),
    "conference": ("conference/conference.obj.gz", []),
    "armadillo": ("armadillo/Armadillo.ply.gz", []),
}


def render(args, scene, extra, budget_mib, stats):
    cmd = [str(args.cohort), "render", str(scene), "--white-sky", *extra, "--res", f"{args.res}x{args.res}",
           "--spp", str(args.spp), "--method", "naive", "--tree", args.tree, "--stats", str(stats),
           "-o", str(args.out / "image")]
    if budget_mib:
        cmd += ["--tree-budget", f"{budget_mib:.3f}"]
    if args.device:
        cmd += ["--device", args.device]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    s = json.loads(stats.read_text())
    return {"mrays_per_s": s["rays_per_second"] * 1e-6, "bytes_per_triangle": s["device_memory"]["bytes_per_triangle"],
            "tree_mib": s["kdtree"]["bytes"] / 1048576.0, "depth": s["kdtree"]["depth"], "nodes": s["kdtree"]["nodes"],
            "sah": s["kdtree"]["sah_cost"], "device": s.get("devices", [{}])[0].get("name")}


def measure(args, name):
    model, extra = SCENES[name]
    scene = SHARED / model
    if not scene.exists():
        print(f"[{name}] {scene} not found, skipped", file=sys.stderr)
        return None
    stats = args.out / "stats.json"
    default_mib = render(args, scene, extra, 0, stats)["tree_mib"]
    points = []
    for fraction in args.fractions:
        budget = 0 if fraction >= 1 else fraction * default_mib
        try:
            runs = [render(args, scene, extra, budget, stats) for _ in range(args.reps)]
        except subprocess.CalledProcessError as e:  # exit 2: no tree fits the budget (the message says why)
            print(f"| {name} | {fraction:.2f} | does not fit: {e.stderr.strip().splitlines()[-1] if e.stderr else e} |")
            break
        point = dict(runs[0], fraction=fraction, budget_mib=budget or None,
                     mrays_per_s=statistics.median(r["mrays_per_s"] for r in runs),
                     mrays_runs=[r["mrays_per_s"] for r in runs])
        points.append(point)
        print(f"| {name} | {fraction:.2f} | {point['tree_mib']:.1f} | {point['bytes_per_triangle']:.1f} | "
              f"{point['depth']} | {point['nodes']} | {point['sah']:.1f} | {point['mrays_per_s']:.3f} | "
              f"{point['mrays_per_s'] / points[0]['mrays_per_s']:.2f} |", flush=True)
    return points


def chart(results, path, label):
    try:
        import matplotlib
    except ImportError:
        print(f"no matplotlib in {sys.executable}: the chart is skipped (scripts/bench tree-budget runs the "
              "venv of scripts/lib/venv.sh when it can make one; --json-only skips the chart)", file=sys.stderr)
        return False

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for name, points in results.items():
        x = [p["bytes_per_triangle"] for p in points]
        y = [p["mrays_per_s"] / points[0]["mrays_per_s"] for p in points]
        ax.plot(x, y, marker="o", label=f"{name} (default {points[0]['mrays_per_s']:.2f} Mrays/s)")
        for p, yy in zip(points, y):
            ax.annotate(f"d{p['depth']}", (p["bytes_per_triangle"], yy), textcoords="offset points", xytext=(4, -10),
                        fontsize=7)
    ax.set_xlabel("device bytes per triangle (nodes, leaf lists, triangles, shading)")
    ax.set_ylabel("path-tracing rays/s, relative to the default tree")
    ax.set_title(f"--tree-budget: rays/s against memory\n{label}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return True


def main():
    p = argparse.ArgumentParser(prog="scripts/bench tree-budget", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scenes", default="sponza-interior,bunny")
    p.add_argument("--fractions", default="1,0.8,0.65,0.5,0.42,0.37")
    p.add_argument("--res", type=int, default=128)
    p.add_argument("--spp", type=int, default=8)
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--device", default="")
    p.add_argument("--tree", default="compact", choices=["compact", "deep"])
    p.add_argument("--cohort", type=Path, default=ROOT / "build" / "cohort")
    p.add_argument("--out", type=Path, default=ROOT / "build" / "bench-tree-budget")
    p.add_argument("--json-only", action="store_true", help="no chart (no matplotlib needed)")
    args = p.parse_args()
    args.fractions = [float(f) for f in args.fractions.split(",")]
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"White sky, naive, {args.res}x{args.res}, {args.spp} spp, median of {args.reps}")
    print("| scene | budget / default | tree MiB | bytes/triangle | depth | nodes | SAH | Mrays/s | relative |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    results = {}
    for name in args.scenes.split(","):
        points = measure(args, name)
        if points:
            results[name] = points
    device = next((p["device"] for pts in results.values() for p in pts if p.get("device")), None)
    doc = {"device": device, "res": args.res, "spp": args.spp, "reps": args.reps, "scenes": results}
    (args.out / "tree-budget.json").write_text(json.dumps(doc, indent=1))
    print(f"wrote {args.out / 'tree-budget.json'}")
    if not args.json_only and results:
        if chart(results, args.out / "tree-budget.png", f"{device}, {args.res}x{args.res} {args.spp} spp white sky"):
            print(f"wrote {args.out / 'tree-budget.png'}")


if __name__ == "__main__":
    main()
