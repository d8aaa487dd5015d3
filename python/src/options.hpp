#pragma once
// python/src/options.hpp: the keywords of mesh_labels() and mesh_file(), named
// as the CLI's options (iterations=20, pipeline="...", drop_labels=[3, "liver"]),
// into the library's options; the library's errors as Python exceptions.

#include <voronoimesh/voronoimesh.hpp>

#include <pybind11/pybind11.h>

namespace vmpy {

/// Where the data comes from: a label array, phase values (no label options
/// apply) or a file (which alone takes the options of volumes read from disk:
/// voxels_per_cell, world, ignore_direction).
enum class Input { labels, values, file };

struct Options {
  vm::MeshOptions mesh;
  vm::InputOptions input;
  pybind11::object progress; ///< None or a callable (stage, message)
};

/// The options the keywords give. Raises TypeError for an unknown keyword or a
/// value of the wrong type; ranges are the library's to check (its messages
/// name the options as the CLI does).
Options options_from(const pybind11::kwargs& kwargs, Input input);

/// vm::InvalidInput -> ValueError, vm::IoError -> OSError, vm::Cancelled ->
/// KeyboardInterrupt, any other vm::Error -> voronoimesh.Error (a RuntimeError).
void register_exceptions(pybind11::module_& m);

} // namespace vmpy
