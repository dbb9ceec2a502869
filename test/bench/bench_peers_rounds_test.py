#!/usr/bin/env python3
"""scripts/lib/bench-peers-rounds.py: each round's ratio divides that round's figures (the faster Cohort
runtime by llvm_ad_rgb), rounds in numeric order, missing figures left out of the median and the
least, and a directory without rounds an error. Standard library only."""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "lib", "bench-peers-rounds.py")
spec = importlib.util.spec_from_file_location("bench_peers_rounds", SCRIPT)
rounds = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rounds)


def row(scene, pocl_cpu, intel_cpu, llvm_cpu, pocl_wall, intel_wall, llvm_wall):
    def cpu(x):
        return {"method": "naive", "msamples_per_cpu_second": x} if x is not None else None

    def wall(x):
        return {"method": "naive", "msamples_per_second": x} if x is not None else None

    return {"scene": scene, "view": "exterior", "pocl": wall(pocl_wall), "intel": wall(intel_wall),
            "pocl_per_cpu_second": cpu(pocl_cpu), "intel_per_cpu_second": cpu(intel_cpu),
            "mitsuba_llvm_ad_rgb_per_cpu_second": llvm_cpu, "mitsuba_llvm_ad_rgb": llvm_wall}


def write_round(root, number, rows):
    d = os.path.join(root, f"round-{number}", "scene")
    os.makedirs(d)
    with open(os.path.join(d, "peers.json"), "w") as f:
        json.dump({"settings": None, "rows": rows}, f)


class BenchPeersRounds(unittest.TestCase):
    def round_ratios(self, r):
        rates = rounds.rates(r)
        return rounds.ratio(*rates["cpu"]), rounds.ratio(*rates["wall"])

    def test_ratio_takes_the_faster_runtime_of_its_own_round(self):
        cpu, wall = self.round_ratios(row("a", 0.2, 0.3, 0.5, 0.4, 0.1, 0.8))
        self.assertAlmostEqual(cpu, 0.6)   # intel per CPU second
        self.assertAlmostEqual(wall, 0.5)  # pocl per wall second

    def test_worst_pairing_crosses_rounds(self):
        self.assertAlmostEqual(rounds.worst_pairing([(0.3, 0.5), (0.4, 0.6), (None, 0.9)]), 0.3 / 0.9)
        self.assertIsNone(rounds.worst_pairing([(None, 0.5)]))

    def test_missing_figures_give_none(self):
        self.assertEqual(self.round_ratios(row("a", 0.2, None, None, 0.4, None, 0.8)), (None, 0.5))
        self.assertEqual(self.round_ratios(row("a", None, None, 0.5, None, None, 0.8)), (None, None))

    def test_rounds_in_numeric_order_median_and_least(self):
        with tempfile.TemporaryDirectory() as root:
            write_round(root, 10, [row("a", 0.9, None, 1.0, 0.9, None, 1.0)])
            write_round(root, 2, [row("a", 0.5, None, 1.0, 0.5, None, 1.0)])
            write_round(root, 1, [row("a", 0.7, None, 1.0, 0.6, None, 1.0)])
            write_round(root, 3, [row("a", 0.2, None, None, 0.2, None, None)])
            out = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True, check=True).stdout
            # worst pairing: Cohort's least (0.2, the round without Mitsuba counts too) over Mitsuba's most (1.0)
            self.assertIn("| a | exterior | 0.70 0.50 - 0.90 | 0.70 | 0.50 | 0.20 | 0.60 0.50 - 0.90 | 0.60 | 0.50 | 0.20 |",
                          out)
            with open(os.path.join(root, "rounds.json")) as f:
                doc = json.load(f)
            self.assertEqual(doc["rows"][0]["rounds"], ["round-1", "round-2", "round-3", "round-10"])
            self.assertIsNone(doc["rows"][0]["cpu"][2])

    def test_a_directory_without_rounds_is_an_error(self):
        with tempfile.TemporaryDirectory() as root:
            r = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("no round-", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(root, "rounds.json")))


if __name__ == "__main__":
    unittest.main()
