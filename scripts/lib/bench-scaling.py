#!/usr/bin/env python3
"""Strong scaling: the same image (fixed resolution and spp) on 1, 2, ... devices of one process
and on 1, 2, ... MPI ranks, with the time of the render loop (load, build and compile excluded, as
docs/decisions.md measures rays/s), the whole wall time beside it (the serial part), path-tracing rays/s,
speedup and efficiency (speedup / workers) against one worker, and whether the image is the
one-worker image bit for bit (it must be on identical devices). Each time is the median of --reps.

Devices: without --gpu, PoCL CPU devices (POCL_DEVICES="pthread pthread ...") of
--threads-per-device threads each (default: the cores divided by the most workers asked for), so
each added device brings cores; with --gpu NAME, the devices whose name matches NAME (one per rank
under MPI: --device rank:NAME).

Usage: scripts/bench scaling [--scene cornell-box|sponza-interior|PATH] [--scene-file PATH] [--res 256] [--spp 64]
                             [--method pth] [--pass-spp N] [--reps 3] [--devices 1,2] [--ranks 1,2] [--gpu NAME]
                             [--mpirun mpirun] [--json OUT.json] [--keep DIR]"""
import argparse
import json
import os
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.environ.get("COHORT_SHARED_SCENES", os.path.join(os.path.dirname(ROOT), "shared", "scenes"))
SCENES = {
    "cornell-box": (os.path.join(ROOT, "scenes", "cornell-box.gltf"), ["--max-depth", "6"]),
    "sponza-interior": (os.path.join(SHARED, "crytek-sponza", "sponza.obj.gz"),
                        ["--white-sky", "--camera-bounds", "0.25,0.2,0.5,0.75,0.35,0.5", "--fov", "60"]),
}


def worker_env(args, devices):
    env = dict(os.environ)
    if not args.gpu:
        env["POCL_DEVICES"] = " ".join(["pthread"] * devices)
        env["POCL_MAX_PTHREAD_COUNT"] = str(args.threads_per_device)
    return env


def agreement(stats, reference):
    """How many standard errors of the image mean (batch means over passes) apart two renders are."""
    a, b = stats["image_mean"], reference["image_mean"]
    z = 0.0
    for c in range(3):
        se = (a["standard_error"][c] ** 2 + b["standard_error"][c] ** 2) ** 0.5
        diff = abs(a["rgb"][c] - b["rgb"][c])
        z = max(z, diff / se if se > 0 else (0.0 if diff == 0 else float("inf")))
    return z


def command(args, scene, extra, devices, ranks, out, stats, device_spec=""):
    cmd = [args.cohort, "render", scene, "--res", f"{args.res}x{args.res}", "--spp", str(args.spp), "--method",
           args.method, "--seed", "1", "-o", out, "--stats", stats] + extra
    if args.pass_spp:
        cmd += ["--pass-spp", str(args.pass_spp)]
    if ranks > 1:
        cmd += ["--device", f"rank:{args.gpu}" if args.gpu else "all"]
        launcher = shlex.split(args.mpirun) + ["-np", str(ranks), "--oversubscribe"]
        if os.geteuid() == 0:
            launcher.append("--allow-run-as-root")
        if not args.gpu:  # every rank gets one PoCL device of its share of the cores
            launcher += ["-x", "POCL_DEVICES=pthread", "-x", f"POCL_MAX_PTHREAD_COUNT={args.threads_per_device}"]
        return launcher + cmd
    if device_spec:
        cmd += ["--device", device_spec]
    elif args.gpu:
        cmd += ["--device", ",".join([args.gpu] * devices)]
    else:
        cmd += ["--device", "all"]
    return cmd


def run_config(args, scene, extra, devices, ranks, workdir, reference, device_spec=""):
    renders, walls, rays, image = [], [], [], None
    for rep in range(args.reps):
        out = os.path.join(workdir, f"d{devices}-r{ranks}" + ("-mixed" if device_spec else ""))
        stats = out + ".json"
        cmd = command(args, scene, extra, devices, ranks, out, stats, device_spec)
        t0 = time.monotonic()
        env = dict(os.environ) if device_spec else worker_env(args, devices if ranks == 1 else 1)
        done = subprocess.run(cmd, env=env, capture_output=True, text=True)
        walls.append(time.monotonic() - t0)
        if done.returncode != 0:
            sys.exit(f"scripts/bench scaling: {' '.join(cmd)} failed ({done.returncode}):\n{done.stdout}{done.stderr}")
        with open(stats) as f:
            s = json.load(f)
        found = len(s["devices"])
        if device_spec:
            devices = found
        elif found != devices * ranks:
            sys.exit(f"scripts/bench scaling: asked for {devices} devices x {ranks} ranks, the render used {found}")
        renders.append(s["timings"]["render_seconds"])
        rays.append(s["rays_per_second"])
        with open(out + ".exr", "rb") as f:
            image = f.read()
    if reference is None:
        same = "reference"
    elif image == reference[0]:
        same = "identical"
    elif device_spec:  # different kinds of device: agreement within the noise is what can be asked
        z = agreement(s, reference[1])
        same = f"z = {z:.2f} (within 3)" if z <= 3 else f"DIFFERS (z = {z:.2f})"
    else:
        same = "DIFFERS"
    return {"devices": devices, "ranks": ranks, "workers": devices * ranks,
            "render_seconds": statistics.median(renders), "render_best": min(renders),
            "wall_seconds": statistics.median(walls), "rays_per_second": statistics.median(rays),
            "passes": s["passes"], "image": same, "device_spec": device_spec}, (image, s)


def main():
    ap = argparse.ArgumentParser(prog="scripts/bench scaling", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="cornell-box")
    ap.add_argument("--scene-file", default="", help="the preset's scene read from this file instead")
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--method", default="pth")
    ap.add_argument("--pass-spp", type=int, default=0, help="samples per pixel in one pass (default: cohort's)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--devices", default="1,2")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--gpu", default="", help="use the GPUs whose name contains this (e.g. nvidia)")
    ap.add_argument("--threads-per-device", type=int, default=0)
    ap.add_argument("--mixed", default="", help="one more run on these devices (e.g. all: GPUs and the CPU), "
                    "checked against the one-worker image within 3 standard errors of the image mean")
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--json", default="")
    ap.add_argument("--keep", default="", help="keep images and stats in this folder")
    ap.add_argument("--cohort", default=os.path.join(ROOT, "build", "cohort"))
    args = ap.parse_args()
    if not os.path.exists(args.cohort):
        sys.exit(f"{args.cohort} not found: run scripts/test or scripts/render first")
    scene, extra = SCENES.get(args.scene, (args.scene, []))
    scene = args.scene_file or scene
    if not os.path.exists(scene):
        sys.exit(f"scripts/bench scaling: {scene} not found")
    devices = [int(d) for d in args.devices.split(",") if d]
    ranks = [int(r) for r in args.ranks.split(",") if r and int(r) > 1]
    if ranks and not shutil.which(shlex.split(args.mpirun)[0]):
        print(f"scripts/bench scaling: {args.mpirun} not found, ranks skipped (apt-get install openmpi-bin)", file=sys.stderr)
        ranks = []
    if not args.threads_per_device:
        args.threads_per_device = max(1, (os.cpu_count() or 1) // max(devices + ranks))
    configs = [(d, 1) for d in devices] + [(1, r) for r in ranks]
    if (1, 1) in configs:
        configs.remove((1, 1))
    configs.insert(0, (1, 1))

    workdir = args.keep or tempfile.mkdtemp(prefix="cohort-scaling-")
    os.makedirs(workdir, exist_ok=True)
    what = f"GPUs matching '{args.gpu}'" if args.gpu else f"PoCL CPU devices of {args.threads_per_device} threads"
    print(f"{args.scene}: {args.res}x{args.res}, {args.spp} spp, --method {args.method}, {what}, "
          f"median of {args.reps}\n")
    print("| devices | ranks | passes | render s | best | wall s | Mrays/s | speedup | efficiency | image |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows, reference, base = [], None, None
    if args.mixed:
        configs.append((0, 1))
    for d, r in configs:
        row, image = run_config(args, scene, extra, d, r, workdir, reference, args.mixed if d == 0 else "")
        d = row["devices"]
        if reference is None:
            reference, base = image, row["render_seconds"]
        row["speedup"] = base / row["render_seconds"] if row["render_seconds"] > 0 else 0
        row["efficiency"] = row["speedup"] / row["workers"]
        rows.append(row)
        label = f"{d} (--device {row['device_spec']})" if row["device_spec"] else str(d)
        print(f"| {label} | {r} | {row['passes']} | {row['render_seconds']:.3f} | {row['render_best']:.3f} | {row['wall_seconds']:.2f} | "
              f"{row['rays_per_second'] * 1e-6:.1f} | {row['speedup']:.2f} | {row['efficiency']:.0%} | "
              f"{row['image']} |", flush=True)
    if not args.keep:
        shutil.rmtree(workdir, ignore_errors=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"scene": args.scene, "res": args.res, "spp": args.spp, "method": args.method,
                       "gpu": args.gpu, "rows": rows}, f, indent=2)
    if any(row["image"].startswith("DIFFERS") for row in rows):
        sys.exit("scripts/bench scaling: an image differs from the one-worker image")


if __name__ == "__main__":
    main()
