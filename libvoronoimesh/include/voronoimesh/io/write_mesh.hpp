#pragma once
/// @file io/write_mesh.hpp
/// Writing an interface mesh in the format its file name asks for, for the
/// tools people take it to: finite-element solvers and Gmsh (.msh), volume
/// meshers (.mesh for MMG and TetGen, per-phase .stl), ParaView (.vtu, .vtp),
/// and anything that reads .ply, .obj or .stl.
///
/// Phases appear in files as their labels (NodeMesh::phase_labels); where a
/// format names a surface, curve or point, the name is built from the labels and
/// phase names of the phases meeting there, "1-sphere1_2-sphere2" (label, then
/// "-name" if the phase has a name; phases joined by '_'). Phase colours
/// (NodeMesh::phase_colors) go where a format holds a table of them: PLY
/// comments, VTU/VTP field data, OBJ materials; STL, MSH and MEDIT have no
/// place for them (docs/formats.md says why). Every file is written
/// to a temporary name and renamed, so a failure leaves no partial file.

#include "voronoimesh/mesh/node_mesh.hpp"

#include <string>
#include <vector>

namespace vm::io {

/// Options of write_mesh().
struct WriteOptions {
  /// PLY and STL: ASCII instead of binary little-endian. (TetGen 1.5 reads
  /// only ASCII STL; ASCII STL also keeps the coordinates exact.)
  bool ascii = false;
};

/// The extensions write_mesh() knows, with the dot: .ply .obj .stl .msh .vtu .vtp .mesh.
/// @return the extensions, lower case, in the order above
const std::vector<std::string>& output_extensions();

/// Checks that write_mesh() knows the extension of `path` (case-insensitive),
/// before any long work.
/// @param path the file to be written
/// @throws InvalidInput "<path>: unknown output format '<ext>' (known: .ply, .obj, ...)", or naming the
///         known formats if `path` has no extension
void check_output_format(const std::string& path);

/// Writes `m` to `path` in the format of its extension:
///  - .ply: io/ply.hpp (double coordinates, face properties phase0/phase1).
///  - .obj: one group `g` per phase pair, named after the pair; when a phase
///    has a colour (NodeMesh::phase_colors), also `<stem>.mtl` beside it, one
///    material per group with the colour of the pair's second phase (else its
///    first's): a face shows one colour, though it lies between two phases.
///  - .stl: one STL per phase pair (STL holds one surface per file), named
///    `<stem>_<pair>.stl` beside `path`, e.g. out_0-outside_1-sphere1.stl; the
///    normals point from the pair's first phase into its second. No file is
///    written at `path` itself. Binary STL stores coordinates as float32.
///  - .msh: Gmsh MSH 4.1 ASCII: one physical surface per phase pair, one
///    physical curve per phase triple (line elements along its triple curves),
///    one physical point per phase set of quadruple points (point elements;
///    curve ends on the domain box are model points without element or group);
///    each node is written once, in the entity of lowest dimension holding it.
///  - .vtu / .vtp: VTK XML UnstructuredGrid / PolyData (ASCII) with cell data
///    phase0/phase1 (labels) and point data junction_order (2 surface, 3 triple
///    curve, 4 or more quadruple point); field data: an Int32 array per named
///    phase holding its label, and the table `phase_colors` (label, red, green,
///    blue per coloured phase).
///  - .mesh: MEDIT (MeshVersionFormatted 2): triangles with one reference per
///    phase pair, triple curves as Edges, quadruple points as Corners and
///    RequiredVertices; the reference table is in comments at the top.
/// @param m       the mesh to write
/// @param path    the file to write; its extension (case-insensitive) chooses the format
/// @param options how to write it (ASCII or binary PLY and STL)
/// @return the files written (one; two for .obj with colours; one per pair for .stl)
/// @throws InvalidInput for an unknown extension (as check_output_format())
/// @throws IoError      if a file cannot be written or the mesh is malformed (pair count differs from the
///                      triangle count, a node id out of range, more than 2^31 - 1 nodes or triangles)
std::vector<std::string> write_mesh(const NodeMesh& m, const std::string& path, const WriteOptions& options = {});

/// Writes one STL per phase (binary unless options.ascii) into the directory
/// `dir` (made if missing):
/// the boundary of the phase, oriented with normals pointing out of it (a
/// triangle of pair (a, b) as it is for a, reversed for b), so each file of a
/// phase that does not touch the domain box is a closed, consistently oriented
/// surface, ready for a volume mesher. Files are named `phase_<token>.stl`
/// (e.g. phase_1-sphere1.stl); phases without triangles get none.
/// @param m       the mesh to write
/// @param dir     the directory to write the files into, made if missing
/// @param options how to write them (ASCII or binary STL)
/// @return the files written
/// @throws IoError as write_mesh()
std::vector<std::string> write_per_phase_stl(const NodeMesh& m, const std::string& dir,
                                             const WriteOptions& options = {});

} // namespace vm::io
