"""The ParaView plugin in pvpython, headless: it loads, meshes a label volume
given as point data and as cell data and phase functions given as point
arrays, and gives the same triangles as the CLI and the Python module on the
same data; its junction and history outputs, its progress and its abort.

Usage: pvpython test_plugin.py PLUGIN.so VORONOIMESH_CLI [PYTHON_MODULE_DIR]
Exits 1 on the first failure (an AssertionError with what differs).
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, TrivialProducer
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

plugin, cli = sys.argv[1], sys.argv[2]
module_dir = sys.argv[3] if len(sys.argv) > 3 else None
LoadPlugin(plugin, remote=False, ns=globals())

SHAPE = (20, 18, 16)           # voxels along x, y, z
SPACING = (0.5, 0.75, 0.625)  # dyadic: cell centres land exactly on the point grid
ORIGIN = (1.0, -2.0, 0.5)      # the first voxel's centre


def three_spheres():
    """Labels 0 (background), 2, 5, 9: overlapping balls, indexed [x, y, z]."""
    x, y, z = np.indices(SHAPE)
    labels = np.zeros(SHAPE, dtype=np.int16)
    for label, c, r in [(2, (7, 8, 7), 5.5), (5, (12, 9, 8), 5), (9, (9, 6, 11), 4)]:
        labels[(x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2 < r * r] = label
    return labels


def image(values, cells=False):
    """vtkImageData with `values` ({name: [x, y, z] array}) as point data,
    or as cell data on an image one point larger (voxel centres unchanged)."""
    img = vtkImageData()
    shape = next(iter(values.values())).shape
    img.SetDimensions(*[n + 1 for n in shape] if cells else shape)
    img.SetSpacing(*SPACING)
    img.SetOrigin(*[o - s / 2 for o, s in zip(ORIGIN, SPACING)] if cells else ORIGIN)
    data = img.GetCellData() if cells else img.GetPointData()
    for name, a in values.items():
        array = numpy_to_vtk(np.ascontiguousarray(a.ravel(order="F")), deep=True)
        array.SetName(name)
        data.AddArray(array)
    return img


def producer(img):
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(img)
    return p


def fetch(f, port=0):
    return servermanager.Fetch(f, idx=port)


def triangles(pd):
    return vtk_to_numpy(pd.GetPolys().GetConnectivityArray()).reshape(-1, 3)


def cell_array(ds, name):
    a = ds.GetCellData().GetArray(name)
    assert a is not None, f"no cell array {name}"
    return vtk_to_numpy(a)


def same_mesh(pd, points, tris, phases, what):
    got = vtk_to_numpy(pd.GetPoints().GetData())
    assert got.shape == points.shape, f"{what}: {got.shape[0]} points, expected {points.shape[0]}"
    assert np.allclose(got, points, rtol=0, atol=1e-9), f"{what}: points differ by {np.abs(got - points).max()}"
    assert np.array_equal(triangles(pd), tris), f"{what}: other triangles"
    got_phases = np.column_stack([cell_array(pd, "phase0"), cell_array(pd, "phase1")])
    assert np.array_equal(got_phases, phases), f"{what}: other phase pairs"


def write_nrrd(path, labels):
    header = (f"NRRD0004\ntype: short\ndimension: 3\nsizes: {' '.join(map(str, labels.shape))}\n"
              f"space dimension: 3\nspace directions: ({SPACING[0]},0,0) (0,{SPACING[1]},0) (0,0,{SPACING[2]})\n"
              f"space origin: ({ORIGIN[0]},{ORIGIN[1]},{ORIGIN[2]})\nkinds: domain domain domain\n"
              "endian: little\nencoding: raw\n\n")
    with open(path, "wb") as f:
        f.write(header.encode() + labels.astype("<i2").tobytes(order="F"))


def cli_mesh(labels, tmp):
    write_nrrd(os.path.join(tmp, "labels.nrrd"), labels)
    out = os.path.join(tmp, "cli.vtu")
    subprocess.run([cli, "mesh", "-q", os.path.join(tmp, "labels.nrrd"), "-o", out], check=True)
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(out)
    reader.Update()
    ug = reader.GetOutput()
    tris = vtk_to_numpy(ug.GetCells().GetConnectivityArray()).reshape(-1, 3)
    phases = np.column_stack([cell_array(ug, "phase0"), cell_array(ug, "phase1")])
    return vtk_to_numpy(ug.GetPoints().GetData()), tris, phases


def test_labels_as_the_cli_meshes_them(tmp):
    labels = three_spheres()
    points, tris, phases = cli_mesh(labels, tmp)
    f = VoronoiMesh(Input=producer(image({"labels": labels})))
    f.Labels = ["POINTS", "labels"]
    surfaces = fetch(f)
    same_mesh(surfaces, points, tris, phases, "point labels against the CLI")
    assert sorted(set(phases.ravel())) == [0, 2, 5, 9]
    names = surfaces.GetFieldData()
    assert {names.GetArrayName(i): names.GetArray(i).GetValue(0) for i in range(names.GetNumberOfArrays())} == \
        {"background": 0, "label2": 2, "label5": 5, "label9": 9}

    # The same labels per voxel (cell data): the same nodes, the same mesh.
    g = VoronoiMesh(Input=producer(image({"labels": labels}, cells=True)))
    g.Labels = ["CELLS", "labels"]
    same_mesh(fetch(g), points, tris, phases, "cell labels against the CLI")

    # The same labels as unsigned 32-bit integers (each was once refused as not
    # fitting in 32 bits) and as reals (a float NIfTI's, a resampled map's).
    for dtype in (np.uint32, np.float32, np.float64):
        h = VoronoiMesh(Input=producer(image({"labels": labels.astype(dtype)})))
        h.Labels = ["POINTS", "labels"]
        same_mesh(fetch(h), points, tris, phases, f"{np.dtype(dtype).name} labels against the CLI")

    # Triple curves: polylines on the surfaces' points, three phases each.
    curves = fetch(f, 1)
    assert curves.GetNumberOfLines() >= 3, "the three balls meet along triple curves"
    assert np.array_equal(vtk_to_numpy(curves.GetPoints().GetData()), vtk_to_numpy(surfaces.GetPoints().GetData()))
    p0, p1, p2 = (cell_array(curves, f"phase{k}") for k in range(3))
    assert ((p0 < p1) & (p1 < p2)).all()
    edges = {tuple(sorted(e)) for t in triangles(surfaces) for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    lines = curves.GetLines()
    lines.InitTraversal()
    ids = vtkIdList()
    while lines.GetNextCell(ids):
        nodes = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
        assert all(tuple(sorted(e)) in edges for e in zip(nodes, nodes[1:])), "a curve edge is no triangle edge"

    # The quality history: iteration 0 (the initial mesh) to the last, at most 20
    # (a label volume stops once quality converges, as the CLI's did).
    table = fetch(f, 2)
    iterations = vtk_to_numpy(table.GetColumnByName("iteration"))
    assert 2 < len(iterations) <= 21 and list(iterations) == list(range(len(iterations)))
    min_q = vtk_to_numpy(table.GetColumnByName("min_quality"))
    assert 0.3 < min_q[-1] <= 1 and min_q[-1] > min_q[0]


def test_phase_arrays_as_the_python_module_meshes_them():
    x, y, z = np.indices(SHAPE).astype(float)
    balls = {"solid": 5 - np.sqrt((x - 8) ** 2 + (y - 8) ** 2 + (z - 7) ** 2),
             "bubble": 4.5 - np.sqrt((x - 13) ** 2 + (y - 9) ** 2 + (z - 9) ** 2)}
    values = dict(balls, liquid=-np.maximum(balls["solid"], balls["bubble"]))
    f = VoronoiMesh(Input=producer(image(values)))
    f.PhaseArrays = ["solid", "bubble", "liquid"]
    f.Iterations = 5
    pd = fetch(f)
    assert pd.GetNumberOfCells() > 500
    names = pd.GetFieldData()
    assert sorted(names.GetArrayName(i) for i in range(names.GetNumberOfArrays())) == ["bubble", "liquid", "solid"]
    if module_dir:
        sys.path.insert(0, module_dir)
        import voronoimesh
        ours = voronoimesh.mesh_values([values[k] for k in ["solid", "bubble", "liquid"]], spacing=SPACING,
                                       origin=ORIGIN, names=["solid", "bubble", "liquid"], iterations=5)
        assert ours.validate() == []
        same_mesh(pd, ours.points, ours.triangles, ours.phases, "phase arrays against the Python module")


def test_the_pipeline_help_lists_the_passes():
    f = VoronoiMesh(Input=producer(image({"labels": three_spheres()})))
    help_text = f.GetProperty("Pipeline").SMProperty.GetDocumentation().GetDescription()
    for name in ["smooth", "project", "clamp", "flip", "remesh"]:
        assert f"\n{name}" in help_text, f"the Pipeline help does not list the pass {name}"


def test_progress_abort_and_errors():
    labels = three_spheres()
    f = VoronoiMesh(Input=producer(image({"labels": labels})))
    f.Labels = ["POINTS", "labels"]
    algorithm = f.GetClientSideObject()
    seen = []
    algorithm.AddObserver("ProgressEvent", lambda o, e: seen.append(o.GetProgress()))
    f.UpdatePipeline()
    # A step for each stage and iteration; the run stops once quality converges,
    # where progress goes to the end.
    assert len(seen) > 10 and seen == sorted(seen) and seen[-1] == 1.0, seen

    # Abort after the mesh is created: the outputs stay empty, nothing crashes.
    g = VoronoiMesh(Input=producer(image({"labels": labels})), Iterations=50)
    g.Labels = ["POINTS", "labels"]
    alg = g.GetClientSideObject()
    alg.AddObserver("ProgressEvent", lambda o, e: o.SetAbortExecute(1) if o.GetProgress() > 0.2 else None)
    assert fetch(g).GetNumberOfCells() == 0

    # Size and Tolerance reach the remesh pass: edges shorten where the balls
    # curve, so more triangles than at Size alone; Tolerance without Size is an error.
    sized = {}
    for tolerance in (0, 0.1):
        s = VoronoiMesh(Input=producer(image({"labels": labels})), Iterations=3, Size=2.0, Tolerance=tolerance)
        s.Labels = ["POINTS", "labels"]
        sized[tolerance] = fetch(s).GetNumberOfCells()
    assert 0 < sized[0] < sized[0.1], sized
    print("an error about --tolerance is expected next:", flush=True)
    t = VoronoiMesh(Input=producer(image({"labels": labels})), Tolerance=0.1)
    t.Labels = ["POINTS", "labels"]
    assert fetch(t).GetNumberOfCells() == 0

    # A real-valued array is a label array only if every value is a whole
    # number: one that is not (linear interpolation's 2.5) is an error, an empty output.
    print("an error about label array 'density' is expected next:", flush=True)
    density = labels.astype(np.float32)
    density[3, 4, 5] = 2.5
    h = VoronoiMesh(Input=producer(image({"density": density})))
    h.Labels = ["POINTS", "density"]
    assert fetch(h).GetNumberOfCells() == 0


with tempfile.TemporaryDirectory() as tmp:
    test_labels_as_the_cli_meshes_them(tmp)
test_phase_arrays_as_the_python_module_meshes_them()
test_the_pipeline_help_lists_the_passes()
test_progress_abort_and_errors()
print("paraview plugin: all checks passed")
