#include "plugin/c_pass.hpp"

#include "core/text.hpp"
#include "mesh/node_rings.hpp"
#include "voronoimesh/core/errors.hpp"

#include <array>
#include <vector>

namespace vm::detail {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "vm_mesh_view hands Vec3 arrays over as packed doubles");
static_assert(sizeof(PhaseSet) == 8 * sizeof(int16_t), "vm_mesh_view hands phase sets over as 8 int16 each");

// The field callbacks: a C caller cannot catch, so failures become status codes.
int field_value(const void* field, int32_t phase, const double x[3], double* value) {
  try {
    const auto& f = *static_cast<const PhaseField*>(field);
    if (phase < 0 || phase >= f.num_phases()) return 1;
    *value = f.value(phase, Vec3(x[0], x[1], x[2]));
    return 0;
  } catch (...) {
    return 1;
  }
}

int field_gradient(const void* field, int32_t phase, const double x[3], double gradient[3]) {
  try {
    const auto& f = *static_cast<const PhaseField*>(field);
    if (phase < 0 || phase >= f.num_phases()) return 1;
    const Vec3 g = f.gradient(phase, Vec3(x[0], x[1], x[2]));
    for (int a = 0; a < 3; ++a) gradient[a] = g[a];
    return 0;
  } catch (...) {
    return 1;
  }
}

/// The arrays of vm_mesh_view the mesh does not hold in that form.
struct MeshArrays {
  std::vector<int32_t> order, neighbour_offsets, neighbours, triangles, pairs;

  explicit MeshArrays(const InterfaceMesh& m) {
    const size_t n = m.num_nodes();
    order.resize(n);
    neighbour_offsets.assign(1, 0);
    for (size_t v = 0; v < n; ++v) {
      order[v] = detail::constraint_order(m, int32_t(v)); // a closed mesh's outside phase adds no constraint
      for (int32_t w : m.neighbours(int32_t(v))) neighbours.push_back(w);
      neighbour_offsets.push_back(int32_t(neighbours.size()));
    }
    for (auto f : m.omesh().faces()) {
      for (int32_t v : m.face_nodes(f)) triangles.push_back(v);
      const PhasePair p = m.pair(f);
      pairs.push_back(p[0]);
      pairs.push_back(p[1]);
    }
  }
};

class CPass : public Pass {
public:
  CPass(const vm_pass_desc& desc, std::shared_ptr<void> library, std::string origin, std::string name,
        std::vector<double> params)
      : run_(desc.run), user_(desc.user), moves_(desc.moves_nodes != 0), library_(std::move(library)),
        origin_(std::move(origin)), name_(std::move(name)), params_(std::move(params)) {}

  void run(PassContext& c) override {
    const InterfaceMesh& m = c.mesh;
    if (m.num_nodes() == 0) return;
    const MeshArrays arrays(m);
    vm_mesh_view view{};
    view.num_nodes = m.num_nodes();
    view.positions = m.positions().empty() ? nullptr : m.positions().front().data();
    view.phases = m.phases().empty() ? nullptr : m.phases().front().data();
    view.box_faces = m.box_faces().data();
    view.junction_order = arrays.order.data();
    view.neighbour_offsets = arrays.neighbour_offsets.data();
    view.neighbours = arrays.neighbours.data();
    view.num_triangles = m.num_triangles();
    view.triangles = arrays.triangles.data();
    view.pairs = arrays.pairs.data();
    view.num_phases = int32_t(m.phase_names().size());
    for (int a = 0; a < 3; ++a) view.domain_min[a] = m.domain().min[a], view.domain_max[a] = m.domain().max[a];
    view.iteration = c.iteration;
    view.displacement = moves_ ? c.displacement().front().data() : nullptr;
    if (c.field) {
      view.num_phases = c.field->num_phases();
      view.field = c.field;
      view.field_value = field_value;
      view.field_gradient = field_gradient;
    }
    std::array<char, 512> error{};
    if (run_(user_, &view, params_.data(), error.data(), error.size()) != 0) {
      error.back() = 0;
      throw PluginError(
          located(origin_, "pass '" + name_ + "': " + (error[0] ? error.data() : "failed without a message")));
    }
    if (moves_) refuse_moves_not_finite(c.delta);
  }

private:
  /// The plugin is the one place a non-finite move can come from: refused here,
  /// naming the plugin and the pass, before anything uses it.
  void refuse_moves_not_finite(const std::vector<Vec3>& delta) const {
    for (size_t n = 0; n < delta.size(); ++n)
      if (!delta[n].allFinite())
        throw PluginError(located(origin_, cat("pass '", name_, "' moved node ", n, " by (", delta[n].x(), ", ",
                                               delta[n].y(), ", ", delta[n].z(), "), which is not a finite move")));
  }

  vm_pass_run run_;
  void* user_;
  bool moves_;
  std::shared_ptr<void> library_;
  std::string origin_;
  std::string name_;
  std::vector<double> params_;
};

std::string text(const char* s) { return s ? s : ""; }

} // namespace

PassInfo adapt_c_pass(const vm_pass_desc& desc, std::shared_ptr<void> library, const std::string& origin) {
  if (!desc.name || !*desc.name || !desc.summary || !desc.run || (desc.num_params && !desc.params))
    throw InvalidInput(located(origin, "a pass '" + text(desc.name) + "' without a name, summary or run function"));
  PassInfo info;
  info.name = desc.name;
  info.summary = desc.summary;
  info.moves_nodes = desc.moves_nodes != 0;
  info.needs_field = desc.needs_field != 0;
  for (size_t i = 0; i < desc.num_params; ++i) {
    const vm_param_spec& p = desc.params[i];
    if (!p.name || !*p.name) throw InvalidInput(located(origin, "pass '" + info.name + "': a parameter without a name"));
    info.params.push_back({p.name, p.default_value, p.min, p.max, p.integer != 0, text(p.help)});
  }
  // The C pass takes its values in declaration order; ParamValues is a map by name.
  const std::vector<ParamSpec> specs = info.params;
  info.make = [desc, library, origin, specs, name = info.name](const ParamValues& values) -> std::unique_ptr<Pass> {
    std::vector<double> ordered;
    for (const ParamSpec& s : specs) ordered.push_back(values.at(s.name));
    return std::make_unique<CPass>(desc, library, origin, name, std::move(ordered));
  };
  return info;
}

} // namespace vm::detail
