#!/usr/bin/env python3
"""The best worst triangle a closed-form scene allows with exact junctions.

Usage: corner_bound.py SCENE.json [...]   (scenes whose phases are "seeds" of one point
       each, as scripts/make_voronoi_scene.py writes them, or "sphere", "plane" and
       "constant" phases, as bench/junction_scenes.sh's balls)
       corner_bound.py --at A,B,C,D [--at ...] INPUT   (the corners at the point where
       those four phases meet; phase ids of a scene, or labels of a labelled point cloud
       with one point per label, "x y z label" lines as bench/make_grains.py writes: the
       grain maps, too many for the search, at their worst triangles' points)

A surface between two phases ends at triple curves, and two of its curves meet
at a quadruple point: there the surface has a corner, of the angle between the
two curves' tangents. A mesh whose junctions are exact has a node at every
quadruple point inside the domain and its triple curves along the curves, so
the triangles at a corner of angle t (about t where the curves are curved)
split it into k angles summing to t, and the worst of them has quality q
(4 sqrt(3) area / sum of squared edges) of at most that of the isosceles
triangle with apex t / k: 2 sqrt(3) sin a / (4 - 2 cos a) for apex a. The
best k gives the corner's bound (one triangle below 60 degrees, where the
bound is about t in degrees / 30 for small t), and the tightest corner
bounds the mesh's min q from above: below about 10 degrees, q >= 0.3 is out
of reach without moving junctions off the exact ones (which a mesh from
sampled phase functions does by O(h) anyway, so it can land above the bound).
The box makes corners too, which a mesh of the box has nodes at: where a
triple curve ends on a box face, each of its surfaces turns between the curve
and the face (on 3 of bench/junction_scenes.sh's 12 seed scenes the tightest
corner is such a one); where a surface meets a box edge, between the two faces.

Quadruple points: of seeds, the circumcentres of four seeds with no seed
nearer; of other phases, where Newton's method on the four phases' equalities
ends, started from a lattice of points in the domain, with every other phase
lower there. Points on the box likewise, with one or two coordinates held on
a face or edge. Prints, per scene, the smallest corner angle, where it is and
the bound on min q. Brute force over every four phases: seconds for the tens
of cells of bench/junction_scenes.sh, too slow for grain maps of hundreds.
"""
import argparse
import itertools
import json
import math
import sys

# Newton starts per axis (spheres and planes), iterations, and when a point counts as found.
NEWTON_STARTS = 6
NEWTON_STEPS = 40
NEWTON_TOLERANCE = 1e-12


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def det3(m):
    return dot(m[0], cross(m[1], m[2]))


def solve3(rows, rhs):
    """x with rows x = rhs (Cramer's rule), or None if the rows are (nearly) dependent."""
    d = det3(rows)
    if abs(d) < 1e-14:
        return None
    x = []
    for c in range(3):
        m = [r[:] for r in rows]
        for r in range(3):
            m[r][c] = rhs[r]
        x.append(det3(m) / d)
    return x


def circumcentre(points):
    """The point equidistant from four points, or None if they are (nearly) coplanar."""
    a = points[0]
    rows = [[2 * (p[i] - a[i]) for i in range(3)] for p in points[1:]]
    return solve3(rows, [dot(p, p) - dot(a, a) for p in points[1:]])


class Phase:
    """A phase function of docs/scenes.md: its value and gradient at a point."""

    def __init__(self, spec):
        self.kind = spec["kind"]
        if self.kind == "seeds":
            self.centre, self.radius = spec["points"][0], 0.0
        elif self.kind == "sphere":
            self.centre, self.radius = spec["center"], float(spec["radius"])
        elif self.kind == "plane":
            n = spec["normal"]
            length = math.sqrt(dot(n, n))
            self.point, self.normal = spec["point"], [v / length for v in n]
        else:
            self.value = float(spec["value"])

    def __call__(self, x):
        if self.kind in ("seeds", "sphere"):
            return self.radius - math.sqrt(dot(sub(x, self.centre), sub(x, self.centre)))
        if self.kind == "plane":
            return dot(self.normal, sub(x, self.point))
        return self.value

    def gradient(self, x):
        if self.kind in ("seeds", "sphere"):
            d = sub(x, self.centre)
            length = math.sqrt(dot(d, d))
            return [-v / length for v in d] if length > 0 else [0.0, 0.0, 0.0]
        if self.kind == "plane":
            return self.normal
        return [0.0, 0.0, 0.0]


def best_quality_at_angle(t):
    """Quality of the isosceles triangle with apex angle t: the most a triangle with an angle t can have."""
    return 2 * math.sqrt(3) * math.sin(t) / (4 - 2 * math.cos(t))


def best_quality_at_corner(t):
    """The most the worst of the triangles filling a corner of angle t can have: t split evenly in k."""
    return max(best_quality_at_angle(t / k) for k in range(1, math.ceil(t / (math.pi / 3)) + 2))


def newton_points(phases, quad, lo, hi):
    """Where the four phases of `quad` are equal inside [lo, hi], from a lattice of starts (deduplicated)."""
    found = []
    a = phases[quad[0]]
    for start in itertools.product(*[[lo[i] + (k + 0.5) * (hi[i] - lo[i]) / NEWTON_STARTS
                                      for k in range(NEWTON_STARTS)] for i in range(3)]):
        x = list(start)
        for _ in range(NEWTON_STEPS):
            ga = a.gradient(x)
            rows = [sub(phases[q].gradient(x), ga) for q in quad[1:]]
            step = solve3(rows, [phases[q](x) - a(x) for q in quad[1:]])
            if step is None:
                break
            x = sub(x, step)
            if dot(step, step) < NEWTON_TOLERANCE ** 2:
                break
        residual = max(abs(phases[q](x) - a(x)) for q in quad[1:])
        if residual < 1e-9 and all(lo[i] <= x[i] <= hi[i] for i in range(3)) and \
                all(dot(sub(x, y), sub(x, y)) > 1e-18 for y in found):
            found.append(x)
    return found


def quadruple_points(phases, lo, hi):
    """(the four phases, the point) of every quadruple point inside [lo, hi]: four phases equal, all others lower."""
    seeds = all(p.kind == "seeds" for p in phases)
    for quad in itertools.combinations(range(len(phases)), 4):
        if seeds:
            x = circumcentre([phases[i].centre for i in quad])
            candidates = [x] if x is not None and all(lo[i] <= x[i] <= hi[i] for i in range(3)) else []
        else:
            candidates = newton_points(phases, quad, lo, hi)
        for x in candidates:
            top = phases[quad[0]](x)
            if all(phases[k](x) <= top + 1e-12 * max(1.0, abs(top)) for k in range(len(phases)) if k not in quad):
                yield quad, x


def corners_at(phases, quad, x):
    """(angle, the face's two phases) of each surface corner at quadruple point x of the phases `quad`."""
    # The curve of three phases leaves the point along the cross product of
    # their gradients' differences, on the side where the fourth phase is lower.
    direction = {}
    for three in itertools.combinations(quad, 3):
        fourth = next(i for i in quad if i not in three)
        g = [phases[i].gradient(x) for i in three]
        n = cross(sub(g[1], g[0]), sub(g[2], g[0]))
        length = math.sqrt(dot(n, n))
        if length == 0:
            continue
        n = [v / length for v in n]
        if dot(n, sub(phases[fourth].gradient(x), g[0])) > 0:
            n = [-v for v in n]
        direction[three] = n
    # Two curves bound the surface of the two phases they share.
    for e, f in itertools.combinations(direction, 2):
        yield math.acos(max(-1.0, min(1.0, dot(direction[e], direction[f])))), sorted(set(e) & set(f))


def unit(v):
    """v / |v|, or None for a (nearly) zero vector."""
    length = math.sqrt(dot(v, v))
    return [c / length for c in v] if length > 1e-14 else None


def on_top(phases, ids, x):
    """Whether no other phase than `ids` is above their (common) value at x."""
    top = phases[ids[0]](x)
    return all(phases[k](x) <= top + 1e-12 * max(1.0, abs(top)) for k in range(len(phases)) if k not in ids)


def solve_small(rows, rhs):
    """The solution of one or two linear equations in as many unknowns, or None if they are (nearly) singular."""
    if len(rows) == 1:
        return [rhs[0] / rows[0][0]] if abs(rows[0][0]) >= 1e-14 else None
    d = rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0]
    if abs(d) < 1e-14:
        return None
    return [(rhs[0] * rows[1][1] - rows[0][1] * rhs[1]) / d, (rows[0][0] * rhs[1] - rhs[0] * rows[1][0]) / d]


def solve_on(phases, ids, x0, free):
    """x0 moved along the axes `free` (one or two) until the phases `ids` (two or three) are equal there:
    for seeds by solving the linear equations of equal squared distances, else by Newton's method; None
    if it fails."""
    x = list(x0)
    a = phases[ids[0]]
    if all(phases[q].kind == "seeds" for q in ids):
        # Equally far from seeds c_a and c_q: 2 (c_q - c_a) . x = |c_q|^2 - |c_a|^2, linear in x.
        rows, rhs = [], []
        for q in ids[1:]:
            d = [2 * (phases[q].centre[i] - a.centre[i]) for i in range(3)]
            rows.append([d[i] for i in free])
            rhs.append(dot(phases[q].centre, phases[q].centre) - dot(a.centre, a.centre) -
                       sum(d[i] * x[i] for i in range(3) if i not in free))
        solution = solve_small(rows, rhs)
        if solution is None:
            return None
        for i, v in zip(free, solution):
            x[i] = v
        return x
    for _ in range(NEWTON_STEPS):
        rows = [[phases[q].gradient(x)[i] - a.gradient(x)[i] for i in free] for q in ids[1:]]
        step = solve_small(rows, [phases[q](x) - a(x) for q in ids[1:]])
        if step is None:
            return None
        for i, s in zip(free, step):
            x[i] -= s
        if sum(v * v for v in step) < NEWTON_TOLERANCE ** 2:
            break
    if max(abs(phases[q](x) - a(x)) for q in ids[1:]) > 1e-9:
        return None
    return x


def box_points(phases, ids, lo, hi):
    """(the box's fixed axes and their inward normals, the point) of each point of the box's boundary where
    the phases `ids` meet and no other is above them: three phases (a triple curve's end) on a box face,
    two (a surface's edge) on a box edge."""
    fixed_count = 4 - len(ids)  # a face fixes one axis, an edge two
    for fixed in itertools.combinations(range(3), fixed_count):
        free = [i for i in range(3) if i not in fixed]
        for sides in itertools.product((0, 1), repeat=fixed_count):
            found = []
            # Seeds meet at one point of a face or edge at most: one start finds it.
            starts = 1 if all(phases[i].kind == "seeds" for i in ids) else NEWTON_STARTS
            grid = [[lo[i] + (k + 0.5) * (hi[i] - lo[i]) / starts for k in range(starts)] for i in free]
            for start in itertools.product(*grid):
                x0 = [0.0] * 3
                for i, side in zip(fixed, sides):
                    x0[i] = (lo, hi)[side][i]
                for i, v in zip(free, start):
                    x0[i] = v
                x = solve_on(phases, ids, x0, free)
                if x is None or not all(lo[i] <= x[i] <= hi[i] for i in free) or not on_top(phases, ids, x):
                    continue
                if all(dot(sub(x, y), sub(x, y)) > 1e-18 for y in found):
                    found.append(x)
                    inward = [[(1.0 if side == 0 else -1.0) * (i == axis) for i in range(3)]
                              for axis, side in zip(fixed, sides)]
                    yield inward, x


def box_corners_at(phases, ids, inward, x):
    """(angle, the face's two phases) of each surface corner at a point x of the box's boundary where the
    phases `ids` meet (box_points()): where a triple curve ends on a box face, each of its three surfaces
    turns between the curve (into the box) and the face; where a surface meets a box edge, between the
    two faces."""
    g = {i: phases[i].gradient(x) for i in ids}
    for i, j in itertools.combinations(ids, 2):
        normal = sub(g[j], g[i])
        if len(ids) == 3:
            k = next(q for q in ids if q not in (i, j))
            curve = unit(cross(sub(g[j], g[i]), sub(g[k], g[i])))
            along_box = unit(cross(normal, inward[0]))
            if curve is None or along_box is None:
                continue
            if dot(curve, inward[0]) < 0:
                curve = [-v for v in curve]
            if dot(sub(g[k], g[i]), along_box) > 0:  # the side where k is below i and j
                along_box = [-v for v in along_box]
            rays = (curve, along_box)
        else:
            first, second = unit(cross(normal, inward[0])), unit(cross(normal, inward[1]))
            if first is None or second is None:
                continue
            if dot(first, inward[1]) < 0:
                first = [-v for v in first]
            if dot(second, inward[0]) < 0:
                second = [-v for v in second]
            rays = (first, second)
        yield math.acos(max(-1.0, min(1.0, dot(*rays)))), [i, j]


def tightest_corner(phases, lo, hi, at_box=False):
    """(angle, the phases meeting at the corner, the face's two phases, the point) of the corner with the
    lowest bound (best_quality_at_corner()): at the quadruple points inside [lo, hi] (four phases); with
    `at_box`, also where a triple curve ends on the box (three) and where a surface meets a box edge (two),
    which a mesh of the box has as corners too."""
    best, bound = (math.inf, None, None, None), math.inf
    for quad, x in quadruple_points(phases, lo, hi):
        for angle, face in corners_at(phases, quad, x):
            if best_quality_at_corner(angle) < bound:
                best, bound = (angle, quad, face, x), best_quality_at_corner(angle)
    if at_box:
        for count in (3, 2):
            for ids in itertools.combinations(range(len(phases)), count):
                for inward, x in box_points(phases, ids, lo, hi):
                    for angle, face in box_corners_at(phases, ids, inward, x):
                        if best_quality_at_corner(angle) < bound:
                            best, bound = (angle, ids, face, x), best_quality_at_corner(angle)
    return best


def read_scene(path):
    """The phases and domain of a scene file; exits with a one-line message naming the file if it is not one."""
    try:
        with open(path) as f:
            scene = json.load(f)
    except OSError as e:
        sys.exit(f"{path}: cannot open ({e.strerror})")
    except json.JSONDecodeError as e:
        sys.exit(f"{path}: malformed JSON at line {e.lineno}, column {e.colno}")
    try:
        specs, domain = scene["phases"], scene["domain"]
        for p in specs:
            if p.get("kind") not in ("seeds", "sphere", "plane", "constant"):
                sys.exit(f"{path}: phase '{p.get('name', '?')}' is of kind '{p.get('kind')}': "
                         "only seeds, sphere, plane and constant phases have a closed-form bound here")
            if p["kind"] == "seeds" and len(p["points"]) != 1:
                sys.exit(f"{path}: phase '{p.get('name', '?')}' has {len(p['points'])} seeds: one each expected")
        return [Phase(p) for p in specs], domain["min"], domain["max"]
    except (KeyError, TypeError, AttributeError, ValueError, ZeroDivisionError):
        sys.exit(f"{path}: not a scene with a domain and phases (docs/scenes.md)")


def read_point_cloud(path):
    """(seed phases in label order, labels) of a labelled point cloud with one point per label."""
    points = {}
    try:
        with open(path) as f:
            for number, line in enumerate(f, 1):
                fields = line.split()
                if not fields or fields[0].startswith("#"):
                    continue
                try:
                    x, y, z, label = float(fields[0]), float(fields[1]), float(fields[2]), int(fields[3])
                except (ValueError, IndexError):
                    sys.exit(f"{path}:{number}: expected 'x y z label'")
                if label in points:
                    sys.exit(f"{path}:{number}: label {label} has a second point: one point per label expected")
                points[label] = [x, y, z]
    except OSError as e:
        sys.exit(f"{path}: cannot open ({e.strerror})")
    labels = sorted(points)
    return [Phase({"kind": "seeds", "points": [points[label]]}) for label in labels], labels


def report_point(path, phases, ids, names, lo, hi):
    """Prints the corners at the point where the phases `ids` meet (for others than seeds, the first
    Newton's method finds from a lattice of starts in [lo, hi])."""
    quad = tuple(sorted(ids))
    if all(phases[i].kind == "seeds" for i in quad):
        x = circumcentre([phases[i].centre for i in quad])
    else:
        found = newton_points(phases, quad, lo, hi)
        x = found[0] if found else None
    if x is None:
        print(f"{path}: phases {', '.join(names[i] for i in quad)} meet nowhere")
        return
    top = phases[quad[0]](x)
    beaten = [names[k] for k in range(len(phases)) if k not in quad and phases[k](x) > top]
    where = ", ".join(f"{v:.4f}" for v in x)
    note = f"; not a point of the partition: {', '.join(beaten)} larger there" if beaten else ""
    print(f"{path}: point of {', '.join(names[i] for i in quad)} at ({where}){note}")
    for angle, face in corners_at(phases, quad, x):
        print(f"  face of {names[face[0]]} and {names[face[1]]}: corner {math.degrees(angle):.1f} deg, "
              f"min q <= {best_quality_at_corner(angle):.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+", metavar="INPUT",
                        help="scenes of seeds (one point each), sphere, plane and constant phases; with --at, "
                             "also a labelled point cloud (.xyz, .txt) with one point per label")
    parser.add_argument("--at", action="append", default=[], metavar="A,B,C,D",
                        help="the corners at the point of these four phases (scene phase ids or point labels)")
    args = parser.parse_args()
    for path in args.scenes:
        if args.at:
            if path.endswith(".json"):
                phases, lo, hi = read_scene(path)
                names = [str(i) for i in range(len(phases))]
            else:
                phases, labels = read_point_cloud(path)
                names = [str(label) for label in labels]
                lo, hi = None, None  # seeds only: no search
            for spec in args.at:
                try:
                    ids = [names.index(v.strip()) for v in spec.split(",")]
                except ValueError:
                    parser.error(f"--at {spec}: not four phases of {path}")
                if len(set(ids)) != 4:
                    parser.error(f"--at {spec}: four different phases expected")
                report_point(path, phases, ids, names, lo, hi)
            continue
        phases, lo, hi = read_scene(path)
        angle, quad, face, vertex = tightest_corner(phases, lo, hi, at_box=True)
        if quad is None:
            print(f"{path}: no corner: no quadruple point inside the domain, no junction at the box")
            continue
        where = {4: "at the point of phases", 3: "where the curve of phases ends on the box,",
                 2: "where it meets a box edge, phases"}[len(quad)]
        print(f"{path}: tightest corner {math.degrees(angle):.1f} deg (face of phases {face[0]} and {face[1]} "
              f"{where} {', '.join(map(str, quad))}, "
              f"({', '.join(f'{v:.3f}' for v in vertex)})): min q <= {best_quality_at_corner(angle):.3f}")


if __name__ == "__main__":
    main()
