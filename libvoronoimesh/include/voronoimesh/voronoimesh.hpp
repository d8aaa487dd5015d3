#pragma once
/// @file voronoimesh.hpp
/// Everything a program needs to mesh its own data, in one include (README,
/// "Use it from C++"):
///  - scenes from files (fields/input.hpp, fields/scene.hpp) or from arrays in memory (fields/array_input.hpp);
///  - create and improve in one call, or each half (run/meshing.hpp);
///  - what the mesh holds (mesh/node_mesh.hpp), its surfaces, phase volumes and
///    curves (mesh/queries.hpp), its junctions (mesh/junctions.hpp), counts and quality
///    (check/stats.hpp), its consistency (check/validate.hpp), where a label
///    volume's voxel centres lie in it (check/label_agreement.hpp);
///  - writing it in the format a file name asks for (io/write_mesh.hpp);
///  - errors: every failure is a vm::Error (core/errors.hpp); the library never exits.
/// The headers it includes are documented one by one; the lower-level steps
/// (fields/sampled_field.hpp, create/create.hpp, mesh/interface_mesh.hpp,
/// improve/pipeline.hpp, improve/registry.hpp, the passes) are public too, for
/// programs that need finer control.

#include "voronoimesh/check/label_agreement.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/array_input.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/mesh/junctions.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"
#include "voronoimesh/mesh/queries.hpp"
#include "voronoimesh/run/meshing.hpp"
#include "voronoimesh/run/mesher.hpp"
