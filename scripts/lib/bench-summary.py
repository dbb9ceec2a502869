#!/usr/bin/env python3
"""Medians and ratios from a scripts/bench output directory, as Markdown tables (standard library
only, so it runs wherever python3 does). Usage: scripts/lib/bench-summary.py DIR"""
import os
import sys

from bench_data import STAGES, load, views

OTHERS = ["naive", "sc", "rg", "sc+rg", "hash"]


def fig(x):
    return f"{x['median']:.2f} ({x['best']:.2f})"


def ratio(a, b):
    return f"{a / b:.2f}x" if a and b else "-"


def table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|")
    for r in rows:
        print("| " + " | ".join(str(c) for c in r) + " |")
    print()


def main():
    out = sys.argv[1]
    cohort = load(os.path.join(out, "cohort", "*.json"))
    embree = load(os.path.join(out, "embree", "*.json"))
    mitsuba = load(os.path.join(out, "mitsuba", "*.json"))
    mitsuba_llvm = load(os.path.join(out, "mitsuba-llvm", "*.json"))
    if not cohort:
        sys.exit(f"{out}: no cohort/*.json")
    first = next(iter(cohort.values()))
    dev, build = first["device"], first["cohort"]
    s = first["settings"]
    print(f"Device: {dev['name']} ({dev['platform']}, driver {dev['driver']}, {dev['compute_units']} compute units); "
          f"cohort {build['git_commit']} ({build['build_type']}, {build['compiler']}). White sky {s['res']}x{s['res']} "
          f"at {s['spp']} spp, protocol rays {s['trace_res']}x{s['trace_res']}; median of {s['reps']} (best).")
    emb = next(iter(embree.values()), None)
    if emb:
        print(f"Embree {emb['embree']['version']}, {emb['embree']['threads']} threads ({emb['embree']['api']}).")
    mit = next(iter(mitsuba.values()), None)
    if mit:
        print(f"Mitsuba {mit['mitsuba']['version']} {mit['mitsuba']['variant']}, {mit['mitsuba']['threads']} threads.")
    print()

    print("### Traversal: protocol rays, Mrays/s median (best)\n")
    rows = []
    for name, doc in cohort.items():
        for scene, v in views(doc):
            if "primary" not in v:
                continue
            e = None
            if name in embree:
                e = next((ev for _, ev in views(embree[name]) if ev["view"] == v["view"]), None)
            ebuild = embree[name]["scenes"][0]["bvh"]["build_seconds"] if e else None
            cp, cd = v["primary"]["mrays_per_second"], v["diffuse"]["mrays_per_second"]
            rows.append([name, v["view"], scene["triangles"], f"{scene['kdtree']['build_seconds']:.3f}",
                         f"{ebuild:.3f}" if e else "-", fig(cp), fig(e["primary"]["mrays_per_second"]) if e else "-",
                         ratio(cp["median"], e["primary"]["mrays_per_second"]["median"]) if e else "-", fig(cd),
                         fig(e["diffuse"]["mrays_per_second"]) if e else "-",
                         ratio(cd["median"], e["diffuse"]["mrays_per_second"]["median"]) if e else "-",
                         f"{v['primary']['hits']} / {e['primary']['hits']}" if e else v["primary"]["hits"]])
    table(["scene", "view", "triangles", "KD build s", "Embree BVH s", "Cohort primary", "Embree primary",
           "Cohort/Embree", "Cohort diffuse", "Embree diffuse", "Cohort/Embree", "primary hits Cohort / Embree"], rows)

    methods = first["settings"]["methods"]
    print("### White-sky path tracing: path-tracing Mrays/s median (best), per method\n")
    rows = []
    simd_rows = []
    for name, doc in cohort.items():
        for scene, v in views(doc):
            pt = v["path_tracing"]
            if not pt:
                continue
            med = {m: pt[m]["mrays_per_second"]["median"] for m in pt}
            best_other = max((m for m in OTHERS if m in med), key=lambda m: med[m], default=None)
            best = max(med, key=lambda m: pt[m]["msamples_per_second"]["median"])
            samples = pt[best]["msamples_per_second"]["median"]
            mk = f"{name}-{v['view']}"
            ms = mitsuba[mk]["msamples_per_second"]["median"] if mk in mitsuba else None
            ml = mitsuba_llvm[mk]["msamples_per_second"]["median"] if mk in mitsuba_llvm else None
            rows.append([name, v["view"]] + [fig(pt[m]["mrays_per_second"]) if m in pt else "-" for m in methods] +
                        [ratio(med.get("pth"), med.get("naive")),
                         f"{ratio(med.get('pth'), med.get(best_other))} ({best_other})" if best_other else "-",
                         f"{samples:.3f} ({best})", f"{ms:.3f}" if ms else "-", ratio(samples, ms) if ms else "-",
                         f"{ml:.3f}" if ml else "-", ratio(samples, ml) if ml else "-"])
            simd_rows.append([name, v["view"]] + [f"{pt[m]['simd_efficiency']:.3f}" if m in pt else "-" for m in methods])
    table(["scene", "view"] + methods + ["pth / naive", "pth / best other", "best Cohort M samples/s",
                                         "Mitsuba scalar_rgb M samples/s", "Cohort/scalar_rgb",
                                         "Mitsuba llvm_ad_rgb M samples/s", "Cohort/llvm_ad_rgb"], rows)
    print("### SIMD efficiency of traversal (mean over max steps per 32 rays; naive: not measured)\n")
    table(["scene", "view"] + methods, simd_rows)

    print("### Time breakdown of the sorting methods (device ms per render, median repetition)\n")
    rows = []
    for name, doc in cohort.items():
        for scene, v in views(doc):
            for m in ("hash", "pth"):
                if m in v["path_tracing"]:
                    b = v["path_tracing"][m]["breakdown_seconds"]
                    rows.append([name, v["view"], m] + [f"{b.get(k, 0) * 1e3:.1f}" for k in STAGES] +
                                [f"{v['path_tracing'][m]['render_seconds'] * 1e3:.1f}"])
    if rows:
        table(["scene", "view", "method"] + STAGES + ["render wall ms"], rows)

    sweep = load(os.path.join(out, "sweep", "*.json"))
    if sweep:
        print("### PTH parameters (pth only): path-tracing Mrays/s and device ms per stage\n")
        rows = []
        for key, doc in sorted(sweep.items(), key=lambda kv: (kv[0].split("-")[0], len(kv[0]), kv[0])):
            scene, v = next(views(doc))
            p = v["path_tracing"]["pth"]
            b = p["breakdown_seconds"]
            rows.append([f"{scene['name']} [{v['view']}]", p["coherence"]["code"], p["coherence"]["pth_levels"],
                         fig(p["mrays_per_second"]), f"{p['simd_efficiency']:.3f}"] +
                        [f"{b.get(k, 0) * 1e3:.1f}" for k in ("pth walk", "sort", "resume traversal", "shadow rays",
                                                             "shading", "other")])
        table(["scene", "code", "levels", "Mrays/s", "SIMD eff.", "pth walk", "sort", "resume", "shadow", "shading",
               "other"], rows)

    scaling = load(os.path.join(out, "scaling", "*.json"))
    if scaling:
        print("### Scaling: one model midpoint-subdivided, protocol rays Mrays/s median (best)\n")
        rows = []
        for level in sorted({k.split("-")[1] for k in scaling}):
            c = scaling.get(f"cohort-{level}")
            e = scaling.get(f"embree-{level}")
            if not c:
                continue
            scene, v = next(views(c))
            ev = next(views(e))[1] if e else None
            rows.append([scene["triangles"], f"{scene['kdtree']['build_seconds']:.3f}",
                         f"{e['scenes'][0]['bvh']['build_seconds']:.3f}" if e else "-",
                         fig(v["primary"]["mrays_per_second"]), fig(ev["primary"]["mrays_per_second"]) if ev else "-",
                         fig(v["diffuse"]["mrays_per_second"]), fig(ev["diffuse"]["mrays_per_second"]) if ev else "-"])
        table(["triangles", "KD build s", "Embree BVH s", "Cohort primary", "Embree primary", "Cohort diffuse",
               "Embree diffuse"], rows)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    main()
