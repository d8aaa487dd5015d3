#include "commands.hpp"

#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/stats.hpp"
#include "voronoimesh/validate.hpp"

#include <iostream>
#include <memory>

namespace vmcli {

void add_stats_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string mesh;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "stats", "Counts (vertices, triangles, surfaces, triple curves, quadruple points) and quality of a mesh.");
  cmd->add_option("mesh", o->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of text");
  cmd->callback([o, &exit_code] {
    exit_code = run_guarded([&] {
      vm::NodeMesh mesh = vm::io::read_ply(o->mesh);
      vm::MeshStats s = vm::compute_stats(mesh);
      vm::ValidationReport report = vm::validate(mesh);
      if (o->json) {
        std::cout << vm::to_json(s) << "\n";
      } else {
        std::cout << vm::to_text(s);
        std::cout << "topology:          " << (report.ok() ? "valid" : "INVALID") << "\n";
        for (const auto& p : report.problems) std::cout << "  " << p << "\n";
      }
      return report.ok() ? kOk : kTopology;
    });
  });
}

} // namespace vmcli
