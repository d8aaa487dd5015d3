#include "commands.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/offsets.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <iostream>
#include <memory>
#include <optional>

namespace vmcli {

void add_stats_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string mesh;
    bool json = false;
    int worst = 0;
    int folds = 0;
    std::string field;
    InputCliOptions input;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "stats", "Counts (vertices, triangles, surfaces, triple curves, quadruple points), quality, and checks (topology, "
      "self-intersections) of a mesh; exit code 4 if a check fails.");
  cmd->add_option("mesh", o->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of text");
  // How many of something to list, N >= 0.
  auto add_listing = [cmd](const char* name, int& n, const char* help) {
    cmd->add_option(name, n, help)->check(CLI::Range(0, 1000000))->option_text("N");
  };
  add_listing("--worst", o->worst,
              "Also list the N triangles of lowest quality, worst first: their quality, smallest angle and "
              "phases, and what meets at each corner (a surface, a triple curve or a quadruple point, of which "
              "phases; whether on the box), and whether its smallest angle is a surface's whole corner at a "
              "junction point (which no remeshing keeping the point can beat), to see where and why a mesh "
              "loses quality");
  add_listing("--folds", o->folds,
              "Also list the N sharpest folds, sharpest first: surface edges across which the surface turns back "
              "by more than 150 degrees (two sheets laid onto each other, which no quality figure shows), with "
              "the turn, the phases, the two triangles, and what meets at each end of the edge");
  CLI::Option* field =
      cmd->add_option("--field", o->field,
                      std::string("Also measure how far the nodes lie from the interface of the input the mesh was "
                                  "made from: per surface, triple-curve and quadruple-point nodes the RMS and largest "
                                  "distance from where their phases are equal (a junction node's found by Newton's "
                                  "method within its box faces; those whose phases meet nowhere near are counted "
                                  "apart), in multiples of the spacing h of the grid the mesh was created on (from "
                                  "the PLY's grid_spacing comment; for a mesh without one, the input's default "
                                  "grid), and the farthest node. For a label volume and a closed mesh (mesh "
                                  "--close), also where the voxel centres lie: the share in a phase of their own "
                                  "label (all, and those whose 26 neighbours share it), the worst label and the "
                                  "labels with none in their phase. ") +
                          kInputHelp)
          ->option_text("INPUT");
  add_input_options(cmd, o->input, field);
  cmd->callback([o, &exit_code] {
    exit_code = run_guarded([&] {
      vm::NodeMesh mesh = vm::io::read_ply(o->mesh);
      // The input first: one the mesh was not made from is refused before any measuring.
      std::optional<vm::MeshOffsets> offsets;
      std::optional<vm::LabelAgreement> agreement;
      std::string not_located; // why a label volume's voxel centres were not located
      if (!o->field.empty()) {
        const vm::InputOptions options = input_options(o->input);
        const vm::Scene scene = vm::read_input(o->field, options);
        offsets = vm::offsets_from_input(mesh, o->mesh, scene, o->field);
        agreement = vm::label_agreement_from_input(mesh, scene, o->field, options);
        not_located = vm::voxel_centres_not_located(mesh, scene);
      }
      vm::MeshStats s = vm::compute_stats(mesh);
      vm::ValidationReport report = vm::validate(mesh);
      // Only a mesh whose topology is sound can be checked for crossings.
      if (report.ok()) s.self_intersections = vm::find_self_intersections(mesh, 0).count;
      const bool crossing = s.self_intersections.value_or(0) > 0;
      const std::vector<vm::WorstTriangle> worst = vm::worst_triangles(mesh, size_t(o->worst));
      const std::vector<vm::Fold> folds = vm::sharpest_folds(mesh, size_t(o->folds));
      if (o->json) {
        std::vector<std::pair<std::string, std::string>> more;
        if (offsets) more.emplace_back("offsets", vm::to_json(offsets->offsets, mesh, offsets->spacing));
        if (agreement) more.emplace_back("label_agreement", vm::to_json(*agreement));
        std::cout << vm::to_json(s, worst, &mesh, folds, more) << "\n";
      } else {
        std::cout << vm::to_text(s);
        std::cout << "topology               "
                  << (!report.ok() ? "INVALID" : crossing ? "INVALID (triangles intersect)" : "valid") << "\n";
        for (const auto& p : report.problems) std::cout << "  " << p << "\n";
        if (!worst.empty()) std::cout << "worst triangles\n" << vm::to_text(worst, mesh);
        if (!folds.empty()) std::cout << "sharpest folds\n" << vm::to_text(folds, mesh);
        if (offsets)
          std::cout << "offsets from the interface (h = " << offsets->spacing
                    << (offsets->spacing_from_mesh ? ", the spacing of the grid the mesh was created on"
                                                   : ", the input's default grid spacing: the mesh does not say its own")
                    << ")\n"
                    << vm::to_text(offsets->offsets, mesh, offsets->spacing);
        if (agreement) std::cout << vm::to_text(*agreement);
        if (!not_located.empty()) std::cout << not_located << "\n";
      }
      return report.ok() && !crossing ? kOk : kTopology;
    });
  });
}

} // namespace vmcli
