#include "fields/phase_reader.hpp"

#include "fields/expr_phase.hpp"
#include "fields/geometric_phases.hpp"

#include <array>
#include <string_view>

namespace vm::detail {

namespace {

using Phase = std::unique_ptr<const PhaseFunction>;

Phase read_constant(const JsonObject& o, const PhaseContext&) {
  o.allow_only({"kind", "name", "value"});
  return std::make_unique<ConstantPhase>(o.number("value"));
}

Phase read_sphere(const JsonObject& o, const PhaseContext&) {
  o.allow_only({"kind", "name", "center", "radius"});
  const double r = o.number("radius");
  if (r < 0) o.fail("'radius' must not be negative, got " + brief(o.at("radius")));
  return std::make_unique<SpherePhase>(o.vec3("center"), r);
}

Phase read_seeds(const JsonObject& o, const PhaseContext&) {
  o.allow_only({"kind", "name", "points"});
  const auto& list = o.at("points");
  if (!list.is_array()) o.fail("'points' must be an array of points [x, y, z]");
  if (list.empty()) o.fail("'points' is empty; a seeds phase needs at least one point");
  std::vector<Vec3> points;
  points.reserve(list.size());
  for (size_t i = 0; i < list.size(); ++i)
    points.push_back(o.as_vec3(list[i], "points[" + std::to_string(i) + "]"));
  return std::make_unique<SeedsPhase>(std::move(points));
}

Phase read_plane(const JsonObject& o, const PhaseContext&) {
  o.allow_only({"kind", "name", "point", "normal"});
  const Vec3 normal = o.vec3("normal");
  if (normal.squaredNorm() == 0) o.fail("'normal' must not be the zero vector");
  return std::make_unique<PlanePhase>(o.vec3("point"), normal);
}

Phase read_expr(const JsonObject& o, const PhaseContext& context) {
  o.allow_only({"kind", "name", "expr", "constants", "gradient"});
  ExprSpec spec;
  spec.value = o.string("expr");
  // Relative to the domain so the step suits any scale; 1e-6 balances the
  // truncation error (step^2) against rounding (1e-16 / step).
  spec.step = 1e-6 * (context.domain.max - context.domain.min).norm();
  if (o.has("constants")) {
    const JsonObject constants = o.object("constants");
    for (const auto& item : constants.json().items())
      spec.constants.emplace_back(item.key(), constants.as_number(item.value(), item.key()));
  }
  if (o.has("gradient")) {
    const auto& g = o.at("gradient");
    if (!g.is_array() || g.size() != 3 || !(g[0].is_string() && g[1].is_string() && g[2].is_string()))
      o.fail("'gradient' must be an array of 3 expression strings, got " + brief(g));
    for (const auto& s : g) spec.gradient.push_back(s.get<std::string>());
  }
  try {
    return std::make_unique<ExprPhase>(std::move(spec));
  } catch (const ExprError& e) {
    o.fail(e.what());
  }
}

Phase read_grid(const JsonObject& o, const PhaseContext& context) { return context.grids.read_phase(o); }

struct Kind {
  std::string_view name;
  Phase (*read)(const JsonObject&, const PhaseContext&);
};

constexpr std::array<Kind, 6> kinds{{{"constant", read_constant},
                                     {"sphere", read_sphere},
                                     {"seeds", read_seeds},
                                     {"plane", read_plane},
                                     {"expr", read_expr},
                                     {"grid", read_grid}}};

} // namespace

std::unique_ptr<const PhaseFunction> read_phase(const JsonObject& phase, const PhaseContext& context) {
  const std::string kind = phase.string("kind");
  std::string expected;
  for (const Kind& k : kinds) {
    if (k.name == kind) return k.read(phase, context);
    expected += (expected.empty() ? "" : ", ") + std::string(k.name);
  }
  phase.fail("unknown kind '" + kind + "' (expected " + expected + ")");
}

} // namespace vm::detail
