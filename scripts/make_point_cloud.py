#!/usr/bin/env python3
"""Writes the four-region labelled point cloud of the paper's sect. 5 (Fig. 10): random points in the unit cube.

Usage: make_point_cloud.py [--count N] [--seed S] [--ascii] OUTPUT   (.xyz or .ply)

Each point gets the label of the first region that holds it:
  2 green: inside a torus (centre (0.5, 0.5, 0.5), ring in the y-z plane,
           radii 0.28 and 0.1), which runs through the red ball and up into blue
  1 red:   inside a ball (centre (0.5, 0.5, 0.42), radius 0.3)
  3 blue:  above the wavy surface z = 0.72 + 0.06 sin(2 pi x) cos(2 pi y),
           which the ball's top pokes through
  4 grey:  the rest
so the interfaces meet in triple curves and four-phase points. The points come
from Python's own generator seeded with S, so the same arguments always give
the same file. .ply files are binary little-endian (x, y, z double, label int)
unless --ascii. Mesh them with `voronoimesh mesh OUTPUT --grid 32` (docs/inputs.md).
"""
import argparse
import math
import random
import struct
import sys


def label(x, y, z):
    ring = math.hypot(y - 0.5, z - 0.5) - 0.28
    if math.hypot(ring, x - 0.5) < 0.1:
        return 2
    if math.dist((x, y, z), (0.5, 0.5, 0.42)) < 0.3:
        return 1
    if z > 0.72 + 0.06 * math.sin(2 * math.pi * x) * math.cos(2 * math.pi * y):
        return 3
    return 4


def points(count, seed):
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        x, y, z = rng.random(), rng.random(), rng.random()
        out.append((x, y, z, label(x, y, z)))
    return out


def write(path, pts, ascii_ply):
    if path.lower().endswith(".ply"):
        fmt = "ascii" if ascii_ply else "binary_little_endian"
        header = (
            f"ply\nformat {fmt} 1.0\ncomment make_point_cloud.py: four regions, sect. 5 of the paper\n"
            f"element vertex {len(pts)}\nproperty double x\nproperty double y\nproperty double z\n"
            "property int label\nend_header\n"
        )
        with open(path, "wb") as f:
            f.write(header.encode())
            for x, y, z, l in pts:
                f.write(f"{x!r} {y!r} {z!r} {l}\n".encode() if ascii_ply else struct.pack("<dddi", x, y, z, l))
    else:
        with open(path, "w") as f:
            f.write("# x y z label (make_point_cloud.py)\n")
            # repr() round-trips, so .xyz and .ply of one seed hold the same points.
            f.writelines(f"{x!r} {y!r} {z!r} {l}\n" for x, y, z, l in pts)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=8000, help="number of points (default 8000)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the random generator (default 1)")
    parser.add_argument("--ascii", action="store_true", help="ascii PLY instead of binary")
    parser.add_argument("output", help="file to write: .xyz (text) or .ply")
    args = parser.parse_args()
    if args.count < 1:
        parser.error("count must be at least 1")
    pts = points(args.count, args.seed)
    write(args.output, pts, args.ascii)
    counts = {l: sum(1 for p in pts if p[3] == l) for l in (1, 2, 3, 4)}
    print(f"{args.output}: {len(pts)} points, per label {counts}", file=sys.stderr)


if __name__ == "__main__":
    main()
