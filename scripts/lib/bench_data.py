"""Reading a scripts/bench output directory: shared by bench-summary.py and bench-charts.py
(standard library only)."""
import glob
import json
import os

METHODS = ["naive", "wavefront", "sc", "rg", "sc+rg", "hash", "pth"]
STAGES = ["pth walk", "hash codes", "sort", "resume traversal", "traversal", "megakernel", "shadow rays", "shading",
          "other"]


def load(pattern):
    """Every JSON file matching pattern, by file stem."""
    out = {}
    for path in sorted(glob.glob(pattern)):
        with open(path) as f:
            out[os.path.splitext(os.path.basename(path))[0]] = json.load(f)
    return out


def views(doc):
    """(scene, view) pairs of a cohort bench or Embree JSON document."""
    for scene in doc["scenes"]:
        for v in scene["views"]:
            yield scene, v
