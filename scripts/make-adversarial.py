#!/usr/bin/env python3
"""Writes the scenes built to defeat the methods (the matrix of test/render/adversarial_test.cpp) as
OBJ files, so that scripts/bench-methods can show which methods lose speed there:

  scripts/make-adversarial.py build/adversarial
  scripts/bench-methods --models build/adversarial/one-triangle.obj,...

Each scene has an emissive quad (Ke) so that it is lit without an environment."""
import os
import random
import sys

MTL = "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.5 0.5 0.5\nKe 4 4 4\n"


def write(path, quads, triangles=()):
    with open(path, "w") as f:
        f.write("mtllib adversarial.mtl\n")
        n = 0
        for material, corners in quads:
            f.write(f"usemtl {material}\n")
            for c in corners:
                f.write("v %.6f %.6f %.6f\n" % c)
            f.write(f"f {n + 1} {n + 2} {n + 3} {n + 4}\n")
            n += 4
        f.write("usemtl white\n")
        for tri in triangles:
            for c in tri:
                f.write("v %.6f %.6f %.6f\n" % c)
            f.write(f"f {n + 1} {n + 2} {n + 3}\n")
            n += 3


def box(size):
    s = size
    return [("white", [(0, 0, 0), (0, 0, s), (s, 0, s), (s, 0, 0)]),
            ("white", [(0, s, 0), (s, s, 0), (s, s, s), (0, s, s)]),
            ("white", [(0, 0, 0), (0, s, 0), (0, s, s), (0, 0, s)]),
            ("white", [(s, 0, 0), (s, 0, s), (s, s, s), (s, s, 0)]),
            ("white", [(0, 0, 0), (s, 0, 0), (s, s, 0), (0, s, 0)]),
            ("light", [(0.4 * s, 0.99 * s, 0.4 * s), (0.6 * s, 0.99 * s, 0.4 * s), (0.6 * s, 0.99 * s, 0.6 * s),
                       (0.4 * s, 0.99 * s, 0.6 * s)])]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "build/adversarial"
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "adversarial.mtl"), "w") as f:
        f.write(MTL)
    write(os.path.join(out, "one-triangle.obj"), [], [((-1, -1, 0), (1, -1, 0), (0, 1, 0))])
    write(os.path.join(out, "shallow-tree.obj"),
          [("white", [(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)]),
           ("light", [(-0.2, 1, -0.2), (0.2, 1, -0.2), (0.2, 1, 0.2), (-0.2, 1, 0.2)])])
    write(os.path.join(out, "coherent-plane.obj"),
          [("white", [(-100, 0, -100), (-100, 0, 100), (100, 0, 100), (100, 0, -100)]),
           ("light", [(-1, 1, -1), (1, 1, -1), (1, 1, 1), (-1, 1, 1)])])
    rng = random.Random(5)
    u = lambda: rng.uniform(0.49, 0.51)
    write(os.path.join(out, "million-in-one-leaf.obj"), box(1.0),
          [((u(), u(), u()), (u(), u(), u()), (u(), u(), u())) for _ in range(1000000)])
    write(os.path.join(out, "open-box.obj"), box(2.0))
    print(f"wrote the adversarial scenes to {out}")


if __name__ == "__main__":
    main()
