#!/usr/bin/env python3
"""scripts/bench-suite: every suite file expands to commands; the GPU portability suite names its
outputs as the H200 record of 2026-12-05 has them; a run with a stand-in `cohort` alternates the
binaries in rounds (or at every step), records every command, and its summary takes medians of the
JSON figures."""
import importlib.machinery
import importlib.util
import json
import os
import shutil
import stat
import subprocess
import sys
import tarfile
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "bench-suite"


def load():
    loader = importlib.machinery.SourceFileLoader("bench_suite", str(SCRIPT))
    spec = importlib.util.spec_from_loader("bench_suite", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


bs = load()

# A stand-in for `cohort bench --json`: primary rays at 100 x the round given in the environment,
# plus 1 for the baseline binary, so the medians over rounds are known.
FAKE = """#!/usr/bin/env python3
import json, os, sys
args = sys.argv[1:]
out = args[args.index("--json") + 1]
base = 1 if os.path.basename(sys.argv[0]).endswith("-base") else 0
n = len([f for f in os.listdir(os.path.dirname(out)) if f.endswith(".json")])
doc = {"cohort": {"git_commit": "abc"}, "device": {"name": "stand-in"}, "scenes": [{"name": "s.obj", "views": [
    {"view": "interior", "primary": {"mrays_per_second": {"median": 100.0 * (n + 1) + base}},
     "path_tracing": {"naive": {"mrays_per_second": {"median": 7.0}}}}]}]}
open(out, "w").write(json.dumps(doc))
"""


class BenchSuite(unittest.TestCase):
    def test_every_suite_expands(self):
        for path in sorted((ROOT / "scripts" / "suites").glob("*.json")):
            _, suite = bs.load_suite(str(path))
            runs = bs.plan(suite, 2, Path("/bin-dir"), Path("/models"), Path("/out"))
            self.assertTrue(runs, path.name)
            names = [r["name"] for r in runs]
            self.assertEqual(len(names), len(set(names)), f"{path.name}: two runs write one file")
            self.assertTrue(suite.get("about"), path.name)

    def test_portability_suite_names_the_record_files(self):
        _, suite = bs.load_suite("gpu-portability")
        runs = bs.plan(suite, 5, Path("/b"), Path("/m"), Path("/out"))
        planned = sorted(Path(r["output"]).name for r in runs)
        record = ROOT / "results" / "raw" / "nvidia-h200-2026-12-05-1c5f785"
        kept = sorted(p.name for p in record.iterdir() if p.name != "README.md")
        self.assertEqual(planned, kept)

    def run_with_stand_ins(self, tmp, program, suite):
        """`suite` run by bench-suite in tmp/out with `program` standing in for cohort and cohort-base."""
        bindir = tmp / "bin"
        bindir.mkdir()
        for name in ("cohort", "cohort-base"):
            exe = bindir / name
            exe.write_text(program)
            exe.chmod(exe.stat().st_mode | stat.S_IEXEC)
        (tmp / "suite.json").write_text(json.dumps(suite))
        out = tmp / "out"
        r = subprocess.run([sys.executable, str(SCRIPT), str(tmp / "suite.json"), str(out), "--bin", str(bindir)],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        return out

    def test_a_run_alternates_binaries_and_summarises_json(self):
        with tempfile.TemporaryDirectory() as tmp:
            suite = {"about": "test", "machine": "local", "rounds": 3, "binaries": ["cohort", "cohort-base"],
                     "steps": [{"name": "trav-{binary}", "kind": "bench", "scene": "scenes/cornell-box.gltf",
                                "args": ["--view", "interior"]}]}
            out = self.run_with_stand_ins(Path(tmp), FAKE, suite)
            record = json.loads((out / "run.json").read_text())
            order = [(x["round"], x["binary"]) for x in record["runs"]]
            self.assertEqual(order, [(1, "cohort"), (1, "cohort-base"), (2, "cohort"), (2, "cohort-base"),
                                     (3, "cohort"), (3, "cohort-base")])
            # files written in order: cohort gets n = 0, 2, 4 -> 100, 300, 500; the baseline 201, 401, 601
            table = bs.summary(out)
            self.assertIn("| trav-cohort | s.obj | interior | primary | 300 | 100 | 500 | 3 |", table)
            self.assertIn("| trav-cohort-base | s.obj | interior | primary | 401 | 201 | 601 | 3 |", table)
            self.assertIn("| trav-cohort | s.obj | interior | naive | 7 | 7 | 7 | 3 |", table)

    def test_a_run_says_which_renders_gave_the_baselines_image_bytes(self):
        # a stand-in render: the same image for both binaries, but for model "b", whose baseline differs
        render = """#!/usr/bin/env python3
import json, os, sys
a = sys.argv[1:]
def opt(name): return a[a.index(name) + 1]
json.dump({"samples_per_second": 1e6}, open(opt("--stats"), "w"))
base = os.path.basename(sys.argv[0]).endswith("-base")
open(opt("-o") + ".exr", "wb").write(b"exr" + (b"!" if base and "-b-" in opt("-o") else b""))
"""
        with tempfile.TemporaryDirectory() as tmp:
            suite = {"about": "test", "machine": "local", "rounds": 2, "binaries": ["cohort", "cohort-base"],
                     "alternate": "step",
                     "steps": [{"name": "r-{binary}-{model}", "kind": "render", "scene": "scenes/cornell-box.gltf",
                                "for": {"model": ["a", "b"]}}]}
            out = self.run_with_stand_ins(Path(tmp), render, suite)
            images = json.loads((out / "run.json").read_text())["images"]
            self.assertEqual(sorted((x["run"], x["twin"], x["same"]) for x in images),
                             [("r-cohort-a-1", "r-cohort-base-a-1", True), ("r-cohort-a-2", "r-cohort-base-a-2", True),
                              ("r-cohort-b-1", "r-cohort-base-b-1", False), ("r-cohort-b-2", "r-cohort-base-b-2", False)])
            self.assertIn("Images: 2 of 4 renders the same bytes as their twin of the other binary; differing: "
                          "r-cohort-b-1, r-cohort-b-2.", bs.summary(out))

    def test_alternate_step_gives_each_step_to_every_binary_in_turn(self):
        steps = [{"name": f"{s}-{{binary}}-{{model}}", "kind": "bench", "scene": "x.obj", "for": {"model": ["a", "b"]}}
                 for s in ("naive", "rays")]
        suite = {"about": "test", "binaries": ["cohort", "cohort-base"], "steps": steps}
        by_round = [r["name"] for r in bs.plan(suite, 1, Path("/b"), Path("/m"), Path("/out"))]
        self.assertEqual(by_round, ["naive-cohort-a-1", "naive-cohort-b-1", "rays-cohort-a-1", "rays-cohort-b-1",
                                    "naive-cohort-base-a-1", "naive-cohort-base-b-1", "rays-cohort-base-a-1",
                                    "rays-cohort-base-b-1"])
        suite["alternate"] = "step"
        by_step = [r["name"] for r in bs.plan(suite, 1, Path("/b"), Path("/m"), Path("/out"))]
        self.assertEqual(by_step, ["naive-cohort-a-1", "naive-cohort-base-a-1", "naive-cohort-b-1",
                                   "naive-cohort-base-b-1", "rays-cohort-a-1", "rays-cohort-base-a-1",
                                   "rays-cohort-b-1", "rays-cohort-base-b-1"])
        with tempfile.TemporaryDirectory() as tmp:
            bad = Path(tmp) / "bad.json"
            bad.write_text(json.dumps(dict(suite, alternate="model")))
            with self.assertRaises(SystemExit):
                bs.load_suite(str(bad))

    def test_a_gpu_machine_unpacks_the_archived_bundle_where_the_folder_is_missing(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            src = root / "src" / "gpu-bundle" / "bin"
            src.mkdir(parents=True)
            (src / "cohort").write_text("stand-in")
            with tarfile.open(root / "gpu-bundle.tar.xz", "w:xz") as tar:
                tar.add(root / "src" / "gpu-bundle", arcname="gpu-bundle")
            self.assertEqual(bs.unpack_bundle(root), root / "gpu-bundle")
            self.assertEqual((root / "gpu-bundle" / "bin" / "cohort").read_text(), "stand-in")
            # a folder already there is used as it is
            (root / "gpu-bundle" / "bin" / "cohort").write_text("newer")
            bs.unpack_bundle(root)
            self.assertEqual((root / "gpu-bundle" / "bin" / "cohort").read_text(), "newer")
            # an archive with anything outside gpu-bundle/ is refused, nothing unpacked
            shutil.rmtree(root / "gpu-bundle")
            (root / "src" / "other").write_text("x")
            with tarfile.open(root / "gpu-bundle.tar.xz", "w:xz") as tar:
                tar.add(root / "src" / "gpu-bundle", arcname="gpu-bundle")
                tar.add(root / "src" / "other", arcname="other")
            with self.assertRaises(SystemExit):
                bs.unpack_bundle(root)
            self.assertFalse((root / "gpu-bundle").exists())

    def test_path_tracing_figures_include_samples_per_cpu_second(self):
        doc = {"scenes": [{"name": "s.obj", "views": [{"view": "exterior", "path_tracing": {"naive": {
            "mrays_per_second": {"median": 7.0}, "msamples_per_cpu_second": {"median": 2.5}}}}]}]}
        self.assertEqual(bs.figures(doc), {("s.obj", "exterior", "naive"): 7.0,
                                           ("s.obj", "exterior", "naive Msamples/CPU s"): 2.5})


if __name__ == "__main__":
    unittest.main()
