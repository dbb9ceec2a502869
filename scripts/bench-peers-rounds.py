#!/usr/bin/env python3
"""Summary of a scripts/bench-peers-rounds directory (issue 28): per scene and view, the faster
Cohort runtime against Mitsuba 3 llvm_ad_rgb in every round, per CPU second and per wall second,
with the median and the least of the rounds. Each ratio divides two figures of one round (the
same scene, minutes apart). Prints Markdown and writes DIR/rounds.json. Standard library only.
Usage: scripts/bench-peers-rounds.py DIR"""
import glob
import json
import os
import statistics
import sys


def round_ratios(row):
    """(per CPU second, wall) ratios of the faster Cohort runtime to llvm_ad_rgb in one peers.json row,
    None where a figure is missing."""
    cpu = [row[rt + "_per_cpu_second"]["msamples_per_cpu_second"] for rt in ("pocl", "intel")
           if row.get(rt + "_per_cpu_second")]
    wall = [row[rt]["msamples_per_second"] for rt in ("pocl", "intel") if row.get(rt)]
    ml_cpu, ml_wall = row.get("mitsuba_llvm_ad_rgb_per_cpu_second"), row.get("mitsuba_llvm_ad_rgb")
    return (max(cpu) / ml_cpu if cpu and ml_cpu else None, max(wall) / ml_wall if wall and ml_wall else None)


def summarise(out):
    """{(scene, view): {"cpu": [...], "wall": [...]}} over the rounds, in round order."""
    scenes = {}
    rounds = sorted(glob.glob(os.path.join(out, "round-*")), key=lambda p: int(p.rsplit("-", 1)[1]))
    for rdir in rounds:
        for path in sorted(glob.glob(os.path.join(rdir, "*", "peers.json"))):
            with open(path) as f:
                doc = json.load(f)
            for row in doc["rows"]:
                cpu, wall = round_ratios(row)
                entry = scenes.setdefault((row["scene"], row["view"]), {"cpu": [], "wall": [], "rounds": []})
                entry["rounds"].append(os.path.basename(rdir))
                entry["cpu"].append(cpu)
                entry["wall"].append(wall)
    return scenes


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: scripts/bench-peers-rounds.py DIR (a scripts/bench-peers-rounds output directory)")
    out = sys.argv[1]
    scenes = summarise(out)
    if not scenes:
        sys.exit(f"{out}: no round-*/*/peers.json (did every bench-runtimes run fail?)")

    def cells(values):
        known = [v for v in values if v is not None]
        rounds = " ".join(f"{v:.2f}" if v is not None else "-" for v in values)
        return [rounds, f"{statistics.median(known):.2f}" if known else "-", f"{min(known):.2f}" if known else "-"]

    print("Faster Cohort runtime / Mitsuba 3 llvm_ad_rgb, M samples per CPU second and per wall second, "
          "one ratio per round (both programs minutes apart).\n")
    print("| scene | view | per CPU s, each round | median | least | wall, each round | median | least |")
    print("|---|---|---|---:|---:|---|---:|---:|")
    rows = []
    for (scene, view), e in sorted(scenes.items()):
        print("| " + " | ".join([scene, view] + cells(e["cpu"]) + cells(e["wall"])) + " |")
        rows.append({"scene": scene, "view": view, **e})
    tmp = os.path.join(out, "rounds.json.tmp")
    with open(tmp, "w") as fh:
        json.dump({"rows": rows}, fh, indent=2)
    os.replace(tmp, os.path.join(out, "rounds.json"))


if __name__ == "__main__":
    main()
