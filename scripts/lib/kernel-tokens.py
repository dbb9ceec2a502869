#!/usr/bin/env python3
"""Do the rendering programs of a scene without a feature compile the same code as before it? (docs/bsdf.md,
"Kernels specialised to the scene"). Expands each program (naive, wavefront, pth, aov, trace, film) as
runtime/backend/embedded_sources.cpp does (each file once, at its first #include), preprocesses it with
`cpp` under sets of feature options and compares the token streams of this working tree's kernels/ with
those of git revision REV. Exit 1 when a program differs.

Usage: scripts/lib/kernel-tokens.py REV [--options="-DCOHORT_FEATURE_X ..."]...   (default: five sets)"""
import argparse
import difflib
import os
import re
import subprocess
import sys
import tarfile
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROGRAMS = ["naive.cl", "wavefront.cl", "pth.cl", "aov.cl", "trace.cl", "film.cl"]
FEATURE_SETS = [
    "",
    "-DCOHORT_FEATURE_TEXTURES -DCOHORT_FEATURE_ALPHA -DCOHORT_FEATURE_TEXTURE_TRANSFORM",
    "-DCOHORT_FEATURE_VOLUME -DCOHORT_FEATURE_DIELECTRIC -DCOHORT_ACCEL_BVH4",
    "-DCOHORT_FEATURE_NORMAL_MAP -DCOHORT_FEATURE_TEXTURES -DCOHORT_FEATURE_TEXCOORD1 -DCOHORT_FEATURE_VERTEX_COLORS "
    "-DCOHORT_FEATURE_PLASTIC -DCOHORT_FEATURE_CONDUCTOR -DCOHORT_FEATURE_ENVMAP -DCOHORT_FEATURE_PUNCTUAL",
    "-DCOHORT_FEATURE_TEXTURES -DCOHORT_FEATURE_PLASTIC -DCOHORT_FEATURE_CLEARCOAT -DCOHORT_FEATURE_SHEEN "
    "-DCOHORT_FEATURE_NORMAL_MAP -DCOHORT_FEATURE_ALPHA -DCOHORT_ACCEL_BVH4",
]
TOKEN = re.compile(r'[A-Za-z_]\w*|\d[\w.]*(?:[eEpP][+-]\d+)?|"(?:\\.|[^"\\])*"|\S')


def expand(root, path, seen, out):
    if path in seen:
        return
    seen.add(path)
    with open(os.path.join(root, path)) as f:
        for line in f:
            body = line.lstrip(" \t")
            if body.startswith('#include "'):
                expand(root, body[10:body.index('"', 10)], seen, out)
                continue
            out.append(line)


def tokens(root, program, options):
    out = []
    expand(root, program, set(), out)
    r = subprocess.run(["cpp", "-P", "-undef", "-D__OPENCL_VERSION__=120", "-D__OPENCL_C_VERSION__=120"] + options.split(),
                       input="".join(out), capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{root}/{program} {options}: {r.stderr[:2000]}")
    return TOKEN.findall(r.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rev")
    ap.add_argument("--options", action="append", help="one set of feature options (repeatable)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", ROOT, "archive", args.rev, "kernels"], capture_output=True, check=True)
        with tarfile.open(fileobj=__import__("io").BytesIO(archive.stdout)) as t:
            t.extractall(tmp)
        differ = 0
        for program in PROGRAMS:
            for options in args.options or FEATURE_SETS:
                a = tokens(os.path.join(tmp, "kernels"), program, options)
                b = tokens(os.path.join(ROOT, "kernels"), program, options)
                print(f"{program:13s} [{options or 'no feature option'}]: {len(a)} and {len(b)} tokens, "
                      f"{'the same' if a == b else 'different'}")
                if a != b:
                    differ += 1
                    for line in list(difflib.unified_diff(a, b, args.rev, "working tree", lineterm="", n=3))[:30]:
                        print("    " + line)
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
