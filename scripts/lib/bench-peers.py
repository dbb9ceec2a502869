#!/usr/bin/env python3
"""The CPU peer a user would pick, from a `scripts/lib/bench-runtimes --peers` directory:
per scene and view, Cohort's fastest method on PoCL and on Intel's runtime beside Mitsuba 3 scalar_rgb
and llvm_ad_rgb (white sky, M samples/s medians), the faster runtime's ratio to each, and where the
distance goes: protocol diffuse rays against Embree's (traversal alone), path-tracing rays/s against
protocol diffuse rays/s (what shading and the path loop add), and the share of the render's wall time
the device spent in kernels (the rest is per-pass host work). Prints Markdown and writes DIR/peers.json.
Standard library only. Usage: scripts/lib/bench-peers.py DIR"""
import json
import os
import sys

from bench_data import load, views


def fastest(view, figure="msamples_per_second"):
    """(method, figures) of the view's method with the most samples/s (or per CPU second), or (None, None)."""
    pt = {m: f for m, f in (view.get("path_tracing") or {}).items() if figure in f}
    if not pt:
        return None, None
    m = max(pt, key=lambda k: pt[k][figure]["median"])
    return m, pt[m]


def peer_rate(docs, key, figure="msamples_per_second"):
    return docs[key][figure]["median"] if key in docs and figure in docs[key] else None




def main():
    out = sys.argv[1]
    cohort = {rt: load(os.path.join(out, rt, "cohort", "*.json")) for rt in ("pocl", "intel")}
    embree = load(os.path.join(out, "pocl", "embree", "*.json"))
    scalar = load(os.path.join(out, "pocl", "mitsuba", "*.json"))
    llvm = load(os.path.join(out, "pocl", "mitsuba-llvm", "*.json"))
    rows = []
    for name, doc in cohort["pocl"].items():
        intel_doc = cohort["intel"].get(name)
        intel_views = {v["view"]: v for _, v in views(intel_doc)} if intel_doc else {}
        embree_views = {v["view"]: v for _, v in views(embree[name])} if name in embree else {}
        for scene, v in views(doc):
            row = {"scene": name, "view": v["view"], "triangles": scene["triangles"]}
            for rt, view in (("pocl", v), ("intel", intel_views.get(v["view"]))):
                m, f = fastest(view) if view else (None, None)
                row[rt] = None if not f else {
                    "method": m, "msamples_per_second": f["msamples_per_second"]["median"],
                    "path_mrays_per_second": f["mrays_per_second"]["median"],
                    "rays_per_sample": f["rays"] / (doc["settings"]["res"] ** 2 * doc["settings"]["spp"]),
                    "kernel_share": sum(f["kernel_seconds"].values()) / f["render_seconds"] if f["render_seconds"] else None,
                    "protocol_diffuse_mrays_per_second":
                        view["diffuse"]["mrays_per_second"]["median"] if "diffuse" in view else None}
                m, f = fastest(view, "msamples_per_cpu_second") if view else (None, None)
                row[rt + "_per_cpu_second"] = None if not f else {
                    "method": m, "msamples_per_cpu_second": f["msamples_per_cpu_second"]["median"]}
            e = embree_views.get(v["view"])
            row["embree_diffuse_mrays_per_second"] = e["diffuse"]["mrays_per_second"]["median"] if e else None
            key = f"{name}-{v['view']}"
            row["mitsuba_scalar_rgb"], row["mitsuba_llvm_ad_rgb"] = peer_rate(scalar, key), peer_rate(llvm, key)
            row["mitsuba_scalar_rgb_per_cpu_second"] = peer_rate(scalar, key, "msamples_per_cpu_second")
            row["mitsuba_llvm_ad_rgb_per_cpu_second"] = peer_rate(llvm, key, "msamples_per_cpu_second")
            runs = [rt for rt in ("pocl", "intel") if row[rt]]
            row["faster_runtime"] = max(runs, key=lambda rt: row[rt]["msamples_per_second"]) if runs else None
            rows.append(row)

    def r(a, b):
        return f"{a / b:.2f}" if a and b else "-"

    first = next(iter(cohort["pocl"].values()), None)
    if first:
        s = first["settings"]
        mit = next(iter(llvm.values()), None) or next(iter(scalar.values()), None)
        print(f"White sky {s['res']}x{s['res']} at {s['spp']} spp, {s['max_depth']} segments, median of {s['reps']}; "
              f"methods {','.join(s['methods'])}; cohort {first['cohort']['git_commit']}"
              + (f"; Mitsuba {mit['mitsuba']['version']}, {mit['mitsuba']['threads']} threads" if mit else "") + ".\n")
    print("| scene | view | Cohort PoCL M samples/s (method) | Cohort Intel (method) | Mitsuba scalar_rgb | "
          "Mitsuba llvm_ad_rgb | faster Cohort / llvm_ad_rgb | / scalar_rgb |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        cells = [f"{row[rt]['msamples_per_second']:.3f} ({row[rt]['method']})" if row[rt] else "-"
                 for rt in ("pocl", "intel")]
        best = row[row["faster_runtime"]]["msamples_per_second"] if row["faster_runtime"] else None
        ms, ml = row["mitsuba_scalar_rgb"], row["mitsuba_llvm_ad_rgb"]
        print(f"| {row['scene']} | {row['view']} | {cells[0]} | {cells[1]} | {f'{ms:.3f}' if ms else '-'} | "
              f"{f'{ml:.3f}' if ml else '-'} | {r(best, ml)} | {r(best, ms)} |")
    print("\nThe same renders per CPU second of the process (every thread; M samples per CPU second): on a "
          "loaded machine, less disturbed by other programs than wall time.\n")
    print("| scene | view | Cohort PoCL (method) | Cohort Intel (method) | Mitsuba scalar_rgb | Mitsuba llvm_ad_rgb | "
          "best Cohort / llvm_ad_rgb | / scalar_rgb |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        c = [row[rt + "_per_cpu_second"] for rt in ("pocl", "intel")]
        best = max((x["msamples_per_cpu_second"] for x in c if x), default=None)
        ms, ml = row["mitsuba_scalar_rgb_per_cpu_second"], row["mitsuba_llvm_ad_rgb_per_cpu_second"]
        print(f"| {row['scene']} | {row['view']} | " +
              " | ".join(f"{x['msamples_per_cpu_second']:.3f} ({x['method']})" if x else "-" for x in c) + " | " +
              " | ".join(f"{x:.3f}" if x else "-" for x in (ms, ml)) + f" | {r(best, ml)} | {r(best, ms)} |")
    print("\nWhere the distance goes, on the faster runtime: protocol diffuse rays (traversal alone) against "
          "Embree's, path-tracing rays/s against protocol diffuse rays/s, rays per sample, and the kernels' "
          "share of the render's wall time.\n")
    print("| scene | view | runtime (method) | Cohort diffuse Mrays/s | Embree diffuse | Cohort/Embree | "
          "path-tracing Mrays/s | path / diffuse | rays per sample | kernel share of wall |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        if not row["faster_runtime"]:
            continue
        f = row[row["faster_runtime"]]
        cd, ed = f["protocol_diffuse_mrays_per_second"], row["embree_diffuse_mrays_per_second"]
        share = f"{f['kernel_share']:.2f}" if f["kernel_share"] is not None else "-"
        print(f"| {row['scene']} | {row['view']} | {row['faster_runtime']} ({f['method']}) | "
              f"{f'{cd:.2f}' if cd else '-'} | {f'{ed:.2f}' if ed else '-'} | {r(cd, ed)} | "
              f"{f['path_mrays_per_second']:.2f} | {r(f['path_mrays_per_second'], cd)} | {f['rays_per_sample']:.2f} | "
              f"{share} |")
    tmp = os.path.join(out, "peers.json.tmp")
    with open(tmp, "w") as fh:
        json.dump({"settings": first["settings"] if first else None, "rows": rows}, fh, indent=2)
    os.replace(tmp, os.path.join(out, "peers.json"))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    main()
