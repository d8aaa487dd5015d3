#pragma once
/// @file sequence.hpp
/// `voronoimesh mesh` on a sequence (the paper's use: an evolving interface
/// meshed step after step): several inputs, or one numbered pattern such as
/// step_%04d.nrrd; one mesh per step, named by a numbered -o, and for VTK
/// outputs a ParaView collection (.pvd) of them with their time values.

#include <string>
#include <vector>

namespace vmcli {

/// One step: its input and its number (the pattern's number, else its index).
struct Step {
  std::string input;
  long number = 0;
};

/// The steps `inputs` name: one numbered pattern (a printf %d, %0Nd) is every
/// existing file it matches, in number order; several inputs are the steps in
/// the order given, numbered from 0. Throws InvalidInput for a pattern that
/// matches no file.
std::vector<Step> sequence_steps(const std::vector<std::string>& inputs);

/// True when `path` holds one printf integer conversion (%d, %Nd or %0Nd, N
/// at most 3 digits).
bool is_numbered(const std::string& path);

/// `pattern` with its number conversion replaced by `number`.
std::string numbered(const std::string& pattern, long number);

/// Writes the ParaView collection `pvd` of the files `meshes` (paths as
/// written), at times `times`; the files are named relative to the .pvd.
void write_pvd(const std::string& pvd, const std::vector<std::string>& meshes, const std::vector<double>& times);

/// The collection's name for numbered outputs: the pattern without its number
/// (and the separator before it), with the extension .pvd: out/step_%04d.vtu
/// gives out/step.pvd.
std::string pvd_name(const std::string& pattern);

} // namespace vmcli
