#pragma once
/// @file fields/phase_field.hpp
/// Phase functions: N scalar functions phi_0..phi_{N-1}; a point belongs to the
/// phase whose phi is largest (paper sect. 3, eq. 1-2).

#include "voronoimesh/core/types.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vm {

/// N phase functions that can be evaluated anywhere, with gradients.
/// Implementations must be safe to call from several threads at once.
class PhaseField {
public:
  virtual ~PhaseField() = default;

  /// Number of phases N (>= 2).
  virtual int num_phases() const = 0;
  /// Display name of phase `i` (the scene's "name", or "phase<i>").
  /// @param i a phase id, in [0, num_phases())
  virtual std::string phase_name(int i) const = 0;
  /// Phase `i` as messages name it: "phase <name>" unless the field knows where
  /// the phase comes from ("scene.json: phase sphere1").
  /// @param i a phase id, in [0, num_phases())
  virtual std::string describe_phase(int i) const;
  /// The id phase `i` shows in output files (a label volume's label value).
  /// Strictly increasing in i. Default: i itself.
  /// @param i a phase id, in [0, num_phases())
  virtual int32_t phase_label(int i) const { return i; }
  /// The display colour of phase `i`, when the input gives one (a 3D Slicer
  /// segment's colour). Default: none.
  /// @param i a phase id, in [0, num_phases())
  virtual std::optional<Rgb> phase_color([[maybe_unused]] int i) const { return std::nullopt; }
  /// phi_i(x) for every phase.
  /// @param x   the point
  /// @param out receives phi_i(x) in out[i]; `out.size() == num_phases()`
  virtual void values(const Vec3& x, std::span<double> out) const = 0;
  /// phi_i(x) of one phase.
  /// @param i a phase id, in [0, num_phases())
  /// @param x the point
  virtual double value(int i, const Vec3& x) const = 0;
  /// grad phi_i(x) of one phase.
  /// @param i a phase id, in [0, num_phases())
  /// @param x the point
  virtual Vec3 gradient(int i, const Vec3& x) const = 0;
  /// The `ids.size()` (<= num_phases()) largest phases at x and their values,
  /// largest first, lower id first among equal values: what SampledField keeps
  /// per grid node. If any phase's value is NaN or infinite, the first such
  /// phase is put in slot 0 instead, so callers can report it. The default
  /// evaluates every phase with values(); fields with many phases (label
  /// volumes, point clouds) override it so that it costs what k costs, not N.
  /// @param x    the point
  /// @param ids  receives the phase ids; its size is k, at most num_phases()
  /// @param vals receives their values, one per entry of `ids`
  virtual void top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const;
  /// True when top_values() gives the same ids and values at every point of
  /// the box [lo, hi], as in a region one phase fills alone: samplers then
  /// evaluate the box once (most lattice nodes of a label volume lie in such
  /// regions). False says nothing. The default: false.
  /// @param lo  the box's lower corner
  /// @param hi  its upper corner
  virtual bool same_top_values(const Vec3& lo, const Vec3& hi) const;

  /// Points that improvement must leave in their own phase (a voxel-faithful
  /// label volume's centres of voxels in thin structures: CrossingGuard::commit()
  /// undoes moves that carry one out): appends those in the box [lo, hi] to
  /// `out`. The default has none.
  /// @param lo  the box's lower corner
  /// @param hi  its upper corner
  /// @param out receives the points
  virtual void kept_points(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& out) const;
  /// The phase a kept point (from kept_points()) must stay in.
  /// @param p the point
  /// @return its phase
  virtual int32_t kept_phase(const Vec3& p) const;
  /// True when kept_points() has points to give.
  virtual bool keeps_points() const { return false; }
};

} // namespace vm
