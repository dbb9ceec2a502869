#!/usr/bin/env python3
"""Summary of a scripts/bench-peers-rounds directory: per scene and view, the faster
Cohort runtime against Mitsuba 3 llvm_ad_rgb in every round, per CPU second and per wall second,
with the median and the least of the rounds. Each ratio divides two figures of one round (the
same scene, minutes apart). Beside them, the worst pairing: Cohort's slowest round against
Mitsuba's fastest, a bound that no drift of the machine between rounds can flatter. Prints
Markdown and writes DIR/rounds.json. Standard library only.
Usage: scripts/lib/bench-peers-rounds.py DIR"""
import glob
import json
import os
import statistics
import sys


def rates(row):
    """{"cpu": (Cohort, llvm_ad_rgb), "wall": (Cohort, llvm_ad_rgb)} of one peers.json row: M samples
    per CPU second and per wall second, Cohort's on its faster runtime; None where a figure is missing."""
    cpu = [row[rt + "_per_cpu_second"]["msamples_per_cpu_second"] for rt in ("pocl", "intel")
           if row.get(rt + "_per_cpu_second")]
    wall = [row[rt]["msamples_per_second"] for rt in ("pocl", "intel") if row.get(rt)]
    return {"cpu": (max(cpu) if cpu else None, row.get("mitsuba_llvm_ad_rgb_per_cpu_second")),
            "wall": (max(wall) if wall else None, row.get("mitsuba_llvm_ad_rgb"))}


def ratio(cohort, mitsuba):
    """One round's Cohort / llvm_ad_rgb, or None where a figure is missing."""
    return cohort / mitsuba if cohort and mitsuba else None


def worst_pairing(pairs):
    """Cohort's least rate over the rounds divided by llvm_ad_rgb's greatest, or None."""
    cohort = [c for c, _ in pairs if c]
    mitsuba = [m for _, m in pairs if m]
    return min(cohort) / max(mitsuba) if cohort and mitsuba else None


def summarise(out):
    """{(scene, view): entry} over the rounds, in round order: each entry lists the rounds, the (Cohort,
    llvm_ad_rgb) rates per CPU second and per wall second ("cpu_rates", "wall_rates"), their ratios
    ("cpu", "wall") and the worst pairing of each."""
    scenes = {}
    rounds = sorted(glob.glob(os.path.join(out, "round-*")), key=lambda p: int(p.rsplit("-", 1)[1]))
    for rdir in rounds:
        for path in sorted(glob.glob(os.path.join(rdir, "*", "peers.json"))):
            with open(path) as f:
                doc = json.load(f)
            for row in doc["rows"]:
                entry = scenes.setdefault((row["scene"], row["view"]),
                                          {"cpu": [], "wall": [], "rounds": [], "cpu_rates": [], "wall_rates": []})
                entry["rounds"].append(os.path.basename(rdir))
                for kind, pair in rates(row).items():
                    entry[kind + "_rates"].append(pair)
                    entry[kind].append(ratio(*pair))
    for entry in scenes.values():
        for kind in ("cpu", "wall"):
            entry[kind + "_worst_pairing"] = worst_pairing(entry[kind + "_rates"])
    return scenes


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: scripts/lib/bench-peers-rounds.py DIR (a scripts/bench-peers-rounds output directory)")
    out = sys.argv[1]
    scenes = summarise(out)
    if not scenes:
        sys.exit(f"{out}: no round-*/*/peers.json (did every bench-runtimes run fail?)")

    def fmt(v):
        return f"{v:.2f}" if v is not None else "-"

    def cells(values, worst):
        known = [v for v in values if v is not None]
        return [" ".join(fmt(v) for v in values), fmt(statistics.median(known) if known else None),
                fmt(min(known) if known else None), fmt(worst)]

    print("Faster Cohort runtime / Mitsuba 3 llvm_ad_rgb, M samples per CPU second and per wall second, "
          "one ratio per round (both programs minutes apart); worst pairing: Cohort's slowest round "
          "against llvm_ad_rgb's fastest.\n")
    print("| scene | view | per CPU s, each round | median | least | worst pairing | "
          "wall, each round | median | least | worst pairing |")
    print("|---|---|---|---:|---:|---:|---|---:|---:|---:|")
    rows = []
    for (scene, view), e in sorted(scenes.items()):
        print("| " + " | ".join([scene, view] + cells(e["cpu"], e["cpu_worst_pairing"]) +
                                cells(e["wall"], e["wall_worst_pairing"])) + " |")
        rows.append({"scene": scene, "view": view, **e})
    tmp = os.path.join(out, "rounds.json.tmp")
    with open(tmp, "w") as fh:
        json.dump({"rows": rows}, fh, indent=2)
    os.replace(tmp, os.path.join(out, "rounds.json"))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0)
    main()
