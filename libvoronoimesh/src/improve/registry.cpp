#include "voronoimesh/improve/registry.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace vm {

void PassRegistry::add(PassInfo info) {
  const bool name_ok = !info.name.empty() && std::all_of(info.name.begin(), info.name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  if (!name_ok) throw InvalidInput(located("pass registry", "bad pass name '" + info.name + "' (use a-z, 0-9, _ and -)"));
  if (std::any_of(passes_.begin(), passes_.end(), [&](const PassInfo& p) { return p.name == info.name; }))
    throw InvalidInput(located("pass registry", "a pass named '" + info.name + "' is already registered"));
  for (const ParamSpec& s : info.params)
    if (!(s.min <= s.default_value && s.default_value <= s.max))
      throw InvalidInput(located("pass registry", "pass '" + info.name + "': default of " + s.name + " out of range"));
  passes_.push_back(std::move(info));
}

const PassInfo& PassRegistry::get(const std::string& name) const {
  for (const PassInfo& p : passes_)
    if (p.name == name) return p;
  std::string known;
  for (const PassInfo* p : all()) {
    if (!known.empty()) known += ", ";
    known += p->name;
  }
  throw InvalidInput(located("pipeline", "unknown pass '" + name + "' (known: " + known + ")"));
}

std::vector<const PassInfo*> PassRegistry::all() const {
  std::vector<const PassInfo*> out;
  for (const PassInfo& p : passes_) out.push_back(&p);
  std::sort(out.begin(), out.end(), [](const PassInfo* a, const PassInfo* b) { return a->name < b->name; });
  return out;
}

ParamValues PassRegistry::resolve(const std::string& pass, const ParamValues& given) const {
  const PassInfo& info = get(pass);
  ParamValues out;
  for (const ParamSpec& s : info.params) out[s.name] = s.default_value;
  for (const auto& [name, value] : given) {
    // &name = name: clang 14 (the fuzz build) cannot capture a structured binding.
    auto spec = std::find_if(info.params.begin(), info.params.end(), [&name = name](const ParamSpec& s) { return s.name == name; });
    if (spec == info.params.end()) {
      std::string known;
      for (const ParamSpec& s : info.params) {
        if (!known.empty()) known += ", ";
        known += s.name;
      }
      throw InvalidInput(located("pipeline", "pass '" + pass + "' has no parameter '" + name + "' (it has: " +
                                                 (known.empty() ? "none" : known) + ")"));
    }
    if (!(value >= spec->min && value <= spec->max) || (spec->integer && value != std::floor(value)))
      throw InvalidInput(located("pipeline", detail::cat(pass, ".", name, " = ", value, ": must be ",
                                                         spec->integer ? "an integer " : "", "in [", spec->min, ", ",
                                                         spec->max, "]")));
    out[name] = value;
  }
  return out;
}

PassRegistry builtin_registry() {
  PassRegistry r;
  register_builtin_passes(r);
  return r;
}

} // namespace vm
