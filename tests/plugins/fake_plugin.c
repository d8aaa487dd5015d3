/* Broken plugins for the refusal tests, one per compile definition:
 *   FAKE_WRONG_ABI   claims a future plugin ABI version
 *   FAKE_NO_ENTRY    a shared library without the entry point
 *   FAKE_CLASH       registers a pass named "smooth", which is built in
 *   FAKE_FAILING     a good plugin whose pass fails at run time
 *   FAKE_NAN         a moving pass whose first move is not a number
 *   FAKE_ODD_NAME    names itself with a line break in its name
 *   FAKE_BAD_PARAMETER a pass whose parameter's name holds a ':', which pipelines split at
 * Written in C: the boundary must work for plugins in plain C. */
#include "voronoimesh/plugin/plugin_abi.h"

#include <math.h>
#include <stdio.h>

#ifndef FAKE_NO_ENTRY
static int run(void* user, const vm_mesh_view* mesh, const double* params, char* error, size_t error_size) {
  (void)user;
  (void)params;
#ifdef FAKE_FAILING
  snprintf(error, error_size, "cannot relax %zu nodes today", mesh->num_nodes);
  return 1;
#elif defined(FAKE_NAN)
  (void)error;
  (void)error_size;
  mesh->displacement[0] = NAN;
  return 0;
#else
  (void)mesh;
  (void)error;
  (void)error_size;
  return 0;
#endif
}

#ifdef FAKE_CLASH
static const char* const kPassName = "smooth";
#elif defined(FAKE_NAN)
static const char* const kPassName = "nan_move";
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
#ifdef FAKE_NAN
  vm_pass_desc pass = {kPassName, "moves the first node nowhere", NULL, 0, 1, 0, run, NULL};
#elif defined(FAKE_BAD_PARAMETER)
  static const vm_param_spec params[] = {{"a:b", 1.0, 0.0, 2.0, 0, "a name a pipeline cannot give"}};
  vm_pass_desc pass = {kPassName, "has a parameter no pipeline can name", params, 1, 1, 0, run, NULL};
#else
  vm_pass_desc pass = {kPassName, "does nothing", NULL, 0, 1, 0, run, NULL};
#endif
#ifdef FAKE_NAN
  host->set_info(host->context, "fake_nan", "0.0");
#elif defined(FAKE_ODD_NAME)
  host->set_info(host->context, "fake\nodd", "0.0");
#else
  host->set_info(host->context, "fake", "0.0");
#endif
  return host->add_pass(host->context, &pass);
}
#endif
