#!/usr/bin/env python3
"""Writes a Voronoi polycrystal as a labelled point cloud: one seed per grain.

Usage: make_grains.py [--labels L] [--seed S] COUNT OUTPUT.xyz

COUNT seeds uniformly random in the unit cube, each labelled with its grain id
(1..COUNT), so meshing the cloud (docs/inputs.md, labelled point clouds) gives
the Voronoi diagram of the seeds with COUNT phases. With --labels L the same
seeds get random labels in 1..L instead: the same geometry with L phases, where
neighbouring seeds that share a label merge (with L = 10 about a tenth of the
faces vanish), to compare many phases against few at about the same triangle
count. Scenes with a "seeds" phase evaluate every phase at every grid node;
point clouds use a k-d tree, so thousands of grains stay cheap to sample. The
points and labels come from Python's own generator seeded with S (default 1),
so the same arguments always give the same file.
"""
import argparse
import random


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", type=int)
    parser.add_argument("output")
    parser.add_argument("--labels", type=int, default=0, help="random labels in 1..L (default: one per grain)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    if args.count < 2 or args.labels < 0 or args.labels == 1:
        parser.error("COUNT must be at least 2 and L at least 2")
    positions = random.Random(args.seed)
    labels = random.Random(args.seed + 1) # a stream of its own: the seeds do not depend on --labels
    with open(args.output, "w") as out:
        out.write(f"# {args.count} Voronoi seeds, seed {args.seed}, labels {args.labels or 'one per grain'}\n")
        for grain in range(1, args.count + 1):
            x, y, z = positions.random(), positions.random(), positions.random()
            label = 1 + int(labels.random() * args.labels) if args.labels else grain
            out.write(f"{x!r} {y!r} {z!r} {label}\n")


if __name__ == "__main__":
    main()
