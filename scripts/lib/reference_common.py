"""What the reference scripts share: Mitsuba's pass loop (reference-cbox.py, reference-scenes.py),
the stored references (test/reference/*.json) and how to render the matching image with Cohort's
CLI (reference-check.py, convergence.py). Imports neither mitsuba nor numpy itself."""
import argparse
import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REFERENCES = os.path.join(ROOT, "test", "reference")


def reference_arguments(description, written):
    """The options of the Mitsuba reference generators (reference-scenes.py, reference-materials.py):
    `written` says what --scenes-only writes."""
    ap = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=60.0, help="render time per scene (default 60)")
    ap.add_argument("--pass-spp", type=int, default=64)
    ap.add_argument("--max-spp", type=int, default=1 << 16)
    ap.add_argument("--only", nargs="*", help="scene names (default: all)")
    ap.add_argument("--scenes-only", action="store_true", help=f"write {written}, render nothing")
    return ap.parse_args()


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


def render_cohort(cohort, scene, meta, spp, seed, out_exr, extra=()):
    """Renders `scene` as the reference was rendered (resolution, depth, environment) to out_exr,
    with `extra` options added; returns the command's standard output."""
    w, h = meta["resolution"]
    cmd = [cohort, "render", scene, "--res", f"{w}x{h}", "--spp", str(spp), "--max-depth", str(meta["max_depth"]),
           "--seed", str(seed), "-o", out_exr]
    if "environment" in meta:
        cmd += ["--env", ",".join(str(v) for v in meta["environment"])]
    if "environment_map" in meta:
        cmd += ["--env", os.path.join(ROOT, meta["environment_map"])]
    return subprocess.run(cmd + list(extra), check=True, stdout=subprocess.PIPE, text=True).stdout


def relative_mse(image, reference):
    """Relative MSE: per pixel and channel (x - ref)^2 / (ref^2 + 0.01), averaged (the figure of
    the denoise and adaptive tests, and what --target-error's estimate aims at)."""
    return float(((image - reference) ** 2 / (reference ** 2 + 0.01)).mean())


def accumulate_passes(render_pass, pass_spp, max_spp, seconds):
    """Calls render_pass(seed) (an image of pass_spp samples per pixel, float64) with seeds 0, 1, ...
    until max_spp or until the next pass would overrun `seconds`; each pass is an unbiased estimate,
    so their mean is too. Returns (mean RGB image, spp, passes, elapsed seconds)."""
    start, total, spp, passes = time.time(), None, 0, 0
    while spp + pass_spp <= max_spp:
        img = render_pass(passes)
        total = img if total is None else total + img
        spp += pass_spp
        passes += 1
        # stop before a pass that would overrun the budget
        if (time.time() - start) * (passes + 1) / passes > seconds:
            break
    return (total / passes)[:, :, :3], spp, passes, time.time() - start
