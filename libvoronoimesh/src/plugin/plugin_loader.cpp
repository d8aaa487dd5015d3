/// @file plugin/plugin_loader.cpp
/// Opens one plugin file with dlopen, checks it speaks our plugin ABI, calls its
/// entry point and adds its passes to a registry, all or none.

#include "core/text.hpp"
#include "plugin/c_pass.hpp"
#include "plugin/plugin_file.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/plugin/plugins.hpp"

#include <dlfcn.h>

#include <algorithm>

#include <filesystem>

namespace vm {
namespace detail {
namespace {

/// The last dlerror() without the file name it starts with (our message names it).
std::string dl_problem(const std::string& path) {
  const char* e = dlerror();
  std::string s = e ? e : "unknown reason";
  if (s.rfind(path + ": ", 0) == 0) s.erase(0, path.size() + 2);
  return s;
}

/// What the entry point tells the host, gathered without throwing: exceptions
/// must not unwind through the plugin's C frames.
struct Registration {
  std::shared_ptr<void> library;
  std::string origin;
  std::string name, version;
  std::vector<PassInfo> passes;
  std::string problem;
};

void set_info(void* context, const char* name, const char* version) {
  auto& r = *static_cast<Registration*>(context);
  r.name = name ? name : "";
  r.version = version ? version : "";
}

int add_pass(void* context, const vm_pass_desc* pass) {
  auto& r = *static_cast<Registration*>(context);
  try {
    if (!pass) throw InvalidInput(located(r.origin, "added a null pass"));
    r.passes.push_back(adapt_c_pass(*pass, r.library, r.origin));
    return 0;
  } catch (const std::exception& e) {
    if (r.problem.empty()) r.problem = e.what();
    return 1;
  }
}

} // namespace

OpenedPlugin open_plugin(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw IoError(located(path, "cannot read the plugin: no such file"));
  // An absolute path, so that dlopen never searches the library path instead.
  const std::string absolute = fs::absolute(path, ec).string();
  void* handle = dlopen(absolute.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    throw InvalidInput(located(path, "not a voronoimesh plugin: cannot load it as a shared library (" +
                                         dl_problem(absolute) + ")"));
  Registration r;
  r.library = std::shared_ptr<void>(handle, [](void* h) { dlclose(h); });
  r.origin = path;
  auto abi = reinterpret_cast<vm_plugin_abi_version_fn>(dlsym(handle, VM_PLUGIN_ABI_SYMBOL));
  auto entry = reinterpret_cast<vm_plugin_entry_v1_fn>(dlsym(handle, VM_PLUGIN_ENTRY_SYMBOL));
  if (!abi || !entry)
    throw InvalidInput(located(path, std::string("not a voronoimesh plugin: no ") +
                                         (abi ? VM_PLUGIN_ENTRY_SYMBOL : VM_PLUGIN_ABI_SYMBOL) + " entry point"));
  if (const uint32_t version = abi(); version != VM_PLUGIN_ABI_VERSION)
    throw InvalidInput(located(path, "built for plugin ABI version " + std::to_string(version) +
                                         ", but this voronoimesh loads version " +
                                         std::to_string(VM_PLUGIN_ABI_VERSION) + " only; rebuild the plugin"));
  const vm_plugin_host host{VM_PLUGIN_ABI_VERSION, VORONOIMESH_VERSION, &r, set_info, add_pass};
  const int status = entry(&host);
  if (!r.problem.empty()) throw InvalidInput(r.problem);
  if (status != 0)
    throw InvalidInput(located(path, "the plugin refused to load (its entry point returned " + std::to_string(status) + ")"));
  if (r.name.empty()) r.name = fs::path(path).stem().string();
  // Names are printed in listings and messages: one line of printable text.
  for (const std::string* text : {&r.name, &r.version})
    if (text->size() > 64 || std::any_of(text->begin(), text->end(), [](char c) { return c < 0x20 || c == 0x7f; }))
      throw InvalidInput(located(path, "the plugin's name and version must be at most 64 printable characters, got " +
                                           vm::detail::quote(*text)));
  return {std::move(r.name), std::move(r.version), std::move(r.passes)};
}

void add_plugin_passes(const OpenedPlugin& plugin, const std::string& path, PassRegistry& registry,
                       PluginRecord& record) {
  PassRegistry trial = registry; // all or none: a clash leaves `registry` as it was
  for (const PassInfo& p : plugin.passes) {
    try {
      trial.add(p);
    } catch (const InvalidInput& e) {
      std::string why = e.what();
      if (const std::string registry_prefix = "pass registry: "; why.rfind(registry_prefix, 0) == 0)
        why.erase(0, registry_prefix.size());
      throw InvalidInput(located(path, "plugin '" + plugin.name + "' cannot add its passes: " + why));
    }
    record.passes.push_back(p.name);
  }
  registry = std::move(trial);
  record.name = plugin.name;
  record.version = plugin.version;
}

} // namespace detail

PluginRecord load_plugin(const std::string& path, PassRegistry& registry) {
  PluginRecord record;
  record.file = path;
  detail::add_plugin_passes(detail::open_plugin(path), path, registry, record);
  return record;
}

} // namespace vm
