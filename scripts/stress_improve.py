#!/usr/bin/env python3
"""Stress test of the whole pipeline (not part of the test suite): random sphere
and seed scenes at coarse grids, meshed with `voronoimesh mesh`, then checked by
`voronoimesh stats` (topology and self-intersections). Prints each failing scene
and a summary; exits 1 if any failed.

  scripts/stress_improve.py [--scenes 40] [--seed 5] [--iterations 20] [--keep DIR] [--guard on|off] [--close]
"""
import argparse
import json
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VM = os.path.join(ROOT, "build", "tools", "voronoimesh", "voronoimesh")


def random_scene(rng, spheres):
    phases = [{"kind": "constant", "value": 0}]
    for _ in range(rng.randint(2, 8)):
        if spheres:
            phases.append({"kind": "sphere", "center": [0.2 + 0.6 * rng.random() for _ in range(3)],
                           "radius": 0.1 + 0.25 * rng.random()})
        else:
            phases.append({"kind": "seeds", "points": [[rng.random() for _ in range(3)]]})
    return {"grid": rng.choice([16, 20, 24, 32]), "phases": phases}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", type=int, default=40)
    ap.add_argument("--seed", type=int, default=5)
    ap.add_argument("--iterations", type=int, default=20)
    ap.add_argument("--keep", help="write the scenes and meshes here instead of a temporary folder")
    ap.add_argument("--guard", choices=["on", "off"], default="on", help="the crossing guard (improve/guard.hpp)")
    ap.add_argument("--close", action="store_true", help="close the domain (--close): box faces become surfaces")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    work = args.keep or tempfile.mkdtemp(prefix="vm-stress-")
    os.makedirs(work, exist_ok=True)
    failed = 0
    for i in range(args.scenes):
        scene = os.path.join(work, f"s{i}.json")
        mesh = os.path.join(work, f"s{i}.ply")
        with open(scene, "w") as f:
            json.dump(random_scene(rng, spheres=i % 2 == 0), f)
        command = [VM, "mesh", "-q", scene, "--iterations", str(args.iterations), "-o", mesh]
        if args.guard == "off":
            command.append("--no-crossing-guard")
        if args.close:
            command.append("--close")
        run = subprocess.run(command, capture_output=True, text=True)
        if run.returncode == 0:
            run = subprocess.run([VM, "stats", "--json", mesh], capture_output=True, text=True)
        if run.returncode != 0:
            failed += 1
            detail = run.stderr.strip() or "self_intersections: " + str(json.loads(run.stdout).get("self_intersections"))
            print(f"{scene}: {detail}")
    print(f"{failed} of {args.scenes} scenes failed (files in {work})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
