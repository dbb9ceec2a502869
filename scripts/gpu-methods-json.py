#!/usr/bin/env python3
"""docs/results/gpu-methods.json from `cohort bench --json` files (issue 25's shape).

One object per (backend, scene, view, spp) with the medians of the bench: for every method its
path-tracing Mrays/s, its sort's device milliseconds (key sort and payload gather, per render) and
its host gap (the render loop's wall time minus the device's busy time, per render), both of the
repetition with the median rate.

Usage: scripts/gpu-methods-json.py OUT.json BENCH.json... [--note TEXT]
"""
import argparse
import json
from pathlib import Path


def entries(bench):
    device = bench["device"]
    for scene in bench["scenes"]:
        for view in scene["views"]:
            methods = {}
            for name, m in view.get("path_tracing", {}).items():
                kernels = m.get("kernel_seconds", {})
                busy = sum(kernels.values())
                sort = sum(s for k, s in kernels.items() if k.startswith("sort"))
                methods[name] = {"mrays_per_s": round(m["mrays_per_second"]["median"], 2),
                                 "sort_ms": round(sort * 1e3, 2),
                                 "host_gap_ms": round(max(m["render_seconds"] - busy, 0.0) * 1e3, 2)}
                if "auto_pick" in m:
                    methods[name]["auto_pick"] = m["auto_pick"]
            if not methods:
                continue
            sizes = {m.get("wavefront_size") for m in view["path_tracing"].values()} - {None}
            yield {"device": f'{device["name"]} (driver {device["driver"]})', "backend": device.get("backend"),
                   "commit": bench["cohort"]["git_commit"], "scene": scene["name"], "view": view["view"],
                   "triangles": scene["triangles"], "res": bench["settings"]["res"], "spp": bench["settings"]["spp"],
                   "wavefront_size": max(sizes) if sizes else None, "methods": methods}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out", type=Path)
    p.add_argument("bench", type=Path, nargs="+")
    p.add_argument("--note", default="")
    args = p.parse_args()
    runs = [e for path in args.bench for e in entries(json.loads(path.read_text()))]
    doc = {"source": "cohort bench --json, converted by scripts/gpu-methods-json.py", "note": args.note,
           "runs": runs}
    args.out.write_text(json.dumps(doc, indent=1) + "\n")
    for r in runs:
        best_other = max(v["mrays_per_s"] for k, v in r["methods"].items() if k not in ("pth", "auto"))
        pth = r["methods"].get("pth", {}).get("mrays_per_s")
        line = f'{r["backend"]} {r["scene"]} {r["view"]} {r["spp"]} spp: ' + ", ".join(
            f'{k} {v["mrays_per_s"]:.0f}' for k, v in r["methods"].items())
        if pth:
            line += f"; pth / best other {pth / best_other:.2f}x"
        print(line)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
