#include "voronoimesh/improve/registry.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace vm {

namespace {

/// True when `name` is a pipeline word: a-z, 0-9, _ and - (a pipeline string
/// splits at ',', ':' and '=', and names are shown in one-line messages).
bool is_pipeline_word(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

} // namespace

void PassRegistry::add(PassInfo info) {
  if (!is_pipeline_word(info.name))
    throw InvalidInput(located("pass registry", "bad pass name " + detail::quote(info.name) +
                                                    " (use a-z, 0-9, _ and -, at most 64 of them)"));
  if (std::any_of(passes_.begin(), passes_.end(), [&](const PassInfo& p) { return p.name == info.name; }))
    throw InvalidInput(located("pass registry", "a pass named '" + info.name + "' is already registered"));
  for (size_t i = 0; i < info.params.size(); ++i) {
    const ParamSpec& s = info.params[i];
    if (!is_pipeline_word(s.name))
      throw InvalidInput(located("pass registry", "pass '" + info.name + "': bad parameter name " +
                                                      detail::quote(s.name) + " (use a-z, 0-9, _ and -)"));
    for (size_t j = 0; j < i; ++j)
      if (info.params[j].name == s.name)
        throw InvalidInput(located("pass registry", "pass '" + info.name + "': parameter '" + s.name + "' twice"));
    if (!(s.min <= s.default_value && s.default_value <= s.max))
      throw InvalidInput(located("pass registry", "pass '" + info.name + "': default of " + s.name + " out of range"));
  }
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
