#!/usr/bin/env python3
"""Writes a Voronoi scene: COUNT "seeds" phases, one random point each, in the unit cube.

Usage: make_voronoi_scene.py COUNT SEED GRID OUTPUT   (OUTPUT "-" writes to stdout)

The points come from Python's own generator seeded with SEED, so the same
arguments always give the same file. Scene format: docs/scenes.md.
"""
import argparse
import random
import sys


def scene_text(count, seed, grid):
    rng = random.Random(seed)
    lines = []
    for i in range(count):
        # Six decimals keep the file short and exactly what the mesher reads.
        x, y, z = (round(rng.random(), 6) for _ in range(3))
        comma = "," if i + 1 < count else ""
        lines.append(f'    {{"name": "cell{i}", "kind": "seeds", "points": [[{x}, {y}, {z}]]}}{comma}')
    return (
        "{\n"
        f'  "description": "{count} Voronoi cells, one random seed each (make_voronoi_scene.py {count} {seed} {grid}).",\n'
        '  "domain": {"min": [0, 0, 0], "max": [1, 1, 1]},\n'
        f'  "grid": {grid},\n'
        '  "phases": [\n' + "\n".join(lines) + "\n  ]\n}\n"
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", type=int, help="number of cells (phases), at least 2")
    parser.add_argument("seed", type=int, help="seed of the random generator")
    parser.add_argument("grid", type=int, help="grid cells per axis, 1 to 4096")
    parser.add_argument("output", help="file to write, or - for stdout")
    args = parser.parse_args()
    if args.count < 2:
        parser.error("count must be at least 2")
    if not 1 <= args.grid <= 4096:
        parser.error("grid must be in [1, 4096]")
    text = scene_text(args.count, args.seed, args.grid)
    if args.output == "-":
        sys.stdout.write(text)
    else:
        with open(args.output, "w", encoding="utf-8") as f:
            f.write(text)


if __name__ == "__main__":
    main()
