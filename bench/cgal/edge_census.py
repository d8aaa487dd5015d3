#!/usr/bin/env python3
"""Counts the edge problems of a voronoimesh PLY, by kind, for bench/race.sh.

    edge_census.py MESH.ply      ->  one line of JSON

`voronoimesh stats` validates a mesh but prints only its first 20 problems and
no total (and `voronoimesh flip` prints the total when it refuses a mesh, not
the kinds). This recounts the edge checks of the library's validate
(libvoronoimesh/src/check/validate.cpp) over the whole mesh, so a table can
say how many edges of each kind are wrong:

- per phase, an edge must be used once in each direction by the triangles the
  phase bounds (pair[0] sees a triangle as it is, pair[1] reversed); on a face
  of the "comment domain" box once in total is allowed. Otherwise it is
  "open" (used once: a hole), "orientation" (twice, same way) or
  "non_manifold" (more than twice);
- a junction edge (3 or more triangles, all counted above) must carry one
  cycle of distinct pairs: every phase on exactly two of its triangles
  (on the box, a path), and the pairs connected: else "broken_junction".

Node checks (one fan per phase around a node) are not recounted; a zero-area or
duplicate triangle neither. Binary little-endian or ASCII PLY with the layout
write_ply and cgal_label_mesher write (double x y z; uchar/int
vertex_indices, int phase0, int phase1). Standard library only.
"""
import json
import struct
import sys
from collections import defaultdict

TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h", "ushort": "H",
         "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I", "float": "f", "float32": "f",
         "double": "d", "float64": "d"}


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    elements, domain, fmt = [], None, None
    for line in data[:end].decode("ascii", "replace").splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "comment" and len(w) == 8 and w[1] == "domain":
            domain = [float(x) for x in w[2:]]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            elements[-1][2].append(w[1:])
    if fmt not in ("binary_little_endian", "ascii"):
        sys.exit(f"edge_census: {path}: format {fmt} not supported")
    tokens = iter(data[end:].split()) if fmt == "ascii" else None
    pos = end

    def scalar(t):
        nonlocal pos
        if tokens is not None:
            tok = next(tokens)
            return float(tok) if TYPES[t] in "fd" else int(tok)
        v = struct.unpack_from("<" + TYPES[t], data, pos)[0]
        pos += struct.calcsize(TYPES[t])
        return v

    points, tris, pairs = [], [], []
    for name, count, props in elements:
        for _ in range(count):
            rec = {}
            for p in props:
                if p[0] == "list":
                    rec[p[3]] = [scalar(p[2]) for _ in range(scalar(p[1]))]
                else:
                    rec[p[1]] = scalar(p[0])
            if name == "vertex":
                points.append((rec["x"], rec["y"], rec["z"]))
            elif name == "face":
                tris.append(rec.get("vertex_indices") or rec["vertex_index"])
                pairs.append((rec["phase0"], rec["phase1"]))
    return points, tris, pairs, domain


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: edge_census.py MESH.ply")
    points, tris, pairs, domain = read_ply(sys.argv[1])
    if domain is None:  # as read_ply: the bounding box of the points
        domain = [min(p[a] for p in points) for a in range(3)] + [max(p[a] for p in points) for a in range(3)]
    diag = sum((domain[a + 3] - domain[a]) ** 2 for a in range(3)) ** 0.5
    tol = 1e-9 * diag

    def box_faces(p):
        bits = 0
        for a in range(3):
            if abs(p[a] - domain[a]) <= tol:
                bits |= 1 << (2 * a)
            if abs(p[a] - domain[a + 3]) <= tol:
                bits |= 1 << (2 * a + 1)
        return bits

    on_box = [box_faces(p) for p in points]
    edges = defaultdict(list)  # (a, b), a < b -> [(triangle, forward)]
    for t, (i, j, k) in enumerate(tris):
        for u, v in ((i, j), (j, k), (k, i)):
            edges[(min(u, v), max(u, v))].append((t, u < v))
    counts = defaultdict(int)
    junction_edges = 0
    for (a, b), uses in edges.items():
        box = (on_box[a] & on_box[b]) != 0
        per_phase = defaultdict(lambda: [0, 0])  # phase -> [forward, back]
        for t, fwd in uses:
            p, q = pairs[t]
            per_phase[p][0 if fwd else 1] += 1
            per_phase[q][1 if fwd else 0] += 1
        for f, r in per_phase.values():
            if (f, r) == (1, 1) or (box and f + r == 1):
                continue
            counts["open" if f + r == 1 else "orientation" if f + r == 2 else "non_manifold"] += 1
        if len(uses) >= 3:
            junction_edges += 1
            degrees = [f + r for f, r in per_phase.values()]
            ends = sum(1 for d in degrees if d == 1)
            ok = all(d == 2 or (box and d == 1) for d in degrees) and ends in (0, 2)
            if ok:  # one cycle (or path): the pairs connect every phase
                parent = {p: p for p in per_phase}

                def find(x):
                    while parent[x] != x:
                        x = parent[x]
                    return x

                for t, _ in uses:
                    parent[find(pairs[t][0])] = find(pairs[t][1])
                ok = len({find(p) for p in per_phase}) == 1
            if not ok:
                counts["broken_junction"] += 1
    # "open" etc. count (edge, phase) uses, as validate logs them; also the
    # distinct edges with any problem of the first three kinds.
    print(json.dumps({"triangles": len(tris), "edges": len(edges), "junction_edges": junction_edges,
                      "open": counts["open"], "orientation": counts["orientation"],
                      "non_manifold": counts["non_manifold"], "broken_junction": counts["broken_junction"]}))


if __name__ == "__main__":
    main()
