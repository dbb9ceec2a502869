"""What scripts/reference-check.py and scripts/convergence.py share: the stored Mitsuba references
(test/reference/*.json) and how to render the matching image with Cohort's CLI."""
import json
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCES = os.path.join(ROOT, "test", "reference")


def references():
    """(name, metadata, exr path, cohort scene path) of every stored reference."""
    out = []
    for f in sorted(os.listdir(REFERENCES)):
        if not f.endswith(".json"):
            continue
        with open(os.path.join(REFERENCES, f)) as fh:
            meta = json.load(fh)
        name = f[: -len(".json")]
        # the Cornell box reference renders Mitsuba's cbox; Cohort renders the shipped conversion
        scene = "scenes/cornell-box.gltf" if name == "cornell-box-mitsuba-rgb" else meta["scene"]
        out.append((name, meta, os.path.join(REFERENCES, name + ".exr"), os.path.join(ROOT, scene)))
    return out


def render_cohort(cohort, scene, meta, spp, seed, out_exr):
    """Renders `scene` as the reference was rendered (resolution, depth, environment) to out_exr."""
    w, h = meta["resolution"]
    cmd = [cohort, "render", scene, "--res", f"{w}x{h}", "--spp", str(spp), "--max-depth", str(meta["max_depth"]),
           "--seed", str(seed), "-o", out_exr]
    if "environment" in meta:
        cmd += ["--env", ",".join(str(v) for v in meta["environment"])]
    if "environment_map" in meta:
        cmd += ["--env", os.path.join(ROOT, meta["environment_map"])]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
