/// @file sequence.cpp
/// Sequences of inputs for `voronoimesh mesh` (sequence.hpp).

#include "sequence.hpp"

#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;

namespace vmcli {

namespace {

/// The number conversion of `path`: %d, %Nd or %0Nd (as a regex of its parts),
/// fields of at most 3 digits (wider ones name no file a system can hold).
const std::regex kConversion(R"(%(0?\d{0,3})d)");

/// The most digits a step number may have: every such number fits a long.
constexpr size_t kLongestNumber = 18;

} // namespace

bool is_numbered(const std::string& path) {
  const auto begin = std::sregex_iterator(path.begin(), path.end(), kConversion);
  return std::distance(begin, std::sregex_iterator()) == 1 && std::count(path.begin(), path.end(), '%') == 1;
}

std::string numbered(const std::string& pattern, long number) {
  std::smatch m;
  std::regex_search(pattern, m, kConversion);
  // Padded as printf would (%04d: zeros, %4d: spaces), without a buffer whose size would cut a wide field.
  const std::string flags = m[1].str();
  std::string digits = std::to_string(number);
  const size_t width = flags.empty() || flags == "0" ? 0 : std::stoul(flags);
  if (digits.size() < width) digits.insert(0, width - digits.size(), flags[0] == '0' ? '0' : ' ');
  return m.prefix().str() + digits + m.suffix().str();
}

std::vector<Step> sequence_steps(const std::vector<std::string>& inputs) {
  std::vector<Step> steps;
  if (inputs.size() != 1 || !is_numbered(inputs[0])) {
    for (size_t i = 0; i < inputs.size(); ++i) steps.push_back({inputs[i], long(i)});
    return steps;
  }
  // The pattern's files: its folder's entries whose name is the pattern with digits for the number.
  const fs::path pattern(inputs[0]);
  const std::string name = pattern.filename().string();
  std::smatch m;
  std::regex_search(name, m, kConversion);
  auto escape = [](const std::string& s) { return std::regex_replace(s, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)"); };
  const std::regex file("^" + escape(m.prefix().str()) + R"((\d+))" + escape(m.suffix().str()) + "$");
  const fs::path folder = pattern.has_parent_path() ? pattern.parent_path() : fs::path(".");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string entry_name = entry.path().filename().string();
    std::smatch digits;
    if (!std::regex_match(entry_name, digits, file)) continue;
    if (digits[1].str().size() > kLongestNumber)
      throw vm::InvalidInput(entry_name + ": matches " + inputs[0] + " with a step number of " +
                             std::to_string(digits[1].str().size()) + " digits (at most " +
                             std::to_string(kLongestNumber) + "): rename it or move it out of the folder");
    const long number = std::stol(digits[1].str());
    // A padded pattern (%04d) names step 7 step_0007 only.
    if (numbered(name, number) != entry_name) continue;
    steps.push_back({(pattern.has_parent_path() ? (folder / entry_name).string() : entry_name), number});
  }
  if (steps.empty())
    throw vm::InvalidInput(inputs[0] + ": no file matches this numbered pattern" +
                           (ec ? " (" + folder.string() + ": " + ec.message() + ")" : std::string()));
  std::sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) { return a.number < b.number; });
  return steps;
}

std::string pvd_name(const std::string& pattern) {
  const fs::path p(pattern);
  std::string stem = std::regex_replace(p.stem().string(), kConversion, "");
  while (!stem.empty() && (stem.back() == '_' || stem.back() == '-' || stem.back() == '.')) stem.pop_back();
  if (stem.empty()) stem = "sequence";
  return (p.parent_path() / (stem + ".pvd")).string();
}

void write_pvd(const std::string& pvd, const std::vector<std::string>& meshes, const std::vector<double>& times) {
  const fs::path folder = fs::path(pvd).parent_path();
  const std::string temporary = pvd + ".partial";
  {
    std::ofstream out(temporary);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (size_t i = 0; i < meshes.size(); ++i)
      out << "    <DataSet timestep=\"" << times[i] << "\" group=\"\" part=\"0\" file=\""
          << fs::path(meshes[i]).lexically_relative(folder.empty() ? fs::path(".") : folder).string() << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    if (!out) throw vm::IoError(pvd + ": cannot write");
  }
  std::error_code ec;
  fs::rename(temporary, pvd, ec);
  if (ec) throw vm::IoError(pvd + ": cannot write (" + ec.message() + ")");
}

} // namespace vmcli
