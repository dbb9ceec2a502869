#!/usr/bin/env python3
"""scripts/bench-suite's peer comparison and the suite cpu-peers: object values of "for" and their
fields, groups that run each model's programs one after the other within a round, a peer step's
inputs prepared once, --only and --set, the figures of `cohort render --stats` and of
scripts/lib/bench-mitsuba.py, and --summary's ratios taken within each round (never across rounds);
then a whole run with a stand-in cohort and a stand-in venv Python for Mitsuba. Standard library
only."""
import importlib.machinery
import importlib.util
import json
import os
import stat
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "bench-suite"
loader = importlib.machinery.SourceFileLoader("bench_suite", str(SCRIPT))
spec = importlib.util.spec_from_loader("bench_suite", loader)
bs = importlib.util.module_from_spec(spec)
loader.exec_module(bs)

# A stand-in cohort: render writes --stats with samples/s = 1 + round/10 (the round is the -N of
# the stats file's name), export writes the mesh, bench writes a camera for the view asked for.
FAKE_COHORT = """#!/usr/bin/env python3
import json, sys
a = sys.argv[1:]
def opt(name): return a[a.index(name) + 1]
if a[0] == "render":
    r = int(opt("--stats").rsplit("-", 1)[1].split(".")[0])
    sps = (1.0 + r / 10) * 1e6
    json.dump({"rays_per_second": 2 * sps, "samples_per_second": sps, "argv": a,
               "timings": {"render_seconds": 2.0, "render_cpu_seconds": 4.0}}, open(opt("--stats"), "w"))
elif a[0] == "export":
    open(opt("-o"), "w").write("ply")
elif a[0] == "bench":
    json.dump({"scenes": [{"name": a[1], "views": [{"view": opt("--view"), "camera": {"eye": [0, 0, 1]}}]}]},
              open(opt("--json"), "w"))
"""

# A stand-in for the venv's python: `-c "import ..."` succeeds (so scripts/lib/venv.sh installs
# nothing); bench-mitsuba.py's arguments give a JSON at 2 M samples/s in every round but round 2,
# which writes nothing (a failed peer run).
FAKE_PYTHON = """#!/usr/bin/env python3
import json, sys
a = sys.argv[1:]
if a[0] == "-c":
    sys.exit(0)
def opt(name): return a[a.index(name) + 1]
assert a[0].endswith("bench-mitsuba.py"), a
assert open(opt("--ply")).read() == "ply"
json.load(open(opt("--camera-json")))
if opt("--name").endswith("-2"):
    sys.exit(1)
json.dump({"peer": "mitsuba", "mitsuba": {"variant": opt("--variant")}, "view": opt("--view"), "argv": a,
           "msamples_per_second": {"median": 2.0}, "msamples_per_cpu_second": {"median": 1.0}},
          open(opt("--json"), "w"))
"""

SUITE = {
    "about": "test", "machine": "local", "rounds": 3,
    "ratios": [{"name": "A / M", "numerator": "a-", "denominator": "m-", "figures": ["Msamples/s", "Msamples/CPU s"]}],
    "steps": [{"name": "peers-{model}", "kind": "group", "for": {"model": [
        {"name": "box", "scene": "scenes/cornell-box.gltf", "res": "8", "view": "exterior", "camera": []},
        {"name": "in", "scene": "scenes/cornell-box.gltf", "res": "4", "view": "interior",
         "camera": ["--fov", "60"]}]},
        "steps": [
            {"name": "a-{model}", "kind": "render", "scene": "{model.scene}",
             "args": ["--white-sky", "--res", "{model.res}x{model.res}", "{model.camera}"]},
            {"name": "m-{model}", "kind": "peer", "scene": "{model.scene}", "view": "{model.view}",
             "args": ["--variant", "llvm_ad_rgb", "--res", "{model.res}"]}]}]}


def executable(path, text):
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IEXEC)


class Plan(unittest.TestCase):
    def plan(self, suite=SUITE, rounds=2, only=None, overrides=None):
        return bs.plan(suite, rounds, Path("/b"), Path("/m"), Path("/out"), only, overrides)

    def test_object_values_and_their_fields(self):
        runs = [r for r in self.plan() if r["kind"] == "render"]
        self.assertEqual(runs[0]["name"], "a-box-1")
        self.assertIn("8x8", runs[0]["argv"])
        self.assertNotIn("--fov", runs[0]["argv"])  # an empty list field splices to nothing
        self.assertEqual(runs[1]["argv"][runs[1]["argv"].index("4x4") + 1:][:2], ["--fov", "60"])

    def test_a_group_alternates_the_programs_per_model_and_prepares_a_peer_once(self):
        names = [r["name"] for r in self.plan()]
        self.assertEqual(names, [
            "a-box-1", "prepare-scenes-cornell-box-gltf", "prepare-scenes-cornell-box-gltf-exterior", "m-box-1",
            "a-in-1", "prepare-scenes-cornell-box-gltf-interior", "m-in-1",
            "a-box-2", "m-box-2", "a-in-2", "m-in-2"])
        peer = next(r for r in self.plan() if r["name"] == "m-in-1")
        argv = peer["argv"]
        self.assertEqual(argv[0], "{venv-python}")
        self.assertTrue(argv[1].endswith("scripts/lib/bench-mitsuba.py"))
        self.assertEqual(argv[argv.index("--view") + 1], "interior")
        self.assertTrue(argv[argv.index("--camera-json") + 1].endswith("-interior.camera.json"))
        self.assertEqual(argv[argv.index("--json") + 1], "/out/m-in-1.json")

    def test_only_and_set(self):
        names = [r["name"] for r in self.plan(only={"a"})]
        self.assertEqual(names, ["a-box-1", "a-in-1", "a-box-2", "a-in-2"])
        names = [r["name"] for r in self.plan(only={"m-in"}, rounds=1)]
        self.assertEqual(names, ["prepare-scenes-cornell-box-gltf", "prepare-scenes-cornell-box-gltf-interior", "m-in-1"])
        self.assertEqual(len(self.plan(only={"peers"})), len(self.plan()))
        runs = self.plan(overrides={"model.res": "2"}, rounds=1)
        self.assertIn("2x2", runs[0]["argv"])
        self.assertEqual(runs[3]["argv"][runs[3]["argv"].index("--res") + 1], "2")

    def test_suite_errors_name_the_file_and_the_step(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = Path(tmp) / "bad.json"
            for suite, words in [
                ({"steps": [{"name": "g", "kind": "group"}]}, "group g has no steps"),
                ({"steps": [{"name": "p", "kind": "peer", "scene": "x", "peer": "blender"}]}, "unknown peer 'blender'"),
                ({"steps": [{"name": "r", "kind": "render", "scene": "x", "opencl": "cuda"}]}, "unknown opencl 'cuda'"),
                ({"steps": [{"name": "r", "kind": "render", "scene": "x", "for": {"m": [{"scene": "y"}]}}]}, "has no 'name'"),
                ({"steps": [], "ratios": [{"numerator": "a-"}]}, "ratio 0 has no 'denominator'"),
            ]:
                bad.write_text(json.dumps(suite))
                with self.assertRaises(SystemExit) as e:
                    bs.load_suite(str(bad))
                self.assertIn(str(bad), str(e.exception))
                self.assertIn(words, str(e.exception))

    def test_the_cpu_peers_suite(self):
        _, suite = bs.load_suite("cpu-peers")
        runs = bs.plan(suite, 2, Path("/b"), Path("/m"), Path("/out"))
        measured = [r for r in runs if r["kind"] != "prepare"]
        models = {r["name"].rsplit("-", 1)[0].replace("cohort-pocl-", "") for r in measured if r["name"].startswith("cohort-pocl-")}
        self.assertGreaterEqual(len(models), 5)
        # within a round each model's renders follow each other: PoCL, Intel's runtime, Mitsuba; in
        # the first, an untimed render on PoCL before them (PoCL compiles at a kernel's first launch)
        m = suite["steps"][0]["for"]["model"][0]["name"]
        first = [r["name"] for r in measured if r["round"] == 1][:4]
        self.assertEqual(first, [f"warm-pocl-{m}", f"cohort-pocl-{m}-1", f"cohort-intel-{m}-1", f"mitsuba-{m}-1"])
        warm = [r for r in measured if r["name"].startswith("warm-pocl-")]
        self.assertEqual(len(warm), len(models))
        self.assertTrue(all(r["round"] == 1 and r["argv"][r["argv"].index("--spp") + 1] == "1" for r in warm))
        only = bs.plan(suite, 2, Path("/b"), Path("/m"), Path("/out"), only={"cohort-pocl", "mitsuba"})
        self.assertEqual(sum(r["name"].startswith("warm-pocl-") for r in only), len(models))
        for r in measured:
            argv = r["argv"]
            if r["kind"] == "render":  # the white-sky protocol: 5 segments, no Russian roulette
                for flag in ("--white-sky", "--no-rr"):
                    self.assertIn(flag, argv)
                self.assertEqual(argv[argv.index("--max-depth") + 1], "5")
                self.assertNotIn("--method", argv)  # Cohort's default method and tree
                self.assertNotIn("--tree", argv)
                self.assertEqual(r["opencl"], "intel" if r["name"].startswith("cohort-intel") else None)
            else:
                self.assertEqual(argv[argv.index("--variant") + 1], "llvm_ad_rgb")
        sponza = [r for r in measured if "sponza" in r["name"] and r["round"] == 1]
        self.assertTrue(sponza)
        self.assertIn("--camera-bounds", sponza[0]["argv"])
        self.assertIn("128x128", sponza[0]["argv"])
        self.assertEqual(sponza[-1]["argv"][sponza[-1]["argv"].index("--view") + 1], "interior")


class Ratios(unittest.TestCase):
    def test_each_round_divides_its_own_figures(self):
        steps = {"a-x": {1: {("render", "", "Msamples/s"): 1.0}, 2: {("render", "", "Msamples/s"): 3.0},
                         10: {("render", "", "Msamples/s"): 2.0}},
                 "m-x": {1: {("mitsuba", "", "Msamples/s"): 2.0}, 2: {("mitsuba", "", "Msamples/s"): 1.0}},
                 "a-y": {1: {("render", "", "Msamples/s"): 1.0}}}  # no m-y: no row
        rows = bs.ratio_rows(steps, {"numerator": "a-", "denominator": "m-"})
        self.assertEqual(len(rows), 1)
        row = rows[0]
        self.assertEqual(row["rounds"], [1, 2, 10])  # numeric order, not 1, 10, 2
        self.assertEqual(row["ratios"], [0.5, 3.0, None])
        self.assertEqual(bs.median_of(row["ratios"]), 1.75)

    def test_figures_of_a_render_and_of_mitsuba(self):
        render = {"rays_per_second": 4e6, "samples_per_second": 2e6, "timings": {"render_seconds": 3.0,
                                                                                  "render_cpu_seconds": 6.0}}
        f = bs.figures(render)
        self.assertEqual(f[("render", "", "Msamples/s")], 2.0)
        self.assertEqual(f[("render", "", "Msamples/CPU s")], 1.0)
        peer = {"peer": "mitsuba", "mitsuba": {"variant": "llvm_ad_rgb"}, "view": "interior",
                "msamples_per_second": {"median": 0.5, "best": 0.9}, "msamples_per_cpu_second": {"median": 0.25}}
        f = bs.figures(peer)
        self.assertEqual(f[("mitsuba llvm_ad_rgb", "interior", "Msamples/s")], 0.5)
        self.assertEqual(f[("mitsuba llvm_ad_rgb", "interior", "Msamples/CPU s")], 0.25)


class WholeRun(unittest.TestCase):
    def test_a_run_with_stand_ins(self):
        with tempfile.TemporaryDirectory() as tmp:
            tmp = Path(tmp)
            (tmp / "bin").mkdir()
            (tmp / "venv" / "bin").mkdir(parents=True)
            executable(tmp / "bin" / "cohort", FAKE_COHORT)
            executable(tmp / "venv" / "bin" / "python", FAKE_PYTHON)
            (tmp / "suite.json").write_text(json.dumps(SUITE))
            out = tmp / "out"
            env = dict(os.environ, COHORT_VENV=str(tmp / "venv"), DRJIT_LIBLLVM_PATH="/stand-in/libLLVM.so")
            r = subprocess.run([sys.executable, str(SCRIPT), str(tmp / "suite.json"), str(out), "--bin",
                                str(tmp / "bin")], capture_output=True, text=True, env=env)
            # round 2's peer runs fail: the run says so and exits 1, the rest is still summarised
            self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
            self.assertIn("2 of", r.stderr)
            self.assertIn("m-box-2", r.stderr)
            record = json.loads((out / "run.json").read_text())
            order = [x["name"] for x in record["runs"] if not x["name"].startswith("prepare")]
            self.assertEqual(order, ["a-box-1", "m-box-1", "a-in-1", "m-in-1", "a-box-2", "m-box-2", "a-in-2", "m-in-2",
                                     "a-box-3", "m-box-3", "a-in-3", "m-in-3"])
            self.assertTrue(all(x["exit"] == 0 for x in record["runs"] if not x["name"].startswith("m-") or
                                not x["name"].endswith("-2")))
            peer = json.loads((out / "m-in-1.json").read_text())
            self.assertEqual(peer["argv"][peer["argv"].index("--view") + 1], "interior")
            self.assertFalse((out / "scenes").exists())  # the exported meshes are removed
            # Cohort 1.1, 1.2, 1.3 M samples/s; Mitsuba 2.0 (round 2 missing): ratios 0.55, -, 0.65
            table = bs.summary(out)
            self.assertIn("| box | Msamples/s | 1.1 1.2 1.3 | 1.2 | 2 - 2 | 2 | 0.55 - 0.65 | 0.6 | 0.55 |", table)
            # per CPU second: Cohort's samples over twice the seconds, Mitsuba 1.0
            self.assertIn("| in | Msamples/CPU s | 0.55 0.6 0.65 | 0.6 | 1 - 1 | 1 | 0.55 - 0.65 | 0.6 | 0.55 |", table)
            self.assertEqual(r.stdout.count("| box | Msamples/s |"), 1)

    def test_llvm_without_libllvm_is_refused_before_any_run(self):
        if bs.LIBLLVM.exists():
            self.skipTest(f"{bs.LIBLLVM} is installed here")
        with tempfile.TemporaryDirectory() as tmp:
            (Path(tmp) / "suite.json").write_text(json.dumps(SUITE))
            env = {k: v for k, v in os.environ.items() if k != "DRJIT_LIBLLVM_PATH"}
            r = subprocess.run([sys.executable, str(SCRIPT), str(Path(tmp) / "suite.json"), str(Path(tmp) / "out"),
                                "--bin", tmp], capture_output=True, text=True, env=env)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("libllvm19", r.stderr)
            self.assertFalse((Path(tmp) / "out").exists())


if __name__ == "__main__":
    unittest.main()
