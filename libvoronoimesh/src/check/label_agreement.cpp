/// @file check/label_agreement.cpp
/// Voxel centres located in a closed mesh and compared with their labels (check/label_agreement.hpp).

#include "voronoimesh/check/label_agreement.hpp"

#include "voronoimesh/check/locate.hpp"
#include "voronoimesh/core/errors.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace vm {

namespace {

/// How far inside the box the outer layer's centres are located, in spacings.
constexpr double kInside = 1e-3;

/// `centres` with those on a face of `box` drawn in by kInside spacings: the
/// outer layer of a volume's voxel centres lies on the box faces of a mesh made
/// from it (on the faces of the low side at least: a grid of an odd number of
/// cells gets one voxel more on the high side), where no ray tells the phase
/// from the outside; a hair inside, it lies in the phase that meets the face
/// there. The points between move by less (the rays pass 5e-4 to 7e-4 spacings
/// beside them).
PointGrid inside_the_box(PointGrid centres, const Box& box) {
  for (int a = 0; a < 3; ++a) {
    const int64_t n = centres.size[size_t(a)];
    const double step = centres.spacing[a], touching = 1e-9 * step;
    double first = centres.origin[a], last = first + step * double(std::max<int64_t>(n - 1, 0));
    if (std::abs(first - box.min[a]) <= touching) first += kInside * step;
    if (std::abs(last - box.max[a]) <= touching) last -= kInside * step;
    centres.origin[a] = first;
    if (n > 1) centres.spacing[a] = (last - first) / double(n - 1);
  }
  return centres;
}

double percent(int64_t part, int64_t whole) { return whole > 0 ? 100.0 * double(part) / double(whole) : 100.0; }

} // namespace

LabelAgreement label_agreement(const NodeMesh& closed, const PointGrid& centres, std::span<const int32_t> labels,
                               int margin) {
  if (closed.outside_phase < 0)
    throw InvalidInput(
        "label agreement: the mesh is not closed (made with --close), so its voxel centres cannot be located");
  const int64_t nx = centres.size[0], ny = centres.size[1], nz = centres.size[2];
  if (nx < 0 || ny < 0 || nz < 0 || int64_t(labels.size()) != nx * ny * nz)
    throw InvalidInput("label agreement: the labels do not fit the grid of voxel centres");
  if (margin < 0) throw InvalidInput("label agreement: the margin must be 0 or more voxels");
  const std::vector<int32_t> located = locate_grid_points(closed, inside_the_box(centres, closed.domain));
  auto label_at = [&](int64_t i, int64_t j, int64_t k) { return labels[size_t(i + nx * (j + ny * k))]; };
  LabelAgreement a;
  std::map<int32_t, LabelAgreement::Label> by_label;
  for (int64_t k = 0; k < nz; ++k)
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const int32_t label = label_at(i, j, k), phase = located[size_t(i + nx * (j + ny * k))];
        if (phase < 0) {
          ++a.undecided;
          continue;
        }
        const bool agrees = phase != closed.outside_phase && closed.label_of(phase) == label;
        // Neighbours beyond the volume are taken from its edge.
        bool uniform = true;
        for (int64_t dk = -margin; dk <= margin && uniform; ++dk)
          for (int64_t dj = -margin; dj <= margin && uniform; ++dj)
            for (int64_t di = -margin; di <= margin && uniform; ++di)
              uniform = label_at(std::clamp(i + di, int64_t(0), nx - 1), std::clamp(j + dj, int64_t(0), ny - 1),
                                 std::clamp(k + dk, int64_t(0), nz - 1)) == label;
        LabelAgreement::Label& l = by_label[label];
        l.label = label;
        ++l.voxels, l.in_phase += agrees;
        ++a.voxels, a.in_phase += agrees;
        if (uniform) ++a.interior, a.interior_in_phase += agrees;
      }
  for (const auto& [label, l] : by_label) a.labels.push_back(l);
  return a;
}

const LabelAgreement::Label* LabelAgreement::worst() const {
  const Label* worst = nullptr;
  for (const Label& l : labels)
    if (!worst || percent(l.in_phase, l.voxels) < percent(worst->in_phase, worst->voxels)) worst = &l;
  return worst;
}

std::vector<int32_t> LabelAgreement::lost() const {
  std::vector<int32_t> none;
  for (const Label& l : labels)
    if (l.in_phase == 0) none.push_back(l.label);
  return none;
}

std::string to_text(const LabelAgreement& a) {
  const LabelAgreement::Label* worst = a.worst();
  std::string none;
  for (int32_t label : a.lost()) none += (none.empty() ? "" : ", ") + std::to_string(label);
  if (a.voxels == 0) return "voxel centres: none located, " + std::to_string(a.undecided) + " undecided\n";
  char line[320];
  std::snprintf(line, sizeof line,
                "voxel centres in their label's phase: %.3f%% of %lld (interior ones %.3f%%), %lld undecided\n",
                percent(a.in_phase, a.voxels), (long long)a.voxels, percent(a.interior_in_phase, a.interior),
                (long long)a.undecided);
  std::string text = line;
  if (worst) {
    std::snprintf(line, sizeof line, "  worst label %d: %.3f%% of its %lld voxel centres\n", worst->label,
                  percent(worst->in_phase, worst->voxels), (long long)worst->voxels);
    text += line;
  }
  text += "  labels with none in their phase: " + (none.empty() ? std::string("none") : none) + "\n";
  return text;
}

std::string to_json(const LabelAgreement& a) {
  nlohmann::ordered_json labels = nlohmann::ordered_json::array();
  for (const LabelAgreement::Label& l : a.labels)
    labels.push_back({{"label", l.label}, {"voxels", l.voxels}, {"in_phase", l.in_phase}});
  const nlohmann::ordered_json j = {{"voxels", a.voxels},
                                    {"in_phase", a.in_phase},
                                    {"interior", a.interior},
                                    {"interior_in_phase", a.interior_in_phase},
                                    {"undecided", a.undecided},
                                    {"labels", labels}};
  return j.dump();
}

} // namespace vm
