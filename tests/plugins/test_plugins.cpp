// Loading plugins: the passes they add, discovery through VORONOIMESH_PLUGIN_PATH,
// and the one-line refusals of files that are not plugins or speak another ABI.

#include "fixtures.hpp"
#include "scratch_dir.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/plugin/plugins.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>

namespace {

const std::string kRelax = std::string(VM_PLUGIN_BUILD_DIR) + "/relax.so";
const std::string kCvt = std::string(VM_PLUGIN_BUILD_DIR) + "/cvt.so";
std::string fake(const std::string& kind) { return std::string(VM_FAKE_PLUGIN_DIR) + "/fake_" + kind + ".so"; }

/// The message load_plugin throws for `path`, or "" if it loads.
std::string refusal(const std::string& path) {
  vm::PassRegistry registry = vm::builtin_registry();
  try {
    vm::load_plugin(path, registry);
  } catch (const vm::Error& e) {
    EXPECT_EQ(registry.all().size(), vm::builtin_registry().all().size()) << "a refused plugin left passes behind";
    return e.what();
  }
  return "";
}

/// Sets an environment variable for one scope.
struct ScopedEnv {
  ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { unsetenv(name_); }
  const char* name_;
};

} // namespace

TEST(Plugins, load_adds_the_passes_with_their_schema) {
  vm::PassRegistry registry = vm::builtin_registry();
  const vm::PluginRecord r = vm::load_plugin(kRelax, registry);
  EXPECT_EQ(r.name, "relax");
  EXPECT_EQ(r.version, "1.0");
  EXPECT_EQ(r.passes, std::vector<std::string>{"relax"});
  const vm::PassInfo& relax = registry.get("relax");
  EXPECT_TRUE(relax.moves_nodes);
  EXPECT_FALSE(relax.needs_field);
  ASSERT_EQ(relax.params.size(), 3u);
  EXPECT_EQ(relax.params[0].name, "lambda");
  EXPECT_DOUBLE_EQ(relax.params[1].default_value, -0.53);
  EXPECT_TRUE(relax.params[2].integer);
  // The schema checks plugin parameters like built-in ones.
  EXPECT_THROW(vm::Pipeline::parse("relax:mu=0.5", registry), vm::InvalidInput);
  EXPECT_NO_THROW(vm::Pipeline::parse("relax:lambda=0.3:junctions=0,project,clamp,flip", registry));
}

TEST(Plugins, discovered_in_the_plugin_path_and_listed) {
  ScopedEnv env("VORONOIMESH_PLUGIN_PATH", std::string("/nonexistent:") + VM_PLUGIN_BUILD_DIR);
  const auto dirs = vm::plugin_search_path();
  ASSERT_GE(dirs.size(), 3u);
  EXPECT_EQ(dirs[0], "/nonexistent");
  EXPECT_EQ(dirs[1], VM_PLUGIN_BUILD_DIR);
  EXPECT_EQ(dirs.back(), vm::installed_plugin_dir());

  vm::PassRegistry registry = vm::builtin_registry();
  const auto records = vm::load_plugins(registry, {});
  std::vector<std::string> loaded;
  for (const auto& r : records)
    if (r.refused.empty() && !r.shadowed) loaded.push_back(r.name + ":" + r.found_by);
  EXPECT_EQ(loaded, (std::vector<std::string>{"cvt:VORONOIMESH_PLUGIN_PATH", "relax:VORONOIMESH_PLUGIN_PATH"}));
  EXPECT_NO_THROW(registry.get("relax"));
  EXPECT_NO_THROW(registry.get("cvt"));
}

TEST(Plugins, the_same_plugin_found_twice_is_loaded_once) {
  ScopedEnv env("VORONOIMESH_PLUGIN_PATH", VM_PLUGIN_BUILD_DIR);
  vm::PassRegistry registry = vm::builtin_registry();
  const auto records = vm::load_plugins(registry, {kRelax});
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records[0].found_by, "--plugin");
  size_t shadowed = 0;
  for (const auto& r : records) {
    EXPECT_EQ(r.refused, "");
    shadowed += r.shadowed && r.name == "relax";
  }
  EXPECT_GE(shadowed, 1u);
}

TEST(Plugins, a_broken_plugin_in_a_folder_is_reported_not_thrown) {
  ScopedEnv env("VORONOIMESH_PLUGIN_PATH", VM_FAKE_PLUGIN_DIR);
  vm::PassRegistry registry = vm::builtin_registry();
  const auto records = vm::load_plugins(registry, {});
  size_t refused = 0;
  for (const auto& r : records) refused += !r.refused.empty();
  EXPECT_EQ(refused, 3u); // wrong ABI, no entry point, clash; the failing one loads
  EXPECT_NO_THROW(registry.get("fake"));
}

TEST(Plugins, refuses_a_wrong_abi_version) {
  EXPECT_EQ(refusal(fake("wrong_abi")),
            fake("wrong_abi") + ": built for plugin ABI version 2, but this voronoimesh loads version 1 only; "
                                "rebuild the plugin");
}

TEST(Plugins, refuses_a_shared_library_without_the_entry_point) {
  EXPECT_EQ(refusal(fake("no_entry")), fake("no_entry") + ": not a voronoimesh plugin: no voronoimesh_plugin_v1 entry point");
}

class PluginFiles : public vm::test::ScratchDir {};

TEST_F(PluginFiles, refuses_a_file_that_is_not_a_shared_library) {
  const std::string path = this->path("notes.so");
  std::ofstream(path) << "this is a text file\n";
  const std::string message = refusal(path);
  EXPECT_EQ(message.rfind(path + ": not a voronoimesh plugin: cannot load it as a shared library (", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(Plugins, refuses_a_missing_file) {
  EXPECT_EQ(refusal("/nonexistent/relax.so"), "/nonexistent/relax.so: cannot read the plugin: no such file");
}

TEST(Plugins, refuses_a_name_that_is_not_one_printable_line) {
  const std::string odd = std::string(VM_FAKE_PLUGIN_DIR) + "/refused/fake_odd_name.so";
  EXPECT_EQ(refusal(odd), odd + ": the plugin's name and version must be at most 64 printable characters, got "
                                "'fake\\x0aodd'");
}

TEST(Plugins, refuses_a_parameter_name_a_pipeline_cannot_give) {
  const std::string bad = std::string(VM_FAKE_PLUGIN_DIR) + "/refused/fake_bad_parameter.so";
  const std::string message = refusal(bad);
  EXPECT_NE(message.find("bad parameter name 'a:b'"), std::string::npos) << message;
}

TEST(Plugins, refuses_a_pass_name_that_exists) {
  EXPECT_EQ(refusal(fake("clash")),
            fake("clash") + ": plugin 'fake' cannot add its passes: a pass named 'smooth' is already registered");
}

/// The message of the PluginError the fake plugin `kind`'s pass throws in one iteration.
std::string plugin_error(const std::string& kind, const std::string& pass, size_t& nodes) {
  vm::PassRegistry registry = vm::builtin_registry();
  vm::load_plugin(fake(kind), registry);
  vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(vm::test::two_cubes(2));
  nodes = mesh.num_nodes();
  vm::RunOptions run;
  run.iterations = 1;
  try {
    vm::Pipeline::parse(pass, registry).run(mesh, nullptr, run);
  } catch (const vm::PluginError& e) {
    return e.what();
  }
  return "no PluginError";
}

TEST(Plugins, a_failing_pass_throws_its_message_naming_the_plugin) {
  size_t nodes = 0;
  const std::string message = plugin_error("failing", "fake", nodes);
  EXPECT_EQ(message, fake("failing") + ": pass 'fake': cannot relax " + std::to_string(nodes) + " nodes today");
}

TEST(Plugins, a_pass_writing_moves_that_are_not_finite_is_a_plugin_error) {
  size_t nodes = 0;
  const std::string message = plugin_error("nan", "nan_move", nodes);
  EXPECT_EQ(message.rfind(fake("nan") + ": pass 'nan_move' moved node 0 by (nan, ", 0), 0u) << message;
}

TEST(Plugins, passes_outlive_the_registry_that_loaded_them) {
  std::optional<vm::Pipeline> pipeline;
  {
    vm::PassRegistry registry = vm::builtin_registry();
    vm::load_plugin(kRelax, registry);
    pipeline = vm::Pipeline::parse("relax", registry);
  }
  vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(vm::test::two_cubes(2));
  vm::RunOptions run;
  run.iterations = 1;
  EXPECT_EQ(pipeline->run(mesh, nullptr, run), 1);
}
