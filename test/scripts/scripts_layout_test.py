#!/usr/bin/env python3
"""scripts/ holds what a user or CI runs: every entry at its top level answers --help (exit 0,
some text, nothing installed or built), `scripts/bench`'s subcommands too; the README's "Scripts"
table names every entry; and every `scripts/...` path that README.md and docs/*.md name exists
(docs/results.md aside: it quotes the command each record was taken with, history that stays as it
was run). Standard library only."""
import os
import re
import subprocess
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "scripts"
SUBCOMMANDS = ("large", "scaling", "tree-budget", "runtimes", "peer-error")


def entries():
    return sorted(p.name for p in SCRIPTS.iterdir() if not p.name.startswith(".") and p.name != "__pycache__")


def answers_help(argv):
    env = dict(os.environ, COHORT_VENV="/nonexistent/venv-must-not-be-made")
    return subprocess.run(argv, capture_output=True, text=True, timeout=60, cwd=ROOT, env=env)


class Layout(unittest.TestCase):
    def test_every_entry_answers_help(self):
        """The top level, and the programs in lib/ and remote/ (the sourced .sh files and Python modules
        aside): those that need the venv's packages read their arguments before importing them."""
        programs = [SCRIPTS / name for name in entries()]
        for folder in ("lib", "remote"):
            programs += sorted(p for p in (SCRIPTS / folder).iterdir()
                               if os.access(p, os.X_OK) and p.is_file() and not p.name.endswith(".sh"))
        for path in programs:
            name = str(path.relative_to(SCRIPTS))
            if path.is_dir():
                continue
            argv = ["bash", str(path), "--help"] if name.endswith(".sh") else [str(path), "--help"]
            with self.subTest(name):
                self.assertTrue(name.endswith(".sh") or os.access(path, os.X_OK), f"{path} is not executable")
                r = answers_help(argv)
                self.assertEqual(r.returncode, 0, f"{name} --help: {r.stdout}{r.stderr}")
                self.assertGreater(len(r.stdout.strip()), 40, f"{name} --help printed too little")

    def test_bench_subcommands_answer_help(self):
        for sub in SUBCOMMANDS:
            with self.subTest(sub):
                r = answers_help([str(SCRIPTS / "bench"), sub, "--help"])
                self.assertEqual(r.returncode, 0, f"scripts/bench {sub} --help: {r.stdout}{r.stderr}")
                self.assertIn("sage", r.stdout)  # usage: or Usage:
                self.assertFalse(Path("/nonexistent/venv-must-not-be-made").exists())

    def test_the_readme_table_names_every_entry(self):
        readme = (ROOT / "README.md").read_text()
        table = readme[readme.index("## Scripts"):]
        table = table[:table.index("\n## ")]
        for name in entries():
            with self.subTest(name):
                self.assertRegex(table, rf"`(scripts/)?{re.escape(name)}/?`", f"README's Scripts table lacks {name}")

    def test_the_top_level_stays_small(self):
        self.assertLessEqual(len(entries()), 16, entries())

    def test_every_named_script_path_exists(self):
        docs = [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md") if p.name != "results.md")
        pattern = re.compile(r"\bscripts/[A-Za-z0-9_./-]*[A-Za-z0-9_]")
        for doc in docs:
            for number, line in enumerate(doc.read_text().splitlines(), 1):
                for path in pattern.findall(line):
                    with self.subTest(f"{doc.name}:{number}"):
                        self.assertTrue((ROOT / path).exists(), f"{doc.name}:{number} names {path}, which does not exist")


if __name__ == "__main__":
    unittest.main()
