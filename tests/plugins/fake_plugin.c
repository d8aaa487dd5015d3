/* Broken plugins for the refusal tests, one per compile definition:
 *   FAKE_WRONG_ABI   claims a future plugin ABI version
 *   FAKE_NO_ENTRY    a shared library without the entry point
 *   FAKE_CLASH       registers a pass named "smooth", which is built in
 *   FAKE_FAILING     a good plugin whose pass fails at run time
 * Written in C: the boundary must work for plugins in plain C. */
#include "voronoimesh/plugin/plugin_abi.h"

#include <stdio.h>

#ifndef FAKE_NO_ENTRY
static int run(void* user, const vm_mesh_view* mesh, const double* params, char* error, size_t error_size) {
  (void)user;
  (void)params;
#ifdef FAKE_FAILING
  snprintf(error, error_size, "cannot relax %zu nodes today", mesh->num_nodes);
  return 1;
#else
  (void)mesh;
  (void)error;
  (void)error_size;
  return 0;
#endif
}

#ifdef FAKE_CLASH
static const char* const kPassName = "smooth";
#else
static const char* const kPassName = "fake";
#endif
#endif

VM_PLUGIN_EXPORT uint32_t voronoimesh_plugin_abi_version(void) {
#ifdef FAKE_WRONG_ABI
  return VM_PLUGIN_ABI_VERSION + 1;
#else
  return VM_PLUGIN_ABI_VERSION;
#endif
}

#ifdef FAKE_NO_ENTRY
VM_PLUGIN_EXPORT int not_an_entry_point(void) { return 0; }
#else
VM_PLUGIN_EXPORT int voronoimesh_plugin_v1(const vm_plugin_host* host) {
  vm_pass_desc pass = {kPassName, "does nothing", NULL, 0, 1, 0, run, NULL};
  host->set_info(host->context, "fake", "0.0");
  return host->add_pass(host->context, &pass);
}
#endif
