"""voronoimesh: meshes of interconnected surfaces (Saye's Voronoi implicit interface method).

    import voronoimesh
    mesh = voronoimesh.mesh_labels(labels, spacing=(0.5, 0.5, 1.0), iterations=20)
    mesh.points, mesh.triangles, mesh.phases      # numpy arrays
    mesh.write("organs.vtu"); mesh.to_meshio()

Options are the command line's, as keywords (iterations=, pipeline=, size=, close=,
threads=, drop_labels=, keep_labels=, merge_labels=, background=, smoothing=, ...); see
docs/python.md. Errors: ValueError (bad input or option), OSError (files),
KeyboardInterrupt (Ctrl-C, which stops a run), voronoimesh.Error (anything else).
"""
import json as _json

from ._voronoimesh import Error, Mesh, Mesher, mesh_file, mesh_labels, mesh_values, output_extensions, read_mesh

__all__ = ["Error", "Mesh", "Mesher", "mesh_file", "mesh_labels", "mesh_values", "output_extensions", "read_mesh"]


def _stats(self, worst=0, folds=0, field="", **input_options):
    """Counts and quality as a dict, the keys of 'voronoimesh stats --json'; with worst=N also
    'worst_triangles': the N triangles of lowest quality and what meets at their corners; with
    folds=M also 'sharpest_folds': the M surface edges that turn back the most, and their ends;
    with field=INPUT (the file the mesh was made from; its input options, such as
    voxels_per_cell=, as keywords) also 'offsets': how far the surface, triple-curve and
    quadruple-point nodes lie from its interface, in world units and in h (the grid spacing
    the mesh was created on), and for a label volume and a closed mesh 'label_agreement':
    where its voxel centres lie (as Mesh.label_agreement()); for a label volume and a mesh
    that is not closed, a UserWarning says why there is none."""
    return _json.loads(self.stats_json(worst, folds, field, **input_options))


def _label_agreement(self, labels, spacing=(1, 1, 1), origin=(0, 0, 0), margin=1):
    """Where the voxel centres of a label array lie in this closed mesh (one meshed with
    close=True), as a dict: 'voxels' located (every centre; the outer layer's, on the box faces,
    a thousandth of a spacing inside), 'in_phase' (those in a phase of their own label), 'interior' and 'interior_in_phase'
    (those whose neighbours within margin voxels share their label), 'undecided', and
    'labels': per label its 'voxels' and 'in_phase'. What 'voronoimesh stats --field' prints
    for a label volume."""
    return _json.loads(self.label_agreement_json(labels, spacing, origin, margin))


def _to_meshio(self):
    """The mesh as a meshio.Mesh: triangles, cell data phase0/phase1 (labels), and the
    phase names as field data (name -> [label]) and their colours as the table
    phase_colors (label, red, green, blue), as the VTU writer stores them."""
    import meshio
    import numpy

    phases = self.phases
    field_data = {name: numpy.array([label]) for name, label in zip(self.phase_names, self.phase_labels) if name}
    colors = [(label, *rgb) for label, rgb in zip(self.phase_labels, self.phase_colors) if rgb is not None]
    if colors:
        field_data["phase_colors"] = numpy.array(colors, dtype=numpy.float64)
    return meshio.Mesh(self.points.copy(), [("triangle", self.triangles.copy())],
                       cell_data={"phase0": [phases[:, 0]], "phase1": [phases[:, 1]]}, field_data=field_data)


Mesh.stats = _stats
Mesh.label_agreement = _label_agreement
Mesh.to_meshio = _to_meshio
