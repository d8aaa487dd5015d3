#!/usr/bin/env python3
"""The best worst triangle a Voronoi seed scene allows with exact junctions.

Usage: voronoi_corner_bound.py SCENE.json [...]   (scenes of "seeds" phases, one point each,
       as scripts/make_voronoi_scene.py writes them)

Each face of a Voronoi diagram is a convex polygon whose corners are Voronoi
vertices (quadruple points). A mesh whose junctions are exact has a node at
every quadruple point inside the domain and its triple curves along the
diagram's edges, so every triangle at a face corner of angle t has an angle of
at most t, and quality q (4 sqrt(3) area / sum of squared edges) of at most
that of the isosceles triangle with apex t: 2 sqrt(3) sin t / (4 - 2 cos t).
The smallest face corner inside the domain therefore bounds the mesh's min q
from above: below about 10 degrees, q >= 0.3 is out of reach without moving
junctions off the exact diagram (which a mesh from sampled phase functions
does by O(h) anyway, so it can land above the bound).

Prints, per scene, the smallest corner angle, where it is and the bound on min q.
Brute force over every four seeds: seconds for the tens of cells of
bench/junction_scenes.sh, too slow for grain maps of hundreds.
"""
import argparse
import itertools
import json
import math
import sys


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def det3(m):
    return dot(m[0], cross(m[1], m[2]))


def circumcentre(points):
    """The point equidistant from four points, or None if they are (nearly) coplanar."""
    a = points[0]
    rows = [[2 * (p[i] - a[i]) for i in range(3)] for p in points[1:]]
    rhs = [dot(p, p) - dot(a, a) for p in points[1:]]
    d = det3(rows)
    if abs(d) < 1e-14:
        return None
    centre = []
    for c in range(3):  # Cramer's rule
        m = [r[:] for r in rows]
        for r in range(3):
            m[r][c] = rhs[r]
        centre.append(det3(m) / d)
    return centre


def best_quality_at_angle(t):
    """Quality of the isosceles triangle with apex angle t: the most a triangle with an angle t can have."""
    return 2 * math.sqrt(3) * math.sin(t) / (4 - 2 * math.cos(t))


def smallest_face_corner(seeds, lo, hi):
    """(angle, the four cells, the face's two cells, the vertex) of the smallest face corner inside [lo, hi]."""
    best = (math.inf, None, None, None)
    for quad in itertools.combinations(range(len(seeds)), 4):
        x = circumcentre([seeds[i] for i in quad])
        if x is None or any(x[i] < lo[i] or x[i] > hi[i] for i in range(3)):
            continue
        r2 = dot(sub(x, seeds[quad[0]]), sub(x, seeds[quad[0]]))
        if any(dot(sub(x, s), sub(x, s)) < r2 * (1 - 1e-12) for k, s in enumerate(seeds) if k not in quad):
            continue  # another seed is nearer: not a vertex of the diagram
        # The edge of three cells leaves the vertex along the normal of their seeds' plane,
        # away from the fourth seed.
        direction = {}
        for three in itertools.combinations(quad, 3):
            fourth = next(i for i in quad if i not in three)
            a, b, c = (seeds[i] for i in three)
            n = cross(sub(b, a), sub(c, a))
            length = math.sqrt(dot(n, n))
            n = [v / length for v in n]
            if dot(n, sub(seeds[fourth], a)) > 0:
                n = [-v for v in n]
            direction[three] = n
        # Two edges bound the face of the two cells they share.
        for e, f in itertools.combinations(direction, 2):
            angle = math.acos(max(-1.0, min(1.0, dot(direction[e], direction[f]))))
            if angle < best[0]:
                best = (angle, quad, sorted(set(e) & set(f)), x)
    return best


def read_seeds(path):
    """The seeds and domain of a scene file; exits with a one-line message naming the file if it is not one."""
    try:
        with open(path) as f:
            scene = json.load(f)
    except OSError as e:
        sys.exit(f"{path}: cannot open ({e.strerror})")
    except json.JSONDecodeError as e:
        sys.exit(f"{path}: malformed JSON at line {e.lineno}, column {e.colno}")
    try:
        phases, domain = scene["phases"], scene["domain"]
        if any(p.get("kind") != "seeds" or len(p["points"]) != 1 for p in phases):
            sys.exit(f"{path}: every phase must be 'seeds' with one point")
        return [p["points"][0] for p in phases], domain["min"], domain["max"]
    except (KeyError, TypeError, AttributeError):
        sys.exit(f"{path}: not a scene with a domain and phases (docs/scenes.md)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+", metavar="SCENE.json", help="scenes of 'seeds' phases, one point each")
    for path in parser.parse_args().scenes:
        seeds, lo, hi = read_seeds(path)
        angle, quad, face, vertex = smallest_face_corner(seeds, lo, hi)
        if quad is None:
            print(f"{path}: no quadruple point inside the domain")
            continue
        print(f"{path}: smallest face corner {math.degrees(angle):.1f} deg (face of cells {face[0]} and {face[1]} "
              f"at the point of cells {', '.join(map(str, quad))}, "
              f"({', '.join(f'{v:.3f}' for v in vertex)})): min q <= {best_quality_at_angle(angle):.3f}")


if __name__ == "__main__":
    main()
