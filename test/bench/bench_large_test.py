#!/usr/bin/env python3
"""scripts/bench large (scripts/lib/bench-large.py): the tree figures of `cohort bench --json` read for every tree it can build
(the BVH's build seconds add the pass that keeps the triangles, as a render's build_seconds do), a
missing tree an error, the CPU lists it pins to, the KD build's target as a ratio to Embree, and, given a
cohort binary (argv[1]), the figures of real builds of the shipped Cornell box (and Embree's build
of it when cohort-embree-bench was built beside it). Standard library only."""
import importlib.machinery
import importlib.util
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
loader = importlib.machinery.SourceFileLoader("bench_large", str(ROOT / "scripts" / "lib" / "bench-large.py"))
spec = importlib.util.spec_from_loader("bench_large", loader)
bench_large = importlib.util.module_from_spec(spec)
loader.exec_module(bench_large)
COHORT = Path(sys.argv.pop(1)).resolve() if len(sys.argv) > 1 else None  # ./cohort works too

def bench_doc(kind, with_bvh=True):
    """A `cohort bench --json` file's scene as the build table reads it."""
    kd = {"kind": kind, "depth": 44, "nodes": 5510199, "sah_cost": 92.33, "build_seconds": 3.543,
          "bytes": 100000, "dropped_triangles": 2}
    if with_bvh:
        kd["bvh4"] = {"depth": 13, "nodes": 668798, "sah_cost": 12.66, "build_seconds": 0.874, "bytes": 50000}
    return {"scenes": [{"name": "x", "triangles": 1002, "kdtree": kd, "views": []}]}


class TreeFigures(unittest.TestCase):
    def test_bvh_build_includes_keeping_the_triangles(self):
        kept, depth, nodes, sah, build_s, tree_bytes = bench_large.tree_figures_of(bench_doc("bvh4"), "bvh4")
        self.assertEqual((kept, depth, nodes, sah, tree_bytes), (1000, 13, 668798, 12.66, 50000))
        self.assertAlmostEqual(build_s, 0.874 + 3.543)

    def test_kd_tree(self):
        self.assertEqual(bench_large.tree_figures_of(bench_doc("compact", with_bvh=False), "compact"),
                         (1000, 44, 5510199, 92.33, 3.543, 100000))
        self.assertEqual(bench_large.tree_figures_of(bench_doc("deep", with_bvh=False)),
                         (1000, 44, 5510199, 92.33, 3.543, 100000))

    def test_no_tree_is_an_error(self):
        with self.assertRaises(SystemExit):
            bench_large.tree_figures_of({"scenes": [{"name": "x", "triangles": 3, "views": []}]})


class EmbreeTarget(unittest.TestCase):
    def test_cpu_lists(self):
        self.assertEqual(bench_large.cpu_count("0,1"), 2)
        self.assertEqual(bench_large.cpu_count("0-15"), 16)
        self.assertEqual(bench_large.cpu_count("0-3,8"), 5)
        self.assertEqual(bench_large.cpu_count(""), bench_large.os.cpu_count())

    def test_rows_pair_each_build_with_its_round(self):
        # rounds (build, Embree): 1.3/1.0, 1.6/1.0, 1.2/1.0 -> ratios 1.2, 1.3, 1.6, median 1.3: met
        rows = bench_large.embree_rows("m", [1.3, 1.6, 1.2], [1.0, 1.0, 1.0])
        self.assertIn("1.30x (1.20-1.60)", rows[1])
        self.assertIn(": met", rows[1])
        # pairing by round, not by sorted value: 2.0/1.0 and 1.0/2.0 are 2.0 and 0.5, median 1.25
        rows = bench_large.embree_rows("m", [2.0, 1.0], [1.0, 2.0])
        self.assertIn("1.25x (0.50-2.00)", rows[1])
        rows = bench_large.embree_rows("m", [1.5, 1.5, 1.5], [1.0, 1.0, 1.0])
        self.assertIn("not met", rows[1])

    def test_an_untimed_embree_build_gives_no_ratio(self):
        rows = bench_large.embree_rows("m", [0.001, 0.001], [0.001, 0.0])
        self.assertEqual(len(rows), 1)
        self.assertIn("too small to time", rows[0])

    def test_target_ratio(self):
        # 1 s for 1M triangles where Embree-high takes 0.70 s for 977K: 1.40x Embree's time
        self.assertAlmostEqual(bench_large.EMBREE_TARGET_RATIO, 977 / 700, places=6)
        self.assertAlmostEqual(1e6 * 0.70 / 977e3 * bench_large.EMBREE_TARGET_RATIO, 1.0)


@unittest.skipUnless(COHORT, "no cohort binary given")
class RealBuilds(unittest.TestCase):
    def test_every_tree_of_the_cornell_box(self):
        scene = ROOT / "scenes" / "cornell-box.gltf"
        figures = {tree: bench_large.tree_figures(COHORT, scene, tree=tree) for tree in ("", "deep", "compact", "bvh4")}
        for tree, f in figures.items():
            self.assertGreater(f["nodes"], 1, tree)
            self.assertGreater(f["sah"], 0.0, tree)
            self.assertGreaterEqual(f["build_s"], 0.0, tree)
            self.assertEqual(f["triangles"], figures[""]["triangles"], tree)
        # the default is the deep KD-tree; the compact one has fewer nodes; the BVH is another tree
        self.assertEqual(figures[""]["nodes"], figures["deep"]["nodes"])
        self.assertLessEqual(figures["compact"]["nodes"], figures["deep"]["nodes"])
        self.assertNotEqual(figures["bvh4"]["nodes"], figures["deep"]["nodes"])

    def test_embree_build_of_the_cornell_box(self):
        embree = COHORT.parent / "cohort-embree-bench"
        if not embree.exists():
            self.skipTest("cohort-embree-bench was not built (no Embree 3)")
        # a build was found in the JSON (embree_seconds exits without one); the Cornell box builds in
        # well under a millisecond
        seconds = bench_large.embree_seconds(embree, ROOT / "scenes" / "cornell-box.gltf", "0")
        self.assertGreaterEqual(seconds, 0.0)
        self.assertLess(seconds, 60.0)


if __name__ == "__main__":
    unittest.main()
