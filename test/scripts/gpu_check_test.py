#!/usr/bin/env python3
"""scripts/remote/gpu-check with stand-in binaries (no GPU here): it passes when every test passes and
every render of every tree, method and backend wrote the same bytes, and fails when one image differs,
one test fails, a render fails or a test binary is missing. Standard library only."""
import os
import stat
import subprocess
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "remote" / "gpu-check"

# `cohort render SCENE ... -o OUT.exr`: writes the same bytes for every render, except the render whose
# tree, backend and method are named in $ODD (other bytes) or $BROKEN (no image, exit 1).
COHORT = """#!/usr/bin/env python3
import os, sys
a = sys.argv[1:]
name = "-".join(a[a.index(k) + 1] for k in ("--tree", "--backend", "--method"))
if name == os.environ.get("BROKEN"):
    sys.exit(1)
open(a[a.index("-o") + 1], "w").write("odd" if name == os.environ.get("ODD") else "image")
"""
# a test binary: passes unless its name is in $FAILING
TEST = """#!/usr/bin/env python3
import os, sys
name = os.path.basename(sys.argv[0])
ok = name not in os.environ.get("FAILING", "").split(",")
print("[  PASSED  ] 3 tests." if ok else "[  FAILED  ] 1 test.")
sys.exit(0 if ok else 1)
"""


def write(path, text):
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)


class GpuCheck(unittest.TestCase):
    def run_check(self, tools=("cohort", "test_cuda", "test_render"), **env):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            (root / "bin").mkdir()
            (root / "lib").mkdir()
            for tool in tools:
                write(root / "bin" / tool, COHORT if tool == "cohort" else TEST)
            scene = root / "scene.obj"
            scene.write_text("v 0 0 0\n")
            out = root / "out"
            r = subprocess.run([str(SCRIPT), str(scene), str(out), "--bin", str(root / "bin")], cwd=ROOT,
                               capture_output=True, text=True, timeout=60, env=dict(os.environ, **env))
            md5 = (out / "md5.txt").read_text().splitlines() if (out / "md5.txt").exists() else []
            return r, md5

    def test_one_set_of_bytes_passes(self):
        r, md5 = self.run_check()
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # naive, sc+rg and pth on two trees, naive and sc+rg on the compressed BVH, two backends
        self.assertEqual(len(md5), 16)
        self.assertIn("images: 16, 1 set(s) of bytes", r.stdout)

    def test_an_image_with_other_bytes_fails(self):
        r, _ = self.run_check(ODD="deep-opencl-pth")
        self.assertEqual(r.returncode, 1)
        self.assertIn("2 set(s) of bytes", r.stdout)

    def test_a_failed_render_fails(self):
        r, md5 = self.run_check(BROKEN="bvh8-cuda-sc+rg")
        self.assertEqual(r.returncode, 1)
        self.assertIn("render bvh8-cuda-sc+rg failed", r.stdout)
        self.assertEqual(len(md5), 15)

    def test_a_failed_or_missing_test_fails(self):
        r, _ = self.run_check(FAILING="test_render")
        self.assertEqual(r.returncode, 1)
        self.assertIn("test_render (opencl): rc 1", r.stdout)
        r, _ = self.run_check(tools=("cohort", "test_render"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("test_cuda: not in the bundle", r.stdout)

    def test_bad_arguments_are_refused_before_anything_runs(self):
        for args in (["--backends", "vulkan"], ["--res"]):
            with self.subTest(args=args), tempfile.TemporaryDirectory() as tmp:
                scene = Path(tmp) / "s.obj"
                scene.write_text("v 0 0 0\n")
                r = subprocess.run([str(SCRIPT), str(scene), str(Path(tmp) / "out"), *args], cwd=ROOT,
                                   capture_output=True, text=True, timeout=30)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertFalse((Path(tmp) / "out").exists())


if __name__ == "__main__":
    unittest.main()
