#!/usr/bin/env python3
"""Checks scripts/corner_bound.py on configurations whose answer is known.

Usage: test_corner_bound.py PATH/TO/corner_bound.py   (exit status 0 when every check holds)
"""
import importlib.util
import math
import os
import subprocess
import sys
import tempfile

spec = importlib.util.spec_from_file_location("corner_bound", sys.argv[1])
bound = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bound)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


# The equilateral triangle is the best there is; an apex of 10 degrees allows about q 0.3.
check(abs(bound.best_quality_at_angle(math.radians(60)) - 1) < 1e-12, "apex 60 degrees: q 1")
check(abs(bound.best_quality_at_angle(math.radians(10)) - 0.2963) < 1e-4, "apex 10 degrees: q 0.2963")
# A corner is filled by triangles whose angles there sum to it: one below 60 degrees, three
# equilateral ones at 180, and at 75 degrees one (q 0.96) beats two of 37.5 (q 0.87).
check(abs(bound.best_quality_at_corner(math.radians(10)) - 0.2963) < 1e-4, "corner of 10 degrees: q 0.2963")
check(abs(bound.best_quality_at_corner(math.radians(180)) - 1) < 1e-12, "corner of 180 degrees: q 1")
check(abs(bound.best_quality_at_corner(math.radians(75)) - bound.best_quality_at_angle(math.radians(75))) < 1e-12,
      "corner of 75 degrees: one triangle")

# Four seeds on a regular tetrahedron round the box's centre: one vertex there, where the
# four edges leave along the directions away from the seeds, 109.47 degrees apart.
c, r = 0.5, 0.3
corners = [[c + r * x, c + r * y, c + r * z] for x, y, z in ((1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1))]
tetra = [bound.Phase({"kind": "seeds", "points": [p]}) for p in corners]
angle, quad, face, vertex = bound.tightest_corner(tetra, [0, 0, 0], [1, 1, 1])
check(quad == (0, 1, 2, 3) and max(abs(v - c) for v in vertex) < 1e-12, f"tetrahedron: vertex {vertex}")
check(abs(math.degrees(angle) - math.degrees(math.acos(-1 / 3))) < 1e-9, f"tetrahedron: corner {math.degrees(angle)}")

# The same vertex outside the domain is no corner of the meshed diagram.
angle, quad, face, vertex = bound.tightest_corner(tetra, [0.6, 0, 0], [1, 1, 1])
check(quad is None, "vertex outside the domain counted")

# A fifth seed nearer the centre than the four: theirs is no vertex of the diagram.
nearer = bound.Phase({"kind": "seeds", "points": [[c, c, c + 0.01]]})
angle, quad, face, vertex = bound.tightest_corner(tetra + [nearer], [0, 0, 0], [1, 1, 1])
check((0, 1, 2, 3) != quad, "a vertex inside another seed's cell counted")

# The same four as equal balls in an outside phase, found by Newton's method: at the centre
# the balls' gradients are the seeds' (the point is 0.52 inside each, so the outside, 0, is
# lower), and the corners are the tetrahedron's.
outside = bound.Phase({"kind": "constant", "value": 0})
balls = [outside] + [bound.Phase({"kind": "sphere", "center": p, "radius": 1.04}) for p in corners]
angle, quad, face, vertex = bound.tightest_corner(balls, [0, 0, 0], [1, 1, 1])
check(quad == (1, 2, 3, 4) and max(abs(v - c) for v in vertex) < 1e-9, f"balls: vertex {vertex} of {quad}")
check(abs(math.degrees(angle) - math.degrees(math.acos(-1 / 3))) < 1e-6, f"balls: corner {math.degrees(angle)}")

# Corners at the box (at_box): a surface that cuts the box turns where it meets a box edge, and
# the surfaces of a triple curve turn where it ends on a box face. Two seeds mirrored in the plane
# through the box's centre normal to (1, 1, 1) cut it in a regular hexagon (corners of 120
# degrees); in the plane x + y + z = 0.3 they cut off a corner, an equilateral triangle (60).
def mirrored(point, normal, d):
    n = [v / math.sqrt(3) for v in normal]
    return [bound.Phase({"kind": "seeds", "points": [[point[i] + s * d * n[i] for i in range(3)]]}) for s in (-1, 1)]


angle, ids, face, vertex = bound.tightest_corner(mirrored([0.5] * 3, [1, 1, 1], 0.1), [0, 0, 0], [1, 1, 1])
check(ids is None, "two seeds: a corner without at_box")
angle, ids, face, vertex = bound.tightest_corner(mirrored([0.5] * 3, [1, 1, 1], 0.1), [0, 0, 0], [1, 1, 1], True)
check(ids == (0, 1) and abs(math.degrees(angle) - 120) < 1e-9, f"hexagon: corner {math.degrees(angle)} of {ids}")
angle, ids, face, vertex = bound.tightest_corner(mirrored([0.1] * 3, [1, 1, 1], 0.05), [0, 0, 0], [1, 1, 1], True)
check(ids == (0, 1) and abs(math.degrees(angle) - 60) < 1e-9, f"cut-off corner: corner {math.degrees(angle)}")
# Three seeds round a vertical axis: their triple curve meets the bottom and top faces at right
# angles, and every surface meets the box's edges at right angles too.
three = [bound.Phase({"kind": "seeds", "points": [[0.5 + 0.2 * math.cos(math.radians(t)),
                                                   0.5 + 0.2 * math.sin(math.radians(t)), 0.5]]})
         for t in (90, 210, 330)]
angle, ids, face, vertex = bound.tightest_corner(three, [0, 0, 0], [1, 1, 1], True)
check(abs(math.degrees(angle) - 90) < 1e-9, f"three seeds: corner {math.degrees(angle)} of {ids} at {vertex}")
ends = [x for inward, x in bound.box_points(three, (0, 1, 2), [0, 0, 0], [1, 1, 1])]
check(sorted(round(x[2], 12) for x in ends) == [0, 1] and all(abs(x[0] - 0.5) + abs(x[1] - 0.5) < 1e-12 for x in ends),
      f"three seeds: the curve's ends {ends}")

# --at on a labelled point cloud: the same four seeds, labelled 7, 3, 9 and 4, and a fifth
# far away; the corners at their point are the tetrahedron's.
with tempfile.TemporaryDirectory() as folder:
    cloud = os.path.join(folder, "seeds.xyz")
    with open(cloud, "w") as f:
        f.write("# x y z label\n")
        for label, p in zip((7, 3, 9, 4), corners):
            f.write(f"{p[0]} {p[1]} {p[2]} {label}\n")
        f.write("0.95 0.95 0.95 1\n")
    run = subprocess.run([sys.executable, sys.argv[1], "--at", "3,4,7,9", cloud], capture_output=True, text=True)
    lines = run.stdout.splitlines()
    check(run.returncode == 0 and len(lines) == 7 and "not a point" not in lines[0], f"--at: {run.stdout}{run.stderr}")
    check(all("corner 109.5 deg" in line for line in lines[1:]), f"--at corners: {run.stdout}")
    run = subprocess.run([sys.executable, sys.argv[1], "--at", "3,4,7,8", cloud], capture_output=True, text=True)
    check(run.returncode == 2 and "not four phases" in run.stderr, f"--at with an unknown label: {run.stderr}")

for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
