#!/usr/bin/python3
"""The reference users reach for with label volumes: VTK's discrete flying edges
plus windowed sinc smoothing, timed and measured as bench/run_labels.sh measures
voronoimesh.

    bench/vtk_reference.py VOLUME.nrrd [--iterations 20] [--threads N] [-o OUT.vtp]

Needs VTK's Python (python3-vtk9, or ParaView's python3-paraview) and numpy (scripts/setup.sh --test-readers; Debian's
/usr/bin/python3, not a virtualenv's). Prints one line per stage with its time,
then the triangles, min and mean q (q = 4 sqrt(3) area / sum of squared edges,
as vm::triangle_quality) and how the surfaces meet at junctions:

- every label present but 0 is contoured (GenerateValues over the labels), as
  users do: each label's boundary is its own closed surface, so an interface
  between two labels comes out twice;
- `open edges`: after merging coincident points of the unsmoothed output,
  edges with one triangle (holes; the volume's sides cut regions open);
- `copies apart`: after smoothing, how far apart the copies of one unsmoothed
  point (one per surface through it) have moved: 0 would mean the surfaces
  still meet exactly, along interfaces and junctions alike.
"""

import argparse
import sys
import time

import numpy as np
# The modules one by one: `import vtk` also loads the MPI readers, whose factory
# then replaces vtkNrrdReader by a parallel one that fails without MPI.
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkWindowedSincPolyDataFilter
from vtkmodules.vtkFiltersGeneral import vtkDiscreteFlyingEdges3D
from vtkmodules.vtkIOImage import vtkNrrdReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def triangles_of(poly):
    cells = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return cells.astype(np.int64)


def quality(points, tris):
    a, b, c = points[tris[:, 0]], points[tris[:, 1]], points[tris[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    edges = ((b - a) ** 2).sum(1) + ((c - b) ** 2).sum(1) + ((a - c) ** 2).sum(1)
    q = np.where(edges > 0, 4 * np.sqrt(3) * area / np.maximum(edges, 1e-300), 0)
    return q.min(), q.mean()


def merged_ids(points):
    """An id per point, equal for points at exactly the same position."""
    _, inverse = np.unique(points, axis=0, return_inverse=True)
    return inverse.ravel()


def edge_counts(tris):
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    e.sort(axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("volume")
    ap.add_argument("--iterations", type=int, default=20)
    ap.add_argument("--threads", type=int, default=0, help="SMP threads (default: VTK's)")
    ap.add_argument("-o", "--output", help="write the smoothed surfaces (.vtp)")
    args = ap.parse_args()
    if args.threads:
        vtkSMPTools.Initialize(args.threads)

    times = {}
    t = time.perf_counter()
    reader = vtkNrrdReader()
    reader.SetFileName(args.volume)
    reader.Update()
    times["read"] = time.perf_counter() - t
    image = reader.GetOutput()
    labels = np.unique(vtk_to_numpy(image.GetPointData().GetScalars()))
    labels = labels[labels != 0]

    t = time.perf_counter()
    contour = vtkDiscreteFlyingEdges3D()
    contour.SetInputData(image)
    for i, label in enumerate(labels):
        contour.SetValue(i, float(label))
    contour.ComputeNormalsOff()
    contour.ComputeGradientsOff()
    contour.ComputeScalarsOn()
    contour.Update()
    times["contour"] = time.perf_counter() - t
    raw = contour.GetOutput()

    t = time.perf_counter()
    smoother = vtkWindowedSincPolyDataFilter()
    smoother.SetInputData(raw)
    smoother.SetNumberOfIterations(args.iterations)
    smoother.SetPassBand(0.001)
    smoother.BoundarySmoothingOff()
    smoother.FeatureEdgeSmoothingOff()
    smoother.NonManifoldSmoothingOn()
    smoother.NormalizeCoordinatesOn()
    smoother.Update()
    times["smooth"] = time.perf_counter() - t
    smooth = smoother.GetOutput()

    if args.output:
        t = time.perf_counter()
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(args.output)
        writer.SetInputData(smooth)
        writer.Write()
        times["write"] = time.perf_counter() - t

    raw_points = vtk_to_numpy(raw.GetPoints().GetData()).astype(np.float64)
    points = vtk_to_numpy(smooth.GetPoints().GetData()).astype(np.float64)
    tris = triangles_of(smooth)
    min_q, mean_q = quality(points, tris)
    ids = merged_ids(raw_points)
    counts = edge_counts(ids[triangles_of(raw)])
    # Spread of the smoothed copies of each unsmoothed position.
    lo = np.full((ids.max() + 1, 3), np.inf)
    hi = np.full((ids.max() + 1, 3), -np.inf)
    np.minimum.at(lo, ids, points)
    np.maximum.at(hi, ids, points)
    apart = np.linalg.norm(hi - lo, axis=1)
    copies = np.bincount(ids)

    for stage, seconds in times.items():
        print(f"{stage}: {seconds:.3f} s")
    print(f"total: {sum(times.values()):.3f} s")
    print(f"labels {len(labels)}, triangles {len(tris)}, points {len(points)} ({len(copies)} distinct before smoothing)")
    print(f"min q {min_q:.3f}, mean q {mean_q:.3f}")
    print(f"open edges: {int((counts == 1).sum())} (after merging coincident points of the unsmoothed output)")
    shared = copies > 1
    print(f"copies apart after smoothing: {int(shared.sum())} positions with 2+ copies, max {apart[shared].max():.3f}, "
          f"mean {apart[shared].mean():.3f} (volume units)" if shared.any() else "copies apart: no shared positions")
    return 0


if __name__ == "__main__":
    sys.exit(main())
