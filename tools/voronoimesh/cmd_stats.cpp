#include "commands.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/io/ply.hpp"

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
      "stats", "Counts (vertices, triangles, surfaces, triple curves, quadruple points), quality, and checks (topology, "
      "self-intersections) of a mesh; exit code 4 if a check fails.");
  cmd->add_option("mesh", o->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of text");
  cmd->callback([o, &exit_code] {
    exit_code = run_guarded([&] {
      vm::NodeMesh mesh = vm::io::read_ply(o->mesh);
      vm::MeshStats s = vm::compute_stats(mesh);
      vm::ValidationReport report = vm::validate(mesh);
      // Only a mesh whose topology is sound can be checked for crossings.
      if (report.ok()) s.self_intersections = vm::find_self_intersections(mesh, 0).count;
      const bool crossing = s.self_intersections.value_or(0) > 0;
      if (o->json) {
        std::cout << vm::to_json(s) << "\n";
      } else {
        std::cout << vm::to_text(s);
        std::cout << "topology               "
                  << (!report.ok() ? "INVALID" : crossing ? "INVALID (triangles intersect)" : "valid") << "\n";
        for (const auto& p : report.problems) std::cout << "  " << p << "\n";
      }
      return report.ok() && !crossing ? kOk : kTopology;
    });
  });
}

} // namespace vmcli
