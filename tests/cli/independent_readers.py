#!/usr/bin/env python3
"""Reads every output format of voronoimesh back with independent, widely used readers.

Usage: independent_readers.py READER VORONOIMESH WORK_DIR
  READER: meshio (MSH, VTU, MEDIT, STL, OBJ, ASCII PLY), vtk (VTU, VTP: what ParaView reads with),
          each also on a 3D Slicer segmentation and a DREAM.3D grain map (written with h5py)
          whose names must reach MSH and VTU, and the segments' colours VTU/VTP field data,
          OBJ materials (VTK's OBJ importer reads the .mtl) and PLY comments,
          gmsh (loads the MSH, then tetrahedralises sphere volumes bounded by its physical surfaces),
          tetgen (tetrahedralises each closed per-phase ASCII STL and the MEDIT file, checking for
          self-intersections with -d).
Exits 77 (ctest's SKIP_RETURN_CODE) when the reader is not installed, 1 on any failure.

The mesh is the four-sphere demo at grid 16 (5 phases, 10 surfaces, 10 triple curves,
5 quadruple points), relabelled to labels 5, 15, 25, 35, 45 so the tests also see that
files show labels, not phase ids. The reference is the ASCII PLY written by the same run.
A second mesh, the Voronoi cells of 4 seeds, has triple curves that end on the domain box.
"""
import collections
import os
import re
import shutil
import subprocess
import sys

SKIP = 77
LABEL = {p: 10 * p + 5 for p in range(5)}
NAMES = ["outside", "sphere1", "sphere2", "sphere3", "sphere4"]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(*args, cwd=None):
    r = subprocess.run(list(args), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise SystemExit(f"FAIL: {' '.join(args)} exited with {r.returncode}:\n{r.stdout}")
    return r.stdout


def token(label):
    return f"{label}-{NAMES[(label - 5) // 10]}"


class Reference:
    """The mesh as the ASCII PLY holds it, and its junction structure computed here."""

    def __init__(self, path):
        with open(path) as f:
            lines = f.read().split("\n")
        end = lines.index("end_header")
        header = lines[:end]
        nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
        nf = int(next(l for l in header if l.startswith("element face")).split()[2])
        body = lines[end + 1:]
        self.points = [tuple(float(x) for x in body[i].split()) for i in range(nv)]
        self.triangles, self.pairs = [], []
        for line in body[nv:nv + nf]:
            w = [int(x) for x in line.split()]
            self.triangles.append(tuple(w[1:4]))
            self.pairs.append((w[4], w[5]))
        phases = collections.defaultdict(set)
        uses = collections.Counter()
        for t, p in zip(self.triangles, self.pairs):
            for k in range(3):
                phases[t[k]].update(p)
                uses[frozenset((t[k], t[(k + 1) % 3]))] += 1
        self.order = [len(phases[n]) for n in range(nv)]
        self.quadruple_points = sum(1 for o in self.order if o >= 4)
        self.junction_edges = sum(1 for u in uses.values() if u >= 3)

    def corners(self, t, as_float=False):
        pts = [self.points[v] for v in self.triangles[t]]
        return [tuple(float32(x) for x in p) for p in pts] if as_float else pts

    def pair_by_triangle(self, as_float=False):
        """Oriented key of each triangle -> its label pair."""
        return {oriented_key(self.corners(t, as_float)): self.pairs[t] for t in range(len(self.triangles))}


def float32(x):
    import struct
    return struct.unpack("f", struct.pack("f", x))[0]


def oriented_key(corners):
    """The triangle's corners rotated to start at the smallest: equal for equally oriented triangles."""
    corners = [tuple(c) for c in corners]
    i = corners.index(min(corners))
    return tuple(corners[i:] + corners[:i])


def closed_and_oriented(triangles):
    """Every directed edge once and its reverse once: a closed, consistently oriented surface."""
    directed = collections.Counter()
    for c in triangles:
        for k in range(3):
            directed[(tuple(c[k]), tuple(c[(k + 1) % 3]))] += 1
    return all(n == 1 and directed[(b, a)] == 1 for (a, b), n in directed.items())


def signed_volume(triangles):
    v = 0.0
    for a, b, c in triangles:
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
    return v


CELLS = """{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 16, "phases": [
  {"name": "a", "kind": "seeds", "points": [[0.3, 0.3, 0.3]]}, {"name": "b", "kind": "seeds", "points": [[0.7, 0.3, 0.35]]},
  {"name": "c", "kind": "seeds", "points": [[0.5, 0.7, 0.4]]}, {"name": "d", "kind": "seeds", "points": [[0.45, 0.5, 0.75]]}]}
"""


def prepare(vm, work):
    """Writes the relabelled reference and every format from it, and the cells as PLY and MSH;
    returns the References of the spheres and of the cells."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    run(vm, "create", "-q", "--grid", "16", "--ascii", "-o", "demo.ply", cwd=work)
    with open(os.path.join(work, "demo.ply")) as f:
        text = f.read()
    header, body = text.split("end_header\n")
    header = re.sub(r"comment phase (\d+) ", lambda m: f"comment phase {LABEL[int(m.group(1))]} ", header)
    lines = body.split("\n")
    for i, line in enumerate(lines):
        w = line.split()
        if len(w) == 6 and w[0] == "3":
            lines[i] = " ".join(w[:4] + [str(LABEL[int(w[4])]), str(LABEL[int(w[5])])])
    with open(os.path.join(work, "labelled.ply"), "w") as f:
        f.write(header + "end_header\n" + "\n".join(lines))
    # No iterations: the mesh goes through read_ply and every writer unchanged.
    same = ["smooth", "labelled.ply", "--pipeline", "flip", "--iterations", "0", "-q"]
    run(vm, *same, "--ascii", "-o", "out.ply", cwd=work)
    for ext in ["obj", "msh", "vtu", "vtp", "mesh"]:
        run(vm, *same, "-o", "out." + ext, cwd=work)
    run(vm, *same, "-o", "surf.stl", "--per-phase", "phases", cwd=work)
    run(vm, *same, "--ascii", "-o", "surf_ascii.stl", "--per-phase", "phases_ascii", cwd=work)
    ref = Reference(os.path.join(work, "out.ply"))
    check(sorted({p for pr in ref.pairs for p in pr}) == sorted(LABEL.values()), "the PLY shows the labels")
    check(len(ref.points) > 400 and ref.quadruple_points == 5, "reference mesh: 5 quadruple points")
    with open(os.path.join(work, "cells.json"), "w") as f:
        f.write(CELLS)
    for out in ["cells.ply", "cells.msh"]:
        run(vm, "create", "-q", "--ascii", "cells.json", "-o", out, cwd=work)
    cells = Reference(os.path.join(work, "cells.ply"))
    write_segmentation(os.path.join(work, "organ.seg.nrrd"))
    for out in ["seg.msh", "seg.vtu", "seg.vtp", "seg.obj"]:
        run(vm, "mesh", "-q", "--iterations", "2", "organ.seg.nrrd", "-o", out, cwd=work)
    run(vm, "mesh", "-q", "--iterations", "2", "--ascii", "organ.seg.nrrd", "-o", "seg.ply", cwd=work)
    write_grains(os.path.join(work, "grains.dream3d"))
    for out in ["grains.msh", "grains.vtu"]:
        run(vm, "mesh", "-q", "--iterations", "2", "grains.dream3d", "-o", out, cwd=work)
    check(cells.quadruple_points == 1 and cells.junction_edges > 10, "cells: 4 triple curves meeting inside the box")
    return ref, cells


SEGMENT_NAMES = {0: "background", 1: "liver", 2: "tumour & cyst"}
SEGMENT_COLORS = {1: (0.9, 0.5, 0.25), 2: (0.0, 0.5, 1.0)}  # the background is no segment: no colour
# The OBJ's material of each surface: its second phase's colour.
SEGMENT_MATERIALS = {"0-background_1-liver": SEGMENT_COLORS[1], "1-liver_2-tumour---cyst": SEGMENT_COLORS[2]}


def write_segmentation(path):
    """A 3D Slicer segmentation in two layers: an organ (a 10^3 cube, layer 0) and a tumour
    (4^3) inside it (layer 1), both of label value 1, as Slicer stores overlapping segments."""
    n = 16
    inside = lambda i, j, k, lo, hi: lo <= i < hi and lo <= j < hi and lo <= k < hi
    data = bytearray()
    for k in range(n):
        for j in range(n):
            for i in range(n):
                data += bytes([int(inside(i, j, k, 3, 13)), int(inside(i, j, k, 6, 10))])
    header = ["NRRD0004", "type: uchar", "dimension: 4", "space: left-posterior-superior", f"sizes: 2 {n} {n} {n}",
              "space directions: none (1,0,0) (0,1,0) (0,0,1)", "kinds: list domain domain domain",
              "encoding: raw", "space origin: (0,0,0)"]
    for s, name in [(0, "liver"), (1, "tumour & cyst")]:
        header += [f"Segment{s}_ID:=Segment_{s + 1}", f"Segment{s}_Name:={name}", f"Segment{s}_LabelValue:=1",
                   f"Segment{s}_Layer:={s}", f"Segment{s}_Color:={' '.join(map(str, SEGMENT_COLORS[s + 1]))}"]
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n\n").encode() + bytes(data))


GRAIN_NAMES = {1: "grain1-Austenite", 2: "grain2-Ferrite", 3: "grain3-Austenite"}


def write_grains(path):
    """A DREAM3D-NX grain map written with h5py: three grains in slabs along x, with the
    grains' phases in a feature-level Phases array and the phases' names in an
    ensemble-level PhaseNames array (entry 0: DREAM.3D's placeholder for no phase)."""
    import h5py
    import numpy as np
    ids = np.empty((8, 10, 12, 1), dtype=np.int32)  # z, y, x, components
    ids[:, :, :4], ids[:, :, 4:8], ids[:, :, 8:] = 1, 2, 3
    with h5py.File(path, "w") as f:
        geometry = f.create_group("DataStructure/Image Geometry")
        geometry.attrs["_DIMENSIONS"] = np.array([12, 10, 8], dtype=np.uint64)
        geometry.attrs["_ORIGIN"] = np.zeros(3, dtype=np.float32)
        geometry.attrs["_SPACING"] = np.ones(3, dtype=np.float32)
        geometry.create_dataset("Cell Data/FeatureIds", data=ids)
        geometry.create_dataset("Cell Feature Data/Phases", data=np.array([[0], [1], [2], [1]], dtype=np.int32))
        geometry.create_dataset("Cell Ensemble Data/PhaseNames", data=["Unknown Phase", "Austenite", "Ferrite"],
                                dtype=h5py.string_dtype())


def triangles_of(mesh):
    """(block index, row) of every triangle cell of a meshio mesh, in order."""
    return [(b, i) for b, block in enumerate(mesh.cells) if block.type == "triangle" for i in range(len(block.data))]


def compare_pairs(name, mesh, ref, pair_of_cell):
    """Every triangle of the meshio mesh has the reference's pair and orientation."""
    want = ref.pair_by_triangle()
    got = {}
    for b, i in triangles_of(mesh):
        key = oriented_key([tuple(mesh.points[v]) for v in mesh.cells[b].data[i]])
        got[key] = pair_of_cell(b, i)
    check(len(mesh.points) == len(ref.points), f"{name}: {len(mesh.points)} nodes, expected {len(ref.points)}")
    check(len(triangles_of(mesh)) == len(ref.triangles), f"{name}: {len(triangles_of(mesh))} triangles")
    check(got == want, f"{name}: triangles, orientation or phase pairs differ from the reference")


def meshio_checks(work, ref, cells):
    import meshio
    path = lambda f: os.path.join(work, f)
    # MSH: physical surface names -> pairs; junction curves and points.
    m = meshio.read(path("out.msh"))
    names = {tag: name for name, (tag, dim) in m.field_data.items()}
    physical = m.cell_data["gmsh:physical"]
    labels_of = lambda name: tuple(int(t.split("-")[0]) for t in name.split("_"))
    compare_pairs("msh", m, ref, lambda b, i: labels_of(names[physical[b][i]]))
    lines = sum(len(c.data) for c in m.cells if c.type == "line")
    check(lines == ref.junction_edges, f"msh: {lines} line elements, expected {ref.junction_edges} junction edges")
    points = [b for b, c in enumerate(m.cells) if c.type == "vertex"]
    check(len(points) == 5 and all(len(labels_of(names[physical[b][0]])) == 4 for b in points),
          "msh: 5 physical points of 4 phases")
    check(f"{token(15)}_{token(25)}" in m.field_data, "msh: a physical surface named after labels and names")
    # Curves ending on the box: their ends are model points without elements or physical groups.
    m = meshio.read(path("cells.msh"))
    names = {tag: name for name, (tag, dim) in m.field_data.items()}
    compare_pairs("cells.msh", m, cells, lambda b, i: labels_of(names[m.cell_data["gmsh:physical"][b][i]]))
    check(sum(len(c.data) for c in m.cells if c.type == "vertex") == 1, "cells.msh: one point element")
    # VTU: cell and point data.
    m = meshio.read(path("out.vtu"))
    compare_pairs("vtu", m, ref, lambda b, i: (int(m.cell_data["phase0"][b][i]), int(m.cell_data["phase1"][b][i])))
    check(list(m.point_data["junction_order"]) == ref.order, "vtu: junction_order differs")
    # A Slicer segmentation's names: VTU field data (name -> label), MSH physical names.
    m = meshio.read(path("seg.vtu"))
    colors = m.field_data.pop("phase_colors", None)
    check({k: list(v) for k, v in m.field_data.items()} == {n: [l] for l, n in SEGMENT_NAMES.items()},
          f"seg.vtu: field data {m.field_data} is not the segments' names and labels")
    # Their colours: one table, a row (label, red, green, blue) per coloured phase.
    check(colors is not None and [tuple(row) for row in colors] == [(l, *c) for l, c in SEGMENT_COLORS.items()],
          f"seg.vtu: phase_colors {colors} is not the segments' colours by label")
    m = meshio.read(path("seg.obj"))
    check(len({int(g) for block in m.cell_data["obj:group_ids"] for g in block}) == 2,
          "seg.obj: its materials keep it readable, two groups")
    m = meshio.read(path("seg.msh"))
    check(sorted(n for n, (t, d) in m.field_data.items() if d == 2) == ["0-background_1-liver", "1-liver_2-tumour---cyst"],
          f"seg.msh: physical surfaces {sorted(m.field_data)} are not named after the segments")
    # A DREAM.3D grain map's grain names, likewise.
    m = meshio.read(path("grains.vtu"))
    check({k: list(v) for k, v in m.field_data.items()} == {n: [l] for l, n in GRAIN_NAMES.items()},
          f"grains.vtu: field data {m.field_data} is not the grains' names and ids")
    m = meshio.read(path("grains.msh"))
    check(sorted(n for n, (t, d) in m.field_data.items() if d == 2) ==
          ["1-grain1-Austenite_2-grain2-Ferrite", "2-grain2-Ferrite_3-grain3-Austenite"],
          f"grains.msh: physical surfaces {sorted(m.field_data)} are not named after the grains")
    # MEDIT: references through the table in the comments.
    with open(path("out.mesh")) as f:
        table = dict(re.findall(r"#   triangle ref (\d+): (\S+)", f.read()))
    m = meshio.read(path("out.mesh"))
    refs = m.cell_data["medit:ref"]
    compare_pairs("mesh", m, ref, lambda b, i: labels_of(table[str(refs[b][i])]))
    lines = sum(len(c.data) for c in m.cells if c.type == "line")
    check(lines == ref.junction_edges, f"mesh: {lines} edges, expected {ref.junction_edges}")
    # STL, one binary file per pair named after it; float32 coordinates.
    want = collections.defaultdict(set)
    for t, p in enumerate(ref.pairs):
        want[f"surf_{token(p[0])}_{token(p[1])}.stl"].add(oriented_key(ref.corners(t, as_float=True)))
    got = {}
    for f in sorted(os.listdir(work)):
        if f.startswith("surf_") and not f.startswith("surf_ascii"):
            m = meshio.read(path(f))
            got[f] = {oriented_key([tuple(float(x) for x in m.points[v]) for v in tri]) for tri in m.cells[0].data}
    check(got == want, f"stl: files {sorted(got)} or their triangles differ from one file per pair")
    # Per-phase binary STL: closed, outward.
    volume = {}
    for label in LABEL.values():
        m = meshio.read(path(f"phases/phase_{token(label)}.stl"))
        tris = [[tuple(m.points[v]) for v in tri] for tri in m.cells[0].data]
        check(closed_and_oriented(tris), f"per-phase stl of {label}: not closed and consistently oriented")
        volume[label] = signed_volume(tris)
    spheres = sum(v for l, v in volume.items() if l != 5)
    check(all(v > 0 for l, v in volume.items() if l != 5), f"per-phase stl: sphere volumes {volume} not positive")
    check(abs(volume[5] + spheres) < 1e-5, "per-phase stl: the outside's boundary does not enclose minus the spheres")
    # OBJ: one group per pair.
    m = meshio.read(path("out.obj"))
    groups = {int(g) for block in m.cell_data["obj:group_ids"] for g in block}
    check(len(m.points) == len(ref.points) and len(triangles_of(m)) == len(ref.triangles), "obj: counts")
    check(len(groups) == 10, f"obj: {len(groups)} groups, expected 10")
    # ASCII PLY (meshio's binary PLY reader cannot read face properties after a list).
    m = meshio.read(path("out.ply"))
    compare_pairs("ply", m, ref, lambda b, i: (int(m.cell_data["phase0"][b][i]), int(m.cell_data["phase1"][b][i])))


def vtk_checks(work, ref, cells):
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    class Errors:
        def __init__(self):
            self.seen = []

        def __call__(self, obj, event):
            self.seen.append(event)

    want = ref.pair_by_triangle()
    for ext, reader in [("vtu", vtk.vtkXMLUnstructuredGridReader()), ("vtp", vtk.vtkXMLPolyDataReader())]:
        errors = Errors()
        for event in ("ErrorEvent", "WarningEvent"):
            reader.AddObserver(event, errors)
        reader.SetFileName(os.path.join(work, "out." + ext))
        reader.Update()
        data = reader.GetOutput()
        check(not errors.seen, f"{ext}: VTK reported {errors.seen}")
        points = vtk_to_numpy(data.GetPoints().GetData())
        phase0 = vtk_to_numpy(data.GetCellData().GetArray("phase0"))
        phase1 = vtk_to_numpy(data.GetCellData().GetArray("phase1"))
        order = vtk_to_numpy(data.GetPointData().GetArray("junction_order"))
        got = {}
        for c in range(data.GetNumberOfCells()):
            cell = data.GetCell(c)
            check(cell.GetCellType() == vtk.VTK_TRIANGLE, f"{ext}: cell {c} is not a triangle")
            ids = [cell.GetPointId(k) for k in range(3)]
            got[oriented_key([tuple(points[i]) for i in ids])] = (int(phase0[c]), int(phase1[c]))
        check(data.GetNumberOfPoints() == len(ref.points), f"{ext}: {data.GetNumberOfPoints()} points")
        check(data.GetNumberOfCells() == len(ref.triangles), f"{ext}: {data.GetNumberOfCells()} cells")
        check(got == want, f"{ext}: triangles, orientation or phase pairs differ from the reference")
        check(list(order) == ref.order, f"{ext}: junction_order differs")
    # What docs/formats.md tells viewers: ParaView's PLY reader (VTK's) keeps no phases.
    ply = vtk.vtkPLYReader()
    ply.SetFileName(os.path.join(work, "out.ply"))
    ply.Update()
    arrays = [ply.GetOutput().GetCellData().GetArrayName(i) for i in range(ply.GetOutput().GetCellData().GetNumberOfArrays())]
    check(ply.GetOutput().GetNumberOfCells() == len(ref.triangles) and "phase1" not in arrays,
          f"ply in VTK: {ply.GetOutput().GetNumberOfCells()} cells, cell arrays {arrays}: docs/formats.md says "
          "ParaView opens a .ply without its phases")
    for ext, reader in [("vtu", vtk.vtkXMLUnstructuredGridReader()), ("vtp", vtk.vtkXMLPolyDataReader())]:
        reader.SetFileName(os.path.join(work, "seg." + ext))
        reader.Update()
        fields = reader.GetOutput().GetFieldData()
        arrays = {fields.GetArrayName(i): fields.GetArray(i) for i in range(fields.GetNumberOfArrays())}
        table = arrays.pop("phase_colors", None)
        got = {name: a.GetValue(0) for name, a in arrays.items()}
        check(got == {n: l for l, n in SEGMENT_NAMES.items()}, f"seg.{ext}: VTK reads field data {got}")
        rows = [] if table is None else [tuple(table.GetTuple4(r)) for r in range(table.GetNumberOfTuples())]
        check(rows == [(l, *c) for l, c in SEGMENT_COLORS.items()] and
              [table.GetComponentName(c) for c in range(4)] == ["label", "red", "green", "blue"],
              f"seg.{ext}: VTK reads the colour table as {rows}")
    # OBJ: VTK's importer (what ParaView's OBJ import uses) reads the .mtl: a coloured actor per material.
    importer = vtk.vtkOBJImporter()
    importer.SetFileName(os.path.join(work, "seg.obj"))
    importer.SetFileNameMTL(os.path.join(work, "seg.mtl"))
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    renderer = vtk.vtkRenderer()
    window.AddRenderer(renderer)
    importer.SetRenderWindow(window)
    importer.Update()
    materials = {}
    actors = renderer.GetActors()
    actors.InitTraversal()
    for i in range(actors.GetNumberOfItems()):
        actor = actors.GetNextActor()
        if actor.GetMapper().GetInput().GetNumberOfCells() > 0:
            name = re.search(r"material named (\S+)", importer.GetOutputDescription(i)).group(1)
            materials[name] = tuple(round(c, 6) for c in actor.GetProperty().GetDiffuseColor())
    check(materials == SEGMENT_MATERIALS, f"seg.obj: VTK imports the materials {materials}")
    # PLY: the colours are comments, which VTK's PLY reader hands over.
    ply = vtk.vtkPLYReader()
    ply.SetFileName(os.path.join(work, "seg.ply"))
    ply.Update()
    comments = [ply.GetComments().GetValue(i) for i in range(ply.GetComments().GetNumberOfValues())]
    want = [f"phase_color {l} {' '.join(f'{x:g}' for x in c)}" for l, c in SEGMENT_COLORS.items()]
    check([c for c in comments if c.startswith("phase_color")] == want, f"seg.ply: VTK reads the comments {comments}")


def gmsh_checks(work, ref, cells):
    gmsh = shutil.which("gmsh")
    for name, mesh in [("out.msh", ref), ("cells.msh", cells)]:
        log = run(gmsh, "-check", name, cwd=work)
        check(not re.search(r"^(Warning|Error)", log, re.M), f"gmsh -check {name}: warnings or errors:\n{log}")
        check(f"{len(mesh.points)} nodes" in log, f"gmsh read a different node count from {name}:\n{log}")
    # A Slicer segmentation's and a grain map's physical names survive Gmsh reading and writing them.
    for name, want in [("seg", {"0-background_1-liver", "1-liver_2-tumour---cyst"}),
                       ("grains", {"1-grain1-Austenite_2-grain2-Ferrite", "2-grain2-Ferrite_3-grain3-Austenite"})]:
        run(gmsh, name + ".msh", "-0", "-o", name + "_again.msh", cwd=work)
        with open(os.path.join(work, name + "_again.msh")) as f:
            again = set(re.findall(r'^2 \d+ "([^"]+)"$', f.read(), re.M))
        check(again == want, f"gmsh: physical surfaces of {name}.msh {again}")
    # Volumes bounded by the physical surfaces: Gmsh tetrahedralises each sphere
    # phase conformally with its neighbours, which needs watertight shared surfaces.
    with open(os.path.join(work, "out.msh")) as f:
        text = f.read()
    surface_of_physical = {}
    entities = text.split("$Entities\n")[1].split("$EndEntities")[0].split("\n")
    n_points, n_curves, n_surfaces, _ = (int(x) for x in entities[0].split())
    for line in entities[1 + n_points + n_curves:1 + n_points + n_curves + n_surfaces]:
        w = line.split()
        surface_of_physical[int(w[8])] = int(w[0])
    names = dict((int(t), n) for d, t, n in re.findall(r'^(\d) (\d+) "([^"]+)"$', text, re.M) if d == "2")
    geo = ['Merge "out.msh";']
    for k, label in enumerate(l for l in LABEL.values() if l != 5):
        bounding = [surface_of_physical[t] for t, n in names.items() if token(label) in n.split("_")]
        geo += [f"Surface Loop({k + 1}) = {{{', '.join(map(str, bounding))}}};", f"Volume({k + 1}) = {{{k + 1}}};"]
    with open(os.path.join(work, "volumes.geo"), "w") as f:
        f.write("\n".join(geo) + "\n")
    log = run(gmsh, "volumes.geo", "-3", "-o", "volumes.msh", cwd=work)
    check(not re.search(r"^(Warning|Error)", log, re.M), f"gmsh -3: warnings or errors:\n{log}")
    tets = [int(n) for n in re.findall(r"(\d+) tetrahedra created", log)]
    check(sum(tets) > 1000, f"gmsh made {sum(tets)} tetrahedra in the four spheres:\n{log}")


def tetgen_checks(work, ref, cells):
    tetgen = shutil.which("tetgen")
    phases = os.path.join(work, "phases_ascii")
    closed = []
    for label in LABEL.values():
        f = f"phase_{token(label)}.stl"
        with open(os.path.join(phases, f)) as stl:
            tris = re.findall(r"vertex (\S+) (\S+) (\S+)", stl.read())
        tris = [tuple(tuple(float(x) for x in v) for v in tris[i:i + 3]) for i in range(0, len(tris), 3)]
        if closed_and_oriented(tris):
            closed.append(label)
        log = run(tetgen, "-d", f, cwd=phases)
        check("No faces are intersecting" in log, f"tetgen -d {f}: self-intersections:\n{log}")
        run(tetgen, "-pQ", f, cwd=phases)
        with open(os.path.join(phases, f[:-4] + ".1.ele")) as ele:
            tets = int(ele.readline().split()[0])
        check(tets > 100, f"tetgen -pQ {f}: {tets} tetrahedra")
    # Every sphere lies inside the domain box, so every phase (the outside too) is closed.
    check(closed == list(LABEL.values()), f"closed phases {closed}, expected all five")
    # The whole interface as MEDIT: one region per sphere.
    log = run(tetgen, "-d", "out.mesh", cwd=work)
    check("No faces are intersecting" in log, f"tetgen -d out.mesh: self-intersections:\n{log}")
    run(tetgen, "-pAQ", "out.mesh", cwd=work)
    with open(os.path.join(work, "out.1.ele")) as ele:
        n = int(ele.readline().split()[0])
        regions = {ele.readline().split()[5] for _ in range(n)}
    check(len(regions) == 4, f"tetgen -pA out.mesh: {len(regions)} regions, expected the 4 spheres")
    # A closed domain (--close) of seven Voronoi cells, every one cut by the box and improved:
    # each cell's surface is watertight, TetGen fills it, and the whole network gives seven regions.
    examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
    run(VM, "mesh", "-q", os.path.join(examples, "voronoi7.json"), "--grid", "16", "--close", "--iterations", "10",
        "--ascii", "-o", "closed.mesh", "--per-phase", "closed_phases", cwd=work)
    cells = sorted(os.listdir(os.path.join(work, "closed_phases")))
    check(len(cells) == 8, f"--close --per-phase: {cells}, expected 7 cells and the exterior")
    for f in cells:
        if "exterior" in f:
            continue
        log = run(tetgen, "-d", f, cwd=os.path.join(work, "closed_phases"))
        check("No faces are intersecting" in log, f"tetgen -d closed {f}: self-intersections:\n{log}")
        run(tetgen, "-pQ", f, cwd=os.path.join(work, "closed_phases"))
    run(tetgen, "-pAQ", "closed.mesh", cwd=work)
    with open(os.path.join(work, "closed.1.ele")) as ele:
        n = int(ele.readline().split()[0])
        regions = {ele.readline().split()[5] for _ in range(n)}
    check(len(regions) == 7, f"tetgen -pA closed.mesh: {len(regions)} regions, expected the 7 cells")


def missing(reader):
    """Why `reader` cannot run here, or None."""
    if reader in ("gmsh", "tetgen") and not shutil.which(reader):
        return f"{reader} is not installed (Debian: {reader})"
    # Every reader's checks include a DREAM.3D file written with h5py.
    needed = {"meshio": [("meshio", "python3-meshio")], "vtk": [("vtk", "python3-vtk9 or python3-paraview")]}.get(reader, [])
    for module, package in needed + [("h5py", "python3-h5py")]:
        try:
            __import__(module)
        except ImportError:
            return f"{sys.executable} has no {module} module (Debian: {package})"
    return None


VM = None  # the voronoimesh tool, for checks that make meshes of their own


def main():
    global VM
    checks = {"meshio": meshio_checks, "vtk": vtk_checks, "gmsh": gmsh_checks, "tetgen": tetgen_checks}
    if len(sys.argv) != 4 or sys.argv[1] not in checks:
        raise SystemExit(__doc__)
    reader, vm, work = sys.argv[1:]
    why = missing(reader)
    if why:
        print("SKIP:", why)
        return SKIP
    VM = os.path.abspath(vm)
    checks[reader](work, *prepare(VM, work))
    print(f"{reader}: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
