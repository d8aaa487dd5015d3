#!/usr/bin/env python3
"""Renders an interface mesh (.vtu written by voronoimesh) to a PNG, each surface (phase pair)
in its own colour, the outside phase's surfaces see-through, triple curves drawn dark: the
README's picture of the demo.

Usage: xvfb-run -a scripts/render_mesh.py MESH.vtu OUT.png [--size 900x700]
Needs VTK's Python (python3-vtk9, or ParaView's python3-paraview) and, without a display, xvfb (Debian: xvfb): VTK renders through X.
"""
import argparse
import sys

import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

# Qualitative colours (Tableau 10), one per surface in order of its phase pair.
PALETTE = [(78, 121, 167), (242, 142, 43), (225, 87, 89), (118, 183, 178), (89, 161, 79), (237, 201, 72),
           (176, 122, 161), (255, 157, 167), (156, 117, 95), (186, 176, 172)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("png")
    parser.add_argument("--size", default="800x640")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(args.mesh)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0 or not grid.GetCellData().GetArray("phase1"):
        sys.exit(f"{args.mesh}: no triangles with phase0/phase1 cell data (a .vtu written by voronoimesh?)")
    phase0 = vtk_to_numpy(grid.GetCellData().GetArray("phase0"))
    phase1 = vtk_to_numpy(grid.GetCellData().GetArray("phase1"))
    pairs = sorted(set(zip(phase0.tolist(), phase1.tolist())))
    index = {pair: i for i, pair in enumerate(pairs)}
    colours = numpy_to_vtk([PALETTE[index[p] % len(PALETTE)] for p in zip(phase0.tolist(), phase1.tolist())],
                           deep=True, array_type=vtk.VTK_UNSIGNED_CHAR)
    colours.SetName("surface")
    grid.GetCellData().AddArray(colours)

    # Surfaces of the outside phase (the smallest label: the background) are see-through,
    # so the surfaces between the other phases show inside them.
    outside = min(min(p) for p in pairs)
    outer = numpy_to_vtk([int(outside in p) for p in zip(phase0.tolist(), phase1.tolist())], deep=True,
                         array_type=vtk.VTK_INT)
    outer.SetName("outer")
    grid.GetCellData().AddArray(outer)
    actors = []
    for wanted, opacity in ((0, 1.0), (1, 0.3)):
        part = vtk.vtkThreshold()
        part.SetInputData(grid)
        part.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, "outer")
        part.SetLowerThreshold(wanted)
        part.SetUpperThreshold(wanted)
        mapper = vtk.vtkDataSetMapper()
        mapper.SetInputConnection(part.GetOutputPort())
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray("surface")
        mapper.SetColorModeToDirectScalars()
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetOpacity(opacity)
        actor.GetProperty().SetEdgeVisibility(opacity == 1.0)
        actor.GetProperty().SetEdgeColor(0.2, 0.2, 0.2)
        actor.GetProperty().SetLineWidth(0.5)
        actors.append(actor)

    # Triple curves: the edges junction_order >= 3 at both ends, thick and dark.
    order = vtk_to_numpy(grid.GetPointData().GetArray("junction_order"))
    lines = vtk.vtkCellArray()
    seen = set()
    for c in range(grid.GetNumberOfCells()):
        ids = [grid.GetCell(c).GetPointId(k) for k in range(3)]
        for a, b in ((ids[0], ids[1]), (ids[1], ids[2]), (ids[2], ids[0])):
            key = (min(a, b), max(a, b))
            if order[a] >= 3 and order[b] >= 3 and key not in seen:
                seen.add(key)
                lines.InsertNextCell(2, key)
    curves = vtk.vtkPolyData()
    curves.SetPoints(grid.GetPoints())
    curves.SetLines(lines)
    curve_mapper = vtk.vtkPolyDataMapper()
    curve_mapper.SetInputData(curves)
    curve_actor = vtk.vtkActor()
    curve_actor.SetMapper(curve_mapper)
    curve_actor.GetProperty().SetColor(0.05, 0.05, 0.05)
    curve_actor.GetProperty().SetLineWidth(3)

    renderer = vtk.vtkRenderer()
    for a in actors + [curve_actor]:
        renderer.AddActor(a)
    renderer.SetUseDepthPeeling(True)
    renderer.SetBackground(1, 1, 1)
    renderer.GetActiveCamera().Azimuth(35)
    renderer.GetActiveCamera().Elevation(25)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.15)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetAlphaBitPlanes(1)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    window.SetSize(width, height)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(args.png)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    print(f"{args.png}: {len(pairs)} surfaces, {len(seen)} triple-curve edges, {grid.GetNumberOfCells()} triangles")


if __name__ == "__main__":
    main()
