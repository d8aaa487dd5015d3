#pragma once
/// @file io/writers.hpp
/// The writer of each format behind write_mesh() (io/write_mesh.hpp), one
/// source file per format. Each assumes check_output_mesh() has passed, and
/// writes its files among `staged` (core/staged_outputs.hpp): they appear when
/// the caller commits every output of its run.

#include "core/staged_outputs.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <string>
#include <vector>

namespace vm::io::detail {

/// Throws IoError "<path>: cannot write: ..." when `m` cannot be written as it
/// is: pair and triangle counts differ, a node id is out of range, a pair is not
/// two phase ids 0 <= a < b < 2^15, or there are more than 2^31 - 1 nodes or
/// triangles (32-bit indices in PLY and STL).
void check_output_mesh(const NodeMesh& m, const std::string& path);

/// Wavefront OBJ, one group per phase pair, and when a phase has a colour the
/// material library `<stem>.mtl` beside it, a material per group (obj.cpp).
/// Returns the files written.
std::vector<std::string> write_obj(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path);

/// One STL per phase pair, `<stem>_<pair>.stl` beside `path`, binary unless
/// `ascii` (stl.cpp).
std::vector<std::string> write_stl_per_pair(vm::detail::StagedOutputs& staged, const NodeMesh& m,
                                            const std::string& path, bool ascii);

/// Gmsh MSH 4.1 ASCII with physical groups for surfaces, triple curves and
/// quadruple points (msh.cpp).
void write_msh(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path);

/// The two VTK XML datasets write_vtk_xml() can write.
enum class VtkDataset { unstructured_grid, poly_data };

/// VTK XML .vtu or .vtp with phase cell data and junction-order point data (vtk_xml.cpp).
void write_vtk_xml(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                   VtkDataset dataset);

/// The ParaView index (.pvtu) of .vtu pieces that write_vtk_xml() wrote, each
/// named by its path relative to the index's folder (vtk_xml.cpp).
void write_pvtu_index(vm::detail::StagedOutputs& staged, const std::string& path,
                      const std::vector<std::string>& pieces);

/// MEDIT .mesh with references per phase pair and triple curve (medit.cpp).
void write_medit(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path);

/// PLY (ply.cpp; write_ply() writes one on its own).
void write_ply(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path, bool ascii);

/// write_mesh() among `staged`; returns the files written.
std::vector<std::string> write_mesh(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                                    const WriteOptions& options);

/// write_per_phase_stl() among `staged`; returns the files written.
std::vector<std::string> write_per_phase_stl(vm::detail::StagedOutputs& staged, const NodeMesh& m,
                                             const std::string& dir, const WriteOptions& options);

} // namespace vm::io::detail
