#pragma once
/// @file voronoimesh.hpp
/// Everything a program needs to mesh its own data, in one include (README,
/// "Use it from C++"):
///  - scenes from files (input.hpp, scene.hpp) or from arrays in memory (array_input.hpp);
///  - create and improve in one call, or each half (meshing.hpp);
///  - what the mesh holds (node_mesh.hpp), its surfaces, phase volumes and
///    curves (queries.hpp), its junctions (junctions.hpp), counts and quality
///    (stats.hpp), its consistency (validate.hpp);
///  - writing it in the format a file name asks for (io/write_mesh.hpp);
///  - errors: every failure is a vm::Error (errors.hpp); the library never exits.
/// The headers it includes are documented one by one; the lower-level steps
/// (sampled_field.hpp, create.hpp, mesh.hpp, pipeline.hpp, registry.hpp, the
/// passes) are public too, for programs that need finer control.

#include "voronoimesh/array_input.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/input.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/junctions.hpp"
#include "voronoimesh/meshing.hpp"
#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/queries.hpp"
#include "voronoimesh/scene.hpp"
#include "voronoimesh/stats.hpp"
#include "voronoimesh/validate.hpp"
