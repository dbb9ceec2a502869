#!/usr/bin/env python3
"""Summarise the --stats JSON that scripts/gpu-breakdown-run keeps: one Markdown row per variant with
the median over repetitions of path-tracing Mrays/s and device milliseconds per stage.

Usage: scripts/breakdown-summary.py RUN_DIR [RUN_DIR...]
Each RUN_DIR holds one NAME.json per variant (gpu-breakdown-run's OUT_DIR); give several for
repetitions of the same variants. Variants print in the order of the first RUN_DIR's log.txt when
there is one, else by name.
"""
import json
import statistics
import sys
from pathlib import Path

# (column, kernels summed); 'key' is the kernel that computes the sort keys (pth: the walk of the
# top subtree with its key; hash: the key alone), 'trace' every kernel that traverses the tree for
# extension rays
STAGES = [
    ("key", ["pth", "hash"]),
    ("sort", ["sort histogram", "sort scatter"]),
    ("resume", ["resume"]),
    ("extend", ["extend"]),
    ("trace", ["pth", "resume", "extend"]),
    ("shade", ["shade"]),
]


def figures(path):
    d = json.loads(path.read_text())
    kernels = {name: v["seconds"] * 1e3 for name, v in d["kernels"].items() if isinstance(v, dict) and "seconds" in v}
    coherence = d.get("coherence", {})
    row = {
        "Mrays/s": d["rays_per_second"] / 1e6,
        "levels": coherence.get("pth_levels", 0),
        "key bits": coherence.get("key_bits", 0),
        "busy ms": d["device"]["busy_seconds"] * 1e3,
        "wall ms": d["timings"]["render_seconds"] * 1e3,
    }
    for column, names in STAGES:
        row[column + " ms"] = sum(kernels.get(n, 0.0) for n in names)
    return row


def variant_order(run_dirs):
    log = run_dirs[0] / "log.txt"
    names = []
    if log.exists():
        for line in log.read_text().splitlines():
            name = line.split(":", 1)[0]
            if name and name not in names:
                names.append(name)
    for run in run_dirs:
        for f in sorted(run.glob("*.json")):
            if f.stem not in names:
                names.append(f.stem)
    return names


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    run_dirs = [Path(a) for a in argv[1:]]
    for run in run_dirs:
        if not run.is_dir():
            print(f"breakdown-summary: {run}: not a directory", file=sys.stderr)
            return 2
    rows = {}
    for name in variant_order(run_dirs):
        reps = [figures(run / f"{name}.json") for run in run_dirs if (run / f"{name}.json").exists()]
        if reps:
            rows[name] = (len(reps), {k: statistics.median(r[k] for r in reps) for k in reps[0]})
    if not rows:
        print("breakdown-summary: no stats JSON found", file=sys.stderr)
        return 1
    columns = list(next(iter(rows.values()))[1])
    print("| variant | runs | " + " | ".join(columns) + " |")
    print("| --- | ---: | " + " | ".join("---:" for _ in columns) + " |")
    for name, (runs, med) in rows.items():
        cells = [f"{med[c]:.0f}" if c in ("levels", "key bits") else f"{med[c]:.1f}" for c in columns]
        print(f"| {name} | {runs} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
