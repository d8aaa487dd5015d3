"""The ParaView plugin against the CLI on the same label volume (issue 20): the
volume, an INR image such as CGAL's liver, is read here into a vtkImageData
(point data, as ParaView holds a label image), meshed by the "Voronoi Mesh"
filter in pvpython, and compared with `voronoimesh mesh` on the file itself:
the same points (to 1e-9), triangles and phase pairs. Prints both times.

Usage: pvpython bench/paraview_liver.py VOLUME.inr[.gz] PLUGIN.so VORONOIMESH_CLI OUT_DIR
(bench/paraview_liver.sh runs it on the liver.)
"""
import gzip
import os
import subprocess
import sys
import time

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, TrivialProducer
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

volume, plugin, cli, out = sys.argv[1:5]
LoadPlugin(plugin, remote=False, ns=globals())


def read_inr(path):
    """An 8-bit unsigned INR image: its labels indexed [x, y, z], spacing, origin."""
    data = (gzip.open if path.endswith(".gz") else open)(path, "rb").read()
    end = data.index(b"##}\n") + 4
    fields = dict(line.split("=", 1) for line in data[:end].decode().splitlines() if "=" in line)
    assert fields["TYPE"] == "unsigned fixed" and fields["PIXSIZE"] == "8 bits", "only 8-bit labels here"
    size = [int(fields[k]) for k in ("XDIM", "YDIM", "ZDIM")]
    spacing = [float(fields.get(k, 1)) for k in ("VX", "VY", "VZ")]
    origin = [float(fields.get(k, 0)) for k in ("XO", "YO", "ZO")]
    labels = np.frombuffer(data, np.uint8, int(np.prod(size)), end)
    return labels, size, spacing, origin


labels, size, spacing, origin = read_inr(volume)
image = vtkImageData()
image.SetDimensions(*size)
image.SetSpacing(*spacing)
image.SetOrigin(*origin)
array = numpy_to_vtk(labels, deep=True)  # x fastest, as INR stores it
array.SetName("labels")
image.GetPointData().AddArray(array)
source = TrivialProducer()
source.GetClientSideObject().SetOutput(image)

start = time.time()
f = VoronoiMesh(Input=source)
f.Labels = ["POINTS", "labels"]
f.UpdatePipeline()
plugin_seconds = time.time() - start
surfaces = servermanager.Fetch(f)

os.makedirs(out, exist_ok=True)
start = time.time()
subprocess.run([cli, "mesh", "-q", volume, "-o", os.path.join(out, "cli.vtu")], check=True)
cli_seconds = time.time() - start
reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(os.path.join(out, "cli.vtu"))
reader.Update()
ug = reader.GetOutput()

ours, theirs = vtk_to_numpy(surfaces.GetPoints().GetData()), vtk_to_numpy(ug.GetPoints().GetData())
tris_pv = vtk_to_numpy(surfaces.GetPolys().GetConnectivityArray()).reshape(-1, 3)
tris_cli = vtk_to_numpy(ug.GetCells().GetConnectivityArray()).reshape(-1, 3)
pairs = [np.column_stack([vtk_to_numpy(d.GetCellData().GetArray(f"phase{k}")) for k in (0, 1)]) for d in (surfaces, ug)]
same = (ours.shape == theirs.shape and np.allclose(ours, theirs, rtol=0, atol=1e-9) and
        np.array_equal(tris_pv, tris_cli) and np.array_equal(*pairs))
print(f"{volume}: plugin {len(tris_pv)} triangles in {plugin_seconds:.2f} s (pvpython, in memory); "
      f"CLI {len(tris_cli)} triangles in {cli_seconds:.2f} s (whole process, reading the file)")
print("the same mesh: points, triangles and phase pairs" if same else "DIFFERENT meshes")
sys.exit(0 if same else 1)
