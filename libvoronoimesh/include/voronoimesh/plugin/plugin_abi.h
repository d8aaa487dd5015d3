#ifndef VORONOIMESH_PLUGIN_ABI_H
#define VORONOIMESH_PLUGIN_ABI_H
/** @file plugin/plugin_abi.h
 * The plain-C boundary between voronoimesh and its pass plugins.
 *
 * A plugin is a shared library that exports two C functions:
 *
 *     uint32_t voronoimesh_plugin_abi_version(void);           // returns VM_PLUGIN_ABI_VERSION
 *     int voronoimesh_plugin_v1(const vm_plugin_host* host);   // names itself, adds its passes
 *
 * Only C types cross this boundary (no C++ classes, no exceptions, no allocations
 * freed on the other side), so a plugin built by another compiler, or another
 * standard library, can be loaded safely. The host reads the ABI version first
 * and refuses the file, naming it, if it differs from its own; any change to a
 * struct below raises VM_PLUGIN_ABI_VERSION (and the entry point's suffix when
 * the change is incompatible).
 *
 * Lifetimes: every pointer a plugin passes to the host (strings, parameter
 * tables) is copied before the call returns, except `run` and `user` of a pass,
 * which must stay valid while the library is loaded. Every pointer the host
 * passes to a plugin is valid only during that call.
 *
 * Write plugins in C against this header, or in C++ with the helpers of
 * voronoimesh/plugin/plugin_helpers.hpp (header only: it adds no link dependency).
 */

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The ABI version this header describes. */
#define VM_PLUGIN_ABI_VERSION 1u

/** Marks the two exported functions of a plugin (default visibility). */
#if defined(_WIN32)
#define VM_PLUGIN_EXPORT __declspec(dllexport)
#else
#define VM_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

/** One parameter of a pass, as ParamSpec in improve/pass.hpp: the CLI's `passes`
 *  listing and pipeline validation are generated from it. */
typedef struct vm_param_spec {
  const char* name;     /**< a-z, 0-9 and _ */
  double default_value; /**< must lie in [min, max] */
  /** Smallest value accepted: the range [min, max] is inclusive. */
  double min, max;      /**< largest value accepted (accepted range, inclusive) */
  int integer;          /**< nonzero: only whole numbers are accepted */
  const char* help;     /**< one line */
} vm_param_spec;

/** The mesh as a pass sees it during one call of `run`. Node-level arrays: node
 *  i has position positions[3i..3i+2]; its phases phases[8i..8i+7] (sorted,
 *  padded with -1); its box faces box_faces[i] (bit 2a: on the min side of axis
 *  a, bit 2a+1: on the max side); junction_order[i] = phases + box faces, the
 *  outside phase of a closed mesh not counted (its surfaces are the box faces)
 *  (2: a surface node, the box faces' too, 3: on a triple curve or where a
 *  surface meets the box, 4 and more: a point); its neighbours neighbours[neighbour_offsets[i] ..
 *  neighbour_offsets[i+1]-1], sorted. Triangle t has nodes triangles[3t..3t+2],
 *  oriented so that its right-hand normal points from phase pairs[2t] into
 *  pairs[2t+1] (pairs[2t] < pairs[2t+1]). */
typedef struct vm_mesh_view {
  size_t num_nodes;                 /**< nodes (geometric points) */
  const double* positions;          /**< 3 x num_nodes: x, y, z of each node */
  const int16_t* phases;            /**< 8 x num_nodes: the phases at each node, sorted, padded with -1 */
  const uint8_t* box_faces;         /**< num_nodes: bit 2a on the min side of axis a, bit 2a+1 on the max */
  const int32_t* junction_order;    /**< num_nodes: phases + box faces of each node (closed: less the outside) */
  const int32_t* neighbour_offsets; /**< num_nodes + 1: where each node's neighbours start in `neighbours` */
  const int32_t* neighbours;        /**< the neighbours of every node, sorted, node after node */
  size_t num_triangles;             /**< triangles */
  const int32_t* triangles;         /**< 3 x num_triangles: the nodes of each triangle, oriented */
  const int32_t* pairs;             /**< 2 x num_triangles: the phase pair of each triangle, ascending */
  int32_t num_phases;               /**< number of phases: the field's if given, else the mesh's named ones */
  /** Corner of the domain box with the smallest coordinates. */
  double domain_min[3], domain_max[3]; /**< corner of the domain box with the largest coordinates */
  int32_t iteration; /**< 1-based iteration of the pipeline */

  /** 3 x num_nodes pending displacements: a pass that moves nodes ADDS its moves
   *  here; the host clamps and commits them through its crossing guard, so a
   *  pass never moves a node itself. NULL for passes that do not move nodes. */
  double* displacement;

  /** The original phase functions, for passes declared with needs_field (else
   *  NULL). Both return 0 on success, nonzero if the field failed. Safe to call
   *  from several threads at once. */
  const void* field;
  /** Writes phi_phase(x) of `field` into *value; returns 0 on success. */
  int (*field_value)(const void* field, int32_t phase, const double x[3], double* value);
  /** Writes grad phi_phase(x) of `field` into gradient; returns 0 on success. */
  int (*field_gradient)(const void* field, int32_t phase, const double x[3], double gradient[3]);
} vm_mesh_view;

/** Runs a pass once. `params` holds the values of the pass's parameters in the
 *  order they were declared, already checked against their ranges. Returns 0 on
 *  success; otherwise writes a one-line message into `error` (at most
 *  `error_size` bytes with the terminating 0) and returns nonzero. */
typedef int (*vm_pass_run)(void* user, const vm_mesh_view* mesh, const double* params, char* error,
                           size_t error_size);

/** A pass type a plugin adds to the registry. */
typedef struct vm_pass_desc {
  const char* name;    /**< a-z, 0-9, _ and -; must not exist yet */
  const char* summary; /**< one line */
  const vm_param_spec* params; /**< its parameters, in the order `run` receives their values */
  size_t num_params;           /**< entries of params */
  int moves_nodes; /**< nonzero: adds to the displacement buffer */
  int needs_field; /**< nonzero: needs the phase functions */
  vm_pass_run run; /**< runs the pass once; must stay valid while the library is loaded */
  void* user; /**< given back to run */
} vm_pass_desc;

/** What the host offers the entry point. */
typedef struct vm_plugin_host {
  uint32_t abi_version;     /**< the host's VM_PLUGIN_ABI_VERSION */
  const char* host_version; /**< "0.1.0" */
  void* context;            /**< give back to the functions below */
  /** Names the plugin (shown by `voronoimesh plugins`); call once. */
  void (*set_info)(void* context, const char* name, const char* version);
  /** Adds a pass. Returns 0, or nonzero if the host refuses it (the host then
   *  refuses the whole plugin with its own message). */
  int (*add_pass)(void* context, const vm_pass_desc* pass);
} vm_plugin_host;

/** The two functions a plugin exports. */
typedef uint32_t (*vm_plugin_abi_version_fn)(void);
/** Returns 0 when the plugin registered itself, nonzero to be refused. */
typedef int (*vm_plugin_entry_v1_fn)(const vm_plugin_host* host);

/** Name of the exported function that returns the plugin's ABI version. */
#define VM_PLUGIN_ABI_SYMBOL "voronoimesh_plugin_abi_version"
/** Name of the exported entry point (version 1), which names the plugin and adds its passes. */
#define VM_PLUGIN_ENTRY_SYMBOL "voronoimesh_plugin_v1"

#ifdef __cplusplus
}
#endif

#endif /* VORONOIMESH_PLUGIN_ABI_H */
