#include "fields/expr_phase.hpp"

#include "core/text.hpp"

#include <muParser.h>

#include <array>
#include <numbers>

namespace vm::detail {

/// One thread's compiled formulas. Heap-allocated and never moved, because the
/// parsers hold the address of `at`.
struct ExprPhase::Evaluator {
  std::array<double, 3> at{0, 0, 0}; ///< the point x, y, z the parsers read
  mu::Parser value;
  std::array<mu::Parser, 3> gradient; ///< compiled only when the spec has a gradient

  double eval(const mu::Parser& p, const Vec3& x) {
    at = {x.x(), x.y(), x.z()};
    return p.Eval();
  }
};

namespace {

/// Binds the variables and constants and compiles `formula`, so that a later
/// Eval() cannot fail to parse. `label` names the formula in errors.
void compile(mu::Parser& p, std::array<double, 3>& at, const ExprSpec& spec,
             const std::string& formula, const std::string& label) {
  try {
    p.DefineVar("x", &at[0]);
    p.DefineVar("y", &at[1]);
    p.DefineVar("z", &at[2]);
    p.DefineConst("pi", std::numbers::pi);
    for (const auto& [name, v] : spec.constants) {
      // muparser would let a constant silently shadow a coordinate.
      if (name == "x" || name == "y" || name == "z")
        throw ExprError("constant " + quote(name) + " would hide the coordinate " + name);
      p.DefineConst(name, v);
    }
    p.SetExpr(formula);
    int results = 0;
    p.Eval(results); // parses on first use
    if (results != 1)
      throw ExprError(label + " " + quote(formula) + " gives " + std::to_string(results) +
                      " comma-separated values, expected one");
  } catch (const mu::Parser::exception_type& e) {
    // muparser's message quotes the token at fault, which may be most of a long formula.
    const std::string why = e.GetMsg();
    throw ExprError("bad " + label + " " + quote(formula) + ": " +
                    (why.size() <= 160 ? why : why.substr(0, 157) + "..."));
  }
}

} // namespace

ExprPhase::ExprPhase(ExprSpec spec)
    : spec_(std::move(spec)), evaluators_([this] { return make_evaluator(); }) {
  make_evaluator(); // validation only; threads build their own on first use
}

ExprPhase::~ExprPhase() = default;

std::unique_ptr<ExprPhase::Evaluator> ExprPhase::make_evaluator() const {
  auto e = std::make_unique<Evaluator>();
  compile(e->value, e->at, spec_, spec_.value, "expr");
  for (size_t i = 0; i < spec_.gradient.size(); ++i)
    compile(e->gradient[i], e->at, spec_, spec_.gradient[i],
            "gradient[" + std::to_string(i) + "]");
  return e;
}

double ExprPhase::value(const Vec3& x) const {
  Evaluator& e = *evaluators_.local();
  return e.eval(e.value, x);
}

Vec3 ExprPhase::gradient(const Vec3& x) const {
  Evaluator& e = *evaluators_.local();
  Vec3 g;
  if (!spec_.gradient.empty()) {
    for (int a = 0; a < 3; ++a) g[a] = e.eval(e.gradient[a], x);
    return g;
  }
  for (int a = 0; a < 3; ++a) {
    Vec3 hi = x, lo = x;
    hi[a] += spec_.step;
    lo[a] -= spec_.step;
    // Divide by the step actually taken, which rounding makes differ from 2*step.
    g[a] = (e.eval(e.value, hi) - e.eval(e.value, lo)) / (hi[a] - lo[a]);
  }
  return g;
}

} // namespace vm::detail
