#!/usr/bin/env python3
"""The bench's table makers on committed records: scripts/lib/bench-peers.py rebuilds the peers.json
and peers.md a 2026-12-03 run wrote (results/raw/pocl-2026-12-03-79b7d2b/peers), and
scripts/lib/bench-summary.py prints each scene's protocol-ray medians as `cohort bench --json` holds
them. Standard library only."""
import json
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RAW = ROOT / "results" / "raw"


class BenchPeers(unittest.TestCase):
    def test_rebuilds_the_records_tables(self):
        record = RAW / "pocl-2026-12-03-79b7d2b" / "peers"
        with tempfile.TemporaryDirectory() as tmp:
            copy = Path(tmp) / "peers"
            shutil.copytree(record, copy)
            (copy / "peers.json").unlink()
            r = subprocess.run([sys.executable, str(ROOT / "scripts" / "lib" / "bench-peers.py"), str(copy)],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(json.loads((copy / "peers.json").read_text()), json.loads((record / "peers.json").read_text()))
            self.assertEqual(r.stdout, (record / "peers.md").read_text())


class BenchSummary(unittest.TestCase):
    def test_protocol_rays_come_from_the_json(self):
        run = RAW / "pocl-2026-12-03-e541858" / "run-1" / "round-1" / "armadillo" / "pocl"
        r = subprocess.run([sys.executable, str(ROOT / "scripts" / "lib" / "bench-summary.py"), str(run)],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads((run / "cohort" / "armadillo.json").read_text())
        view = doc["scenes"][0]["views"][0]
        primary = view["primary"]["mrays_per_second"]
        row = next(line for line in r.stdout.splitlines() if line.startswith("| armadillo | exterior | 345944 |"))
        self.assertIn(f"{primary['median']:.2f} ({primary['best']:.2f})", row)


if __name__ == "__main__":
    unittest.main()
