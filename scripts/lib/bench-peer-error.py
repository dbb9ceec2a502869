#!/usr/bin/env python3
"""Error against time on this machine's CPU: Cohort's default render (PoCL) beside Mitsuba 3
llvm_ad_rgb on the models and views of the cpu-peers suite (white sky, docs/bench-protocol.md).

Samples/s alone does not say which renderer reaches a clean image first: the two estimators differ.
Mitsuba's `path` integrator samples the constant sky at every vertex (next-event estimation with
MIS), one shadow ray more per bounce; Cohort samples it by the BSDF alone, which for a Lambertian
is the sky's own cosine distribution. So this measures the error as well as the time: each model is
rendered at a ladder of sample counts by both, in alternated rounds (per round and spp: Cohort, then
Mitsuba), and each image's relative RMSE is taken against one reference (a Cohort render at
--ref-factor times the top of the ladder, another seed; the means of Mitsuba's images are printed
beside it as the check that both converge to it). For an unbiased renderer the squared error falls
as 1 / time, so error^2 x seconds is its cost of an image at a given error; the ratio of Mitsuba's
to Cohort's, per ladder point, is how many times sooner Cohort gets there (above 1: Cohort first).

Times: Cohort's render_seconds (`cohort render --stats`: load, build and compile excluded),
Mitsuba's mi.render wall time after an untimed render at the same spp (its JIT). Images: the
ladder's first round. Writes OUT/MODEL/*.exr and *.json with OUT/MODEL/result.json (the model's
figures), OUT/peer-error.json (all of them),
OUT/summary.md (medians) and the chart OUT/peer-error-vs-time.png (--chart elsewhere).

Run through `scripts/bench peer-error OUT [--rounds 3] [--models a,b] [--ladder 0.125,0.5,2]
[--ref-factor 16] [--chart PATH]`, which provides the venv (numpy, matplotlib, mitsuba) and
DRJIT_LIBLLVM_PATH. The ladder's factors multiply each model's spp in the cpu-peers suite."""
import argparse
import importlib.machinery
import importlib.util
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--models", default="", help="comma list of the cpu-peers models (default: all)")
    ap.add_argument("--ladder", default="0.125,0.5,2", help="factors of each model's cpu-peers spp")
    ap.add_argument("--ref-factor", type=int, default=16, help="the reference's spp over the ladder's top")
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    ap.add_argument("--scenes", default=os.environ.get("COHORT_SHARED_SCENES",
                                                       os.path.join(ROOT, "..", "shared", "scenes")))
    ap.add_argument("--chart", default="", help="where the chart goes (default OUT/peer-error-vs-time.png)")
    ap.add_argument("--replot", action="store_true", help="only redraw the chart and summary from OUT/peer-error.json")
    return ap.parse_args()


# --help answers before the imports below, which need the venv's packages
ARGS = arguments() if __name__ == "__main__" else None

import drjit as dr  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import mitsuba as mi  # noqa: E402
import numpy as np  # noqa: E402
from image_error import read_exr, rel_rmse  # noqa: E402


def suite_models():
    """The cpu-peers suite's models: name, scene, res, spp, view and Cohort's camera arguments."""
    with open(os.path.join(ROOT, "scripts", "suites", "cpu-peers.json")) as f:
        suite = json.load(f)
    return suite["steps"][0]["for"]["model"]


def run(argv, log):
    with open(log, "a") as f:
        f.write("== " + " ".join(argv) + "\n")
        f.flush()
        done = subprocess.run(argv, stdout=f, stderr=subprocess.STDOUT, timeout=1800)
    if done.returncode != 0:
        raise SystemExit(f"bench-peer-error: {' '.join(argv)} failed ({done.returncode}); see {log}")


def mitsuba_harness():
    """scripts/lib/bench-mitsuba.py as a module: its white-sky scene and its timed render."""
    loader = importlib.machinery.SourceFileLoader("bench_mitsuba", os.path.join(ROOT, "scripts", "lib", "bench-mitsuba.py"))
    spec = importlib.util.spec_from_loader("bench_mitsuba", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


MITSUBA = mitsuba_harness()


def mitsuba_render(scene, spp, seed):
    image, seconds, _ = MITSUBA.timed_render(scene, spp, seed)
    return np.array(image, dtype=np.float64)[..., :3], seconds


def measure_model(model, args, ladder_factors, log):
    name, res, view = model["name"], int(model["res"]), model["view"]
    scene = os.path.join(args.scenes, model["scene"])
    d = os.path.join(args.out, name)
    os.makedirs(d, exist_ok=True)
    ladder = sorted({max(1, round(int(model["spp"]) * f)) for f in ladder_factors})
    ref_spp = args.ref_factor * ladder[-1]
    cohort = [args.cohort, "render", scene, "--white-sky", "--res", f"{res}x{res}"] + model["camera"]

    mesh, camera_json = os.path.join(d, "mesh.ply"), os.path.join(d, "camera.json")
    run([args.cohort, "export", scene, "-o", mesh], log)
    run([args.cohort, "bench", scene, "--view", view, "--methods", "none", "--no-traversal", "--json", camera_json], log)
    with open(camera_json) as f:
        camera = next(v["camera"] for s in json.load(f)["scenes"] for v in s["views"] if v["view"] == view)
    print(f"{name}: reference, Cohort at {ref_spp} spp", flush=True)
    run(cohort + ["--spp", str(ref_spp), "--seed", "7", "-o", os.path.join(d, "reference")], log)
    reference = read_exr(os.path.join(d, "reference.exr"))

    mscene = mi.load_dict(MITSUBA.white_sky_scene(mesh, camera, res, ladder[0]))
    for spp in ladder:  # Dr.Jit's compile, untimed
        mitsuba_render(mscene, spp, 999)
    points = {"cohort": {s: [] for s in ladder}, "mitsuba": {s: [] for s in ladder}}
    means = []
    for r in range(1, args.rounds + 1):
        for spp in ladder:
            stem = os.path.join(d, f"cohort-{spp}-{r}")
            run(cohort + ["--spp", str(spp), "--seed", str(100 + r), "-o", stem, "--stats", stem + ".json"], log)
            with open(stem + ".json") as f:
                seconds = json.load(f)["timings"]["render_seconds"]
            points["cohort"][spp].append({"seconds": seconds, "rel_rmse": rel_rmse(read_exr(stem + ".exr"), reference)})
            image, seconds = mitsuba_render(mscene, spp, 200 + r)
            points["mitsuba"][spp].append({"seconds": seconds, "rel_rmse": rel_rmse(image, reference)})
            means.append(float(np.mean(image)))
            if r > 1:  # the first round's images stay
                os.remove(stem + ".exr")
            if os.path.exists(stem + ".png"):
                os.remove(stem + ".png")
        print(f"{name}: round {r} of {args.rounds}", flush=True)
    os.remove(mesh)

    def median(who, spp, key):
        return statistics.median(p[key] for p in points[who][spp])

    ladder_rows = []
    for spp in ladder:
        row = {"spp": spp}
        for who in ("cohort", "mitsuba"):
            row[who] = {"seconds": median(who, spp, "seconds"), "rel_rmse": median(who, spp, "rel_rmse")}
            row[who]["cost"] = row[who]["rel_rmse"] ** 2 * row[who]["seconds"]
        row["samples_per_second_ratio"] = row["mitsuba"]["seconds"] / row["cohort"]["seconds"]
        row["equal_error_ratio"] = row["mitsuba"]["cost"] / row["cohort"]["cost"]
        ladder_rows.append(row)
    reference_mean = float(np.mean(reference))
    return {"model": name, "view": view, "res": res, "ladder": ladder, "reference_spp": ref_spp,
            "reference_mean": reference_mean, "mitsuba_mean_ratio": statistics.median(means) / reference_mean,
            "points": points, "rows": ladder_rows,
            "samples_per_second_ratio": statistics.median(r["samples_per_second_ratio"] for r in ladder_rows),
            "equal_error_ratio": statistics.median(r["equal_error_ratio"] for r in ladder_rows)}


def chart(results, path):
    cols = min(3, len(results))
    rows = (len(results) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.4 * cols, 3.9 * rows), squeeze=False)
    for ax in axes.flat[len(results):]:
        ax.set_visible(False)
    for ax, res in zip(axes.flat, results):
        for who, style, label in (("cohort", "o-", "Cohort (PoCL, default)"), ("mitsuba", "s--", "Mitsuba 3 llvm_ad_rgb")):
            xs = [r[who]["seconds"] for r in res["rows"]]
            ys = [r[who]["rel_rmse"] for r in res["rows"]]
            ax.plot(xs, ys, style, label=label, ms=4, lw=1)
            for r in res["rows"]:
                ax.annotate(str(r["spp"]), (r[who]["seconds"], r[who]["rel_rmse"]), fontsize=6,
                            textcoords="offset points", xytext=(3, 3))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("render seconds (medians of the rounds)")
        ax.set_ylabel("relative RMSE to the reference")
        ax.set_title(f"{res['model']} ({res['view']}, {res['res']}x{res['res']})\ntime to an equal error, "
                     f"Mitsuba / Cohort: {res['equal_error_ratio']:.2f}x", fontsize=8)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def summary(results, rounds):
    lines = [f"Error against time, Cohort on PoCL beside Mitsuba 3 llvm_ad_rgb ({rounds} alternated rounds; "
             "medians). Time ratio: Mitsuba's render seconds over Cohort's at the same spp (samples/s, Cohort "
             "over Mitsuba); equal-error ratio: Mitsuba's error^2 x seconds over Cohort's (above 1: Cohort "
             "reaches a given error sooner). Mean check: Mitsuba's image mean over the reference's.", "",
             "| model | ladder (spp) | samples/s ratio | equal-error ratio, per spp | equal-error ratio | "
             "Mitsuba mean / reference |", "|---|---|---:|---|---:|---:|"]
    for res in results:
        per = " ".join(f"{r['equal_error_ratio']:.2f}" for r in res["rows"])
        lines.append(f"| {res['model']} ({res['view']}) | {', '.join(map(str, res['ladder']))} | "
                     f"{res['samples_per_second_ratio']:.2f}x | {per} | {res['equal_error_ratio']:.2f}x | "
                     f"{res['mitsuba_mean_ratio']:.4f} |")
    return "\n".join(lines) + "\n"


def main():
    args = ARGS
    mi.set_variant("llvm_ad_rgb")
    if args.replot:
        if not os.path.exists(os.path.join(args.out, "peer-error.json")):
            raise SystemExit(f"bench-peer-error: --replot: {args.out} holds no peer-error.json")
        with open(os.path.join(args.out, "peer-error.json")) as f:
            doc = json.load(f)
        chart(doc["models"], args.chart or os.path.join(args.out, "peer-error-vs-time.png"))
        sys.stdout.write(summary(doc["models"], doc["rounds"]))
        return
    if not os.access(args.cohort, os.X_OK):
        raise SystemExit(f"bench-peer-error: {args.cohort} is not an executable Cohort (build it, or pass --cohort)")
    os.makedirs(args.out, exist_ok=True)
    models = suite_models()
    if args.models:
        wanted = args.models.split(",")
        unknown = sorted(set(wanted) - {m["name"] for m in models})
        if unknown:
            raise SystemExit(f"bench-peer-error: no such cpu-peers model: {', '.join(unknown)}")
        models = [m for m in models if m["name"] in wanted]
    factors = [float(x) for x in args.ladder.split(",") if x]
    if not factors or min(factors) <= 0:
        raise SystemExit(f"bench-peer-error: --ladder {args.ladder}: expected positive factors")
    log = os.path.join(args.out, "log.txt")
    results = []
    for m in models:
        results.append(measure_model(m, args, factors, log))
        with open(os.path.join(args.out, m["name"], "result.json"), "w") as f:
            json.dump(results[-1], f, indent=1)
    with open(os.path.join(args.out, "peer-error.json"), "w") as f:
        json.dump({"rounds": args.rounds, "cohort": args.cohort, "mitsuba": mi.__version__,
                   "threads": dr.thread_count(), "models": results}, f, indent=1)
    chart(results, args.chart or os.path.join(args.out, "peer-error-vs-time.png"))
    text = summary(results, args.rounds)
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
