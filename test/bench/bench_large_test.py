#!/usr/bin/env python3
"""scripts/bench-large: the tree line of `cohort info` read for every tree it can build (the BVH's
build seconds add the pass that keeps the triangles, as a render's build_seconds do), a missing
tree line an error, the CPU lists it pins to, the KD build's target as a ratio to Embree, and, given a
cohort binary (argv[1]), the figures of real builds of the shipped Cornell box (and Embree's build
of it when cohort-embree-bench was built beside it). Standard library only."""
import importlib.machinery
import importlib.util
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
loader = importlib.machinery.SourceFileLoader("bench_large", str(ROOT / "scripts" / "bench-large"))
spec = importlib.util.spec_from_loader("bench_large", loader)
bench_large = importlib.util.module_from_spec(spec)
loader.exec_module(bench_large)
COHORT = Path(sys.argv.pop(1)).resolve() if len(sys.argv) > 1 else None  # ./cohort works too

BVH_LINE = ("4-wide BVH: depth 13, 668798 nodes, 1338419 leaves, 1597397 references to 1111216 triangles, "
            "1.19 per leaf, SAH cost 12.66, built in 0.874s (triangles kept in 0.119s)")
KD_LINE = ("kd-tree (compact): depth 44, 5510199 nodes, 2755100 leaves (900000 empty), 3.07 triangles per leaf, "
           "SAH cost 92.33, built in 3.543s")


class ParseTree(unittest.TestCase):
    def test_bvh_build_includes_keeping_the_triangles(self):
        depth, nodes, sah, build_s = bench_large.parse_tree("scene: x\n" + BVH_LINE + "\n")
        self.assertEqual((depth, nodes, sah), (13, 668798, 12.66))
        self.assertAlmostEqual(build_s, 0.874 + 0.119)

    def test_kd_tree(self):
        self.assertEqual(bench_large.parse_tree(KD_LINE), (44, 5510199, 92.33, 3.543))
        # binaries before the tree kinds printed "kd-tree:" alone
        self.assertEqual(bench_large.parse_tree(KD_LINE.replace(" (compact)", "")), (44, 5510199, 92.33, 3.543))

    def test_no_tree_line_is_an_error(self):
        with self.assertRaises(SystemExit):
            bench_large.parse_tree("scene: x\ntriangles: 3\n")


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
        figures = {tree: bench_large.info_figures(COHORT, scene, tree=tree) for tree in ("", "deep", "compact", "bvh4")}
        for tree, f in figures.items():
            self.assertGreater(f["nodes"], 1, tree)
            self.assertGreater(f["sah"], 0.0, tree)
            self.assertGreaterEqual(f["build_s"], 0.0, tree)
            self.assertEqual(f["triangles"], figures[""]["triangles"], tree)
        # info's own tree is the deep KD-tree; the compact one has fewer nodes; the BVH is another tree
        self.assertEqual(figures[""]["nodes"], figures["deep"]["nodes"])
        self.assertLessEqual(figures["compact"]["nodes"], figures["deep"]["nodes"])
        self.assertNotEqual(figures["bvh4"]["nodes"], figures["deep"]["nodes"])

    def test_embree_build_of_the_cornell_box(self):
        embree = COHORT.parent / "cohort-embree-bench"
        if not embree.exists():
            self.skipTest("cohort-embree-bench was not built (no Embree 3)")
        # a build line was found (embree_seconds exits without one); the Cornell box builds in
        # well under a millisecond, which the bench prints as 0.000 s
        seconds = bench_large.embree_seconds(embree, ROOT / "scenes" / "cornell-box.gltf", "0")
        self.assertGreaterEqual(seconds, 0.0)
        self.assertLess(seconds, 60.0)


if __name__ == "__main__":
    unittest.main()
