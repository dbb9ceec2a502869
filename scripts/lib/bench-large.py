#!/usr/bin/env python3
"""Large-scene benchmark: KD-tree build figures and (with --render) white-sky path tracing on
scenes of 1M to 31M triangles generated from the external models (scenes/external.json; never committed).

Scenes are midpoint-subdivided Crytek Sponza (4x triangles per level), 7 copies of it side by side
for ~31M (instancing flattened into one mesh, the middle copy at the interior view), and the
conference and armadillo at ~1M; `cohort export` writes them once to OUT/scenes.

Build figures come from `cohort bench --methods none --no-traversal --json` (one build per run):
build seconds, nodes, depth, SAH cost, the tree's bytes per triangle; medians over --reps runs. --baseline BIN runs a second cohort binary on
the same scenes, alternating with this one, and prints the ratios (before/after on one machine).
--embree BIN (cohort-embree-bench) alternates Embree 3's high-quality BVH build of each scene on
the same CPUs and prints the build's time over Embree's per round: the large-scene target of 1 s for 1M
triangles, anchored at Embree-high's 0.70 s for 977K, is a ratio of at most 1.40 on any machine.

--render renders each scene per method with `cohort render --white-sky` at the interior view of
docs/bench-protocol.md (--camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60) and reads rays/s, build
time, device memory and time to first pixel from --stats; OUT/large-scenes.json then has the shape
of results/raw/nvidia-h200-2026-12-02-2f72453/gpu-large-scenes.json.

Examples:
  scripts/bench large                                  # 1M scenes and Sponza x16 (4.5M), build only
  scripts/bench large --sizes 1m --baseline OLD/cohort # before/after the build change
  scripts/bench large --sizes 1m --cpus 0,1            # the build on 2 cores of a bigger machine
  scripts/bench large --sizes 1m --cpus 0,1 --tree compact --embree build/cohort-embree-bench
  scripts/bench large --sizes 1m --tree bvh4           # the 4-wide BVH a default render builds
  scripts/bench large --sizes 4m,18m,31m --render --device NVIDIA --methods naive,sc+rg,pth
  scripts/bench large --sizes 31m --render --backend cuda
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
INTERIOR = ["--camera-bounds", "0.25,0.2,0.5,0.75,0.35,0.5", "--fov", "60"]
SPONZA = "crytek-sponza/sponza.obj.gz"
# name: (shared model, subdivision levels, copies along z)
SCENES = {
    "orig": [("sponza", SPONZA, 0, 1)],
    "1m": [("sponza-1m", SPONZA, 1, 1), ("conference-1m", "conference/conference.obj.gz", 1, 1),
           ("armadillo-1m", "armadillo/Armadillo.ply.gz", 1, 1)],
    "4m": [("sponza-4m", SPONZA, 2, 1)],
    "18m": [("sponza-18m", SPONZA, 3, 1)],
    "31m": [("sponza-31m", SPONZA, 2, 7)],
}
METHODS = "naive,wavefront,sc,rg,sc+rg,hash,pth,auto"


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


def make_scene(cohort, shared, out_dir, name, model, levels, copies):
    path = out_dir / f"{name}.ply"
    if not path.exists():
        source = shared / model
        if not source.exists():
            print(f"[{name}] {source} not found, skipped", file=sys.stderr)
            return None
        print(f"[{name}] exporting {model} subdivided {levels}x, {copies} copies", file=sys.stderr)
        run([str(cohort), "export", str(source), "-o", str(path), "--subdivide", str(levels),
             "--copies", str(copies)])
    return path


def child_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def tree_figures_of(doc, tree=""):
    """(triangles kept, depth, nodes, SAH cost, build seconds, tree bytes) of one scene of a
    `cohort bench --json` file. The BVH's build seconds add the pass that keeps the triangles (a
    one-leaf KD-tree), as a render's build_seconds do."""
    scenes = doc.get("scenes") or []
    if not scenes or not scenes[0].get("kdtree"):
        sys.exit("scripts/bench large: no tree in cohort bench's JSON")
    scene = scenes[0]
    kd = scene["kdtree"]
    kept = scene["triangles"] - kd.get("dropped_triangles", 0)
    kind = tree if tree in ("bvh4", "bvh8", "bvh8f") else kd.get("kind")
    bvh = kd.get(kind) if kind in ("bvh4", "bvh8", "bvh8f") else None
    if bvh:
        return kept, bvh["depth"], bvh["nodes"], bvh["sah_cost"], bvh["build_seconds"] + kd["build_seconds"], bvh["bytes"]
    return kept, kd["depth"], kd["nodes"], kd["sah_cost"], kd["build_seconds"], kd["bytes"]


def tree_figures(cohort, scene, cpus="", tree=""):
    """One build through `cohort bench --methods none --no-traversal --json` (`--tree TREE` when
    given, else the deep KD-tree): dict of build_s, cpu_s (user + system seconds of the whole run, loading included: on a
    shared machine wall seconds depend on the load, CPU seconds much less), nodes, depth, sah,
    triangles and tree_bytes_per_tri (the tree's own bytes; `cohort info` gives the whole scene's)."""
    cpu = child_cpu_seconds()
    pin = ["taskset", "-c", cpus] if cpus else []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "bench.json"
        # without --tree the deep KD-tree, as `cohort info` builds (bench's own default is the BVH)
        run(pin + [str(cohort), "bench", str(scene), "--methods", "none", "--no-traversal", "--json", str(out),
                   "--tree", tree or "deep"])
        doc = json.loads(out.read_text())
    cpu = child_cpu_seconds() - cpu
    kept, depth, nodes, sah, build_s, tree_bytes = tree_figures_of(doc, tree)
    return {"depth": depth, "nodes": nodes, "sah": sah, "build_s": build_s, "cpu_s": cpu, "triangles": kept,
            "bytes_per_tri": tree_bytes / max(kept, 1)}


# The KD build's target as a ratio to Embree-high on the same machine: 1 s per 1M triangles
# where Embree 3's high-quality build takes 0.70 s per 977K.
EMBREE_TARGET_RATIO = (1.0 / 1e6) / (0.70 / 977e3)


def cpu_count(cpus):
    """How many CPUs a taskset list names ("0,1", "0-15", "0-3,8"); all of them when empty."""
    if not cpus:
        return os.cpu_count()
    count = 0
    for part in cpus.split(","):
        first, _, last = part.partition("-")
        count += int(last or first) - int(first) + 1
    return count


def embree_seconds(embree, scene, cpus=""):
    """Embree 3's high-quality BVH build of the scene with as many threads as CPUs, seconds (from
    cohort-embree-bench's --json)."""
    pin = ["taskset", "-c", cpus] if cpus else []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "embree.json"
        run(pin + [str(embree), str(scene), "--threads", str(cpu_count(cpus)), "--build-quality", "high",
                   "--trace-res", "16", "--reps", "3", "--view", "interior", "--json", str(out)])
        doc = json.loads(out.read_text())
    seconds = ((doc.get("scenes") or [{}])[0].get("bvh") or {}).get("build_seconds")
    if seconds is None:
        sys.exit("scripts/bench large: no BVH build in cohort-embree-bench's JSON")
    return float(seconds)


def embree_rows(name, build_s, embree_s):
    """The table rows comparing the builds with the Embree builds alternated with them: per round,
    each build over the Embree build right after it, their median and range against the target."""
    if min(embree_s) <= 0.0:  # printed as 0.000 s: no ratio to take
        return [f"| {name} | | Embree high | {max(embree_s):.3f} | | | | too small to time | |"]
    ratios = sorted(b / e for b, e in zip(build_s, embree_s))
    median = statistics.median(ratios)
    verdict = "met" if median <= EMBREE_TARGET_RATIO else "not met"
    return [f"| {name} | | Embree high | {statistics.median(embree_s):.3f} | | | | | |",
            f"| {name} | | new/Embree-high | {median:.2f}x ({ratios[0]:.2f}-{ratios[-1]:.2f}) | | | | "
            f"target <= {EMBREE_TARGET_RATIO:.2f}x: {verdict} | |"]


def build_table(args, scenes):
    binaries = [("new", args.cohort)] + ([("baseline", args.baseline)] if args.baseline else [])
    cores = f"pinned to CPUs {args.cpus}" if args.cpus else f"machine: {os.cpu_count()} cores"
    what = f"--tree {args.tree}" if args.tree else "KD-tree"
    print(f"\n{what} build, median of {args.reps} (cohort bench --json, no rays; {cores})")
    header = "| scene | triangles | binary | build s | run CPU s | nodes | depth | SAH cost | tree bytes/tri |"
    print(header + ("\n|---|---:|---|---:|---:|---:|---:|---:|---:|"))
    results = {}
    for name, path in scenes:
        runs = {label: [] for label, _ in binaries}
        embree = []
        for _ in range(args.reps):  # alternate, so both see the same load
            for label, binary in binaries:
                runs[label].append(tree_figures(binary, path, args.cpus, args.tree))
            if args.embree:
                embree.append(embree_seconds(args.embree, path, args.cpus))
        for label, _ in binaries:
            r = runs[label]
            med = {k: statistics.median(x[k] for x in r) for k in r[0]}
            results[(name, label)] = med
            print(f"| {name} | {med['triangles']:.0f} | {label} | {med['build_s']:.3f} | {med['cpu_s']:.2f} | {med['nodes']:.0f} | "
                  f"{med['depth']:.0f} | {med['sah']:.2f} | {med.get('bytes_per_tri', float('nan')):.1f} |")
        if args.baseline:
            new, old = results[(name, "new")], results[(name, "baseline")]
            print(f"| {name} | | new/baseline | {new['build_s'] / old['build_s']:.3f}x | {new['cpu_s'] / old['cpu_s']:.3f}x | "
                  f"{new['nodes'] / old['nodes']:.3f}x | | {new['sah'] / old['sah']:.4f}x | |")
        if embree:
            for line in embree_rows(name, [r["build_s"] for r in runs["new"]], embree):
                print(line)
    return results


def render_table(args, scenes):
    methods = METHODS if args.methods == "all" else args.methods
    print(f"\nWhite-sky path tracing, interior view, {args.res}x{args.res}, {args.spp} spp, "
          f"backend {args.backend}, Mrays/s")
    print("| scene | triangles | build s | device MiB | first pixel s | " + " | ".join(methods.split(",")) + " |")
    print("|---|---:|---:|---:|---:|" + "---:|" * len(methods.split(",")))
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], text=True,
                            capture_output=True).stdout.strip() or None
    summary = {"device": None, "backend": args.backend, "commit": commit, "res": args.res, "spp": args.spp,
               "scenes": []}
    stats = args.out / "stats.json"
    for name, path in scenes:
        entry = {"name": name, "methods": {}}
        for method in methods.split(","):
            cmd = [str(args.cohort), "render", str(path), "--white-sky", *INTERIOR, "--res",
                   f"{args.res}x{args.res}", "--spp", str(args.spp), "--method", method,
                   "--backend", args.backend, "--stats", str(stats), "-o", str(args.out / f"{name}-{method}")]
            if args.device:
                cmd += ["--device", args.device]
            start = time.monotonic()
            run(cmd)
            wall = time.monotonic() - start
            s = json.loads(stats.read_text())
            timings = s["timings"]
            entry.update(triangles=s["scene_stats"]["triangles"], build_s=timings["build_seconds"],
                         device_mib=s.get("device_memory", {}).get("total", 0) / 1048576.0)
            # time to first pixel: everything before the render loop (load, build, upload, compile)
            entry.setdefault("first_pixel_s", wall - timings["render_seconds"])
            entry["methods"][method] = {"mrays_per_s": s["rays_per_second"] / 1e6}
            summary["device"] = s.get("device", {}).get("name") if isinstance(s.get("device"), dict) else s.get("device")
        summary["scenes"].append(entry)
        rates = " | ".join(f"{entry['methods'][m]['mrays_per_s']:.3g}" for m in methods.split(","))
        print(f"| {name} | {entry['triangles']} | {entry['build_s']:.2f} | {entry['device_mib']:.1f} | "
              f"{entry['first_pixel_s']:.1f} | {rates} |")
    (args.out / "large-scenes.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"\nwrote {args.out / 'large-scenes.json'}")


def main():
    p = argparse.ArgumentParser(prog="scripts/bench large", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cohort", type=Path, default=ROOT / "build" / "cohort")
    p.add_argument("--baseline", type=Path, help="a second cohort binary to compare build figures with")
    p.add_argument("--embree", type=Path, help="cohort-embree-bench: alternate Embree-high's BVH build "
                   "and print the build's time over it against the KD build's target ratio")
    p.add_argument("--shared", type=Path,
                   default=Path(os.environ.get("COHORT_SHARED_SCENES", ROOT.parent / "shared" / "scenes")))
    p.add_argument("--out", type=Path, default=ROOT / "build" / "bench-large")
    p.add_argument("--sizes", default="1m,4m", help="comma list of orig (Crytek Sponza as shipped), 1m, 4m, 18m, 31m ('' for none)")
    p.add_argument("--scene", type=Path, action="append", default=[], help="another scene file (repeatable)")
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--tree", default="", choices=["", "deep", "compact", "bvh4", "bvh8", "bvh8f"],
                   help="the tree to build (default: the deep KD-tree); the BVHs' build "
                        "seconds include keeping the triangles, as a render's do")
    p.add_argument("--cpus", default="", help="pin the builds to these CPUs (taskset -c "
                   "LIST, e.g. 0,1 for the 2-core target on a bigger machine)")
    p.add_argument("--render", action="store_true", help="also render each scene per method")
    p.add_argument("--no-build-table", action="store_true", help="with --render: skip the build table")
    p.add_argument("--methods", default="all")
    p.add_argument("--backend", default="opencl")
    p.add_argument("--device", default="")
    p.add_argument("--res", type=int, default=1024)
    p.add_argument("--spp", type=int, default=16)
    args = p.parse_args()
    if not args.cohort.exists():
        sys.exit(f"scripts/bench large: {args.cohort} not found (build first: source scripts/setup.sh && cohort_build)")
    if args.embree:
        args.embree = args.embree.resolve()  # a bare name would be looked up on PATH
    if args.embree and not args.embree.exists():
        sys.exit(f"scripts/bench large: {args.embree} not found (it is built with cohort when Embree 3 is installed)")
    (args.out / "scenes").mkdir(parents=True, exist_ok=True)
    scenes = []
    for size in filter(None, args.sizes.split(",")):
        if size not in SCENES:
            sys.exit(f"scripts/bench large: unknown size '{size}' (have {', '.join(SCENES)})")
        for name, model, levels, copies in SCENES[size]:
            path = make_scene(args.cohort, args.shared, args.out / "scenes", name, model, levels, copies)
            if path:
                scenes.append((name, path))
    scenes += [(path.name.split(".")[0], path) for path in args.scene]  # sponza.obj.gz: sponza
    if not args.no_build_table:
        build_table(args, scenes)
    if args.render:
        render_table(args, scenes)


if __name__ == "__main__":
    main()
