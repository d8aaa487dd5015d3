#include "voronoimesh/fields/outside_phase.hpp"

#include "voronoimesh/core/errors.hpp"
#include "core/text.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace vm {
namespace {

/// Signed distance to the box (positive outside) and its gradient.
double signed_distance(const Box& box, const Vec3& x, Vec3* gradient) {
  const Vec3 below = box.min - x, above = x - box.max;
  const Vec3 excess = below.cwiseMax(above); // per axis: > 0 outside that slab
  if ((excess.array() > 0).any()) {
    const Vec3 out = excess.cwiseMax(0.0);
    const double d = out.norm();
    if (gradient)
      for (int a = 0; a < 3; ++a) (*gradient)[a] = out[a] > 0 ? (above[a] > 0 ? 1 : -1) * out[a] / d : 0;
    return d;
  }
  // Inside: minus the distance to the nearest face (lowest axis, min side first on ties).
  int axis = 0;
  excess.maxCoeff(&axis);
  if (gradient) {
    gradient->setZero();
    (*gradient)[axis] = above[axis] > below[axis] ? 1 : -1;
  }
  return excess[axis];
}

class OutsidePhaseField : public PhaseField {
public:
  OutsidePhaseField(std::shared_ptr<const PhaseField> inner, const Box& box)
      : inner_(std::move(inner)), box_(box), n_(inner_->num_phases()), label_(outside_phase_label(*inner_)) {}

  int num_phases() const override { return n_ + 1; }
  std::string phase_name(int i) const override { return i == n_ ? kOutsidePhaseName : inner_->phase_name(i); }
  std::string describe_phase(int i) const override {
    return i == n_ ? "the phase outside the domain box" : inner_->describe_phase(i);
  }
  int32_t phase_label(int i) const override { return i == n_ ? label_ : inner_->phase_label(i); }
  std::optional<Rgb> phase_color(int i) const override { return i == n_ ? std::nullopt : inner_->phase_color(i); }

  void values(const Vec3& x, std::span<double> out) const override {
    inner_->values(x, out.first(size_t(n_)));
    out[size_t(n_)] = top(x) + signed_distance(box_, x, nullptr);
  }
  double value(int i, const Vec3& x) const override {
    return i == n_ ? top(x) + signed_distance(box_, x, nullptr) : inner_->value(i, x);
  }
  Vec3 gradient(int i, const Vec3& x) const override {
    if (i != n_) return inner_->gradient(i, x);
    std::array<int32_t, 1> id;
    std::array<double, 1> v;
    inner_->top_values(x, id, v);
    Vec3 g;
    signed_distance(box_, x, &g);
    return inner_->gradient(id[0], x) + g;
  }

  void kept_points(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& out) const override {
    inner_->kept_points(lo, hi, out);
  }
  int32_t kept_phase(const Vec3& p) const override { return inner_->kept_phase(p); }
  bool keeps_points() const override { return inner_->keeps_points(); }

private:
  double top(const Vec3& x) const {
    std::array<int32_t, 1> id;
    std::array<double, 1> v;
    inner_->top_values(x, id, v);
    return v[0];
  }

  std::shared_ptr<const PhaseField> inner_;
  Box box_;
  int n_;
  int32_t label_;
};

} // namespace

int32_t outside_phase_label(const PhaseField& field) {
  int32_t largest = 0; // of no phases: 0, the outside phase's label when it is the only one
  for (int p = 0; p < field.num_phases(); ++p) {
    const int32_t label = field.phase_label(p);
    if (label == std::numeric_limits<int32_t>::max())
      throw InvalidOption("close", detail::cat("the phase outside the box takes the label above every phase's, and ",
                                               detail::quote(field.phase_name(p)), " has label ", label,
                                               ", the largest a 32-bit label can be: give it another to close the "
                                               "domain (in a label volume, --merge-labels or --drop-labels)"));
    largest = p == 0 ? label : std::max(largest, label);
  }
  return field.num_phases() > 0 ? largest + 1 : 0;
}

std::shared_ptr<const PhaseField> with_outside_phase(std::shared_ptr<const PhaseField> field, const Box& box) {
  return std::make_shared<OutsidePhaseField>(std::move(field), box);
}

std::shared_ptr<const PhaseField> phases_of_mesh(const NodeMesh& mesh, std::shared_ptr<const PhaseField> field) {
  return mesh.outside_phase >= 0 ? with_outside_phase(std::move(field), mesh.domain) : field;
}

} // namespace vm
