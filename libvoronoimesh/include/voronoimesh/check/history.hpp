#pragma once
/// @file check/history.hpp
/// Per-iteration histograms of mesh quality and geometry (paper sect. 5, Fig. 7):
/// triangle inradius, circumradius, edge length, quality, angles and vertex
/// degree, recorded after each improvement iteration and written as CSV, JSON
/// or an SVG picture (one heat-map panel per measure).

#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace vm {

/// The measures of a QualityHistory, in panel order.
enum class Measure : int { inradius, circumradius, edge_length, quality, angle, degree };
/// Number of measures (of Measure values): one panel each.
inline constexpr int kNumMeasures = 6;

/// The fixed bins of one measure. Bin i is [lo[i], hi[i]); the last bin of a
/// measure with an overflow bin has hi = +infinity. Values are in the measure's
/// axis units: lengths relative to the RMS edge length of the initial mesh, q,
/// degrees, or vertex degree.
struct MeasureBins {
  const char* key;   ///< "inradius", "circumradius", "edge_length", "quality", "angle", "degree"
  const char* title; ///< panel title, e.g. "Triangle inradius"
  const char* unit;  ///< axis label, e.g. "x RMS edge length (initial)"
  /// Lower edge of each bin, in axis units.
  std::vector<double> lo, hi; ///< upper edge of each bin, in axis units (+infinity for an overflow bin)

  /// Number of bins.
  size_t size() const { return lo.size(); }
  /// The bin holding `value` (in axis units). Values below the range go to the
  /// first bin, above it (and non-finite ones) to the last; a value within a
  /// rounding error (1e-9 bin widths) below a bin edge counts in the bin above,
  /// so 60 degrees lands in [60, 65) and a length of exactly 1 x RMS in [1, 1.05).
  /// @param value the value, in axis units
  /// @return the index of its bin, in [0, size())
  size_t bin_of(double value) const;
};

/// The bins of measure `m`: inradius 50 bins of 0.02 over [0, 1], circumradius
/// and edge length 50 bins of 0.05 over [0, 2.5], each plus an overflow bin;
/// quality 40 bins over [0, 1]; angles 36 bins of 5 degrees over [0, 180];
/// degree one bin per integer 0..14 and a last bin "15 or more".
/// @param m the measure
/// @return its bins
const MeasureBins& measure_bins(Measure m);

/// Per-iteration histograms of mesh measures (paper Fig. 7). Features counted:
/// inradius, circumradius and quality once per triangle, angles three times per
/// triangle, edge lengths once per distinct node edge, degree (distinct
/// neighbouring nodes) once per node, including nodes no triangle uses (degree 0).
/// Triangles with out-of-range or repeated node ids are skipped.
class QualityHistory {
public:
  /// Records the mesh after iteration `iteration` (0 = the initial mesh).
  /// The first recorded mesh that has edges fixes the length scale (its RMS
  /// edge length), so later iterations are binned on the same axis.
  /// Iterations must increase from call to call.
  /// @param iteration the iteration just done, 0 for the initial mesh; greater than the last one recorded
  /// @param m         the mesh after it
  /// @throws InvalidInput if `iteration` is negative or not greater than the last one recorded
  void record(int iteration, const NodeMesh& m);

  /// Long format, one row per measure, iteration and bin:
  /// `measure,iteration,bin_lo,bin_hi,percent` (an overflow bin has bin_hi "inf").
  /// @param path the file to write
  /// @throws IoError as write()
  void write_csv(const std::string& path) const;
  /// {"length_scale", "iterations": [...], "measures": [{"key", "title", "unit",
  ///  "bin_lo", "bin_hi" (null for overflow), "total": [per iteration],
  ///  "count": [[per bin] per iteration], "percent": [[per bin] per iteration]}]}
  /// @param path the file to write
  /// @throws IoError as write()
  void write_json(const std::string& path) const;
  /// Six heat-map panels (2 x 3): x = iteration, y = bin, colour = percentage
  /// class, with axes, titles and a legend.
  /// @param path the file to write
  /// @throws IoError as write()
  void write_svg(const std::string& path) const;
  /// The format is chosen from the extension: .csv, .json, .svg (case-insensitive).
  ///
  /// Every writer writes to a temporary file beside `path` and renames it into
  /// place, so a failure leaves no file.
  /// @param path the file to write
  /// @throws InvalidInput for an extension other than .csv, .json and .svg
  /// @throws IoError      "<path>: cannot write (<reason>)" if the file cannot be written
  void write(const std::string& path) const;
  /// Checks, as write() would, that `path` has a known extension: lets a caller
  /// refuse a bad name before the work that precedes writing.
  /// @param path the file to be written
  /// @throws InvalidInput for an extension other than .csv, .json and .svg
  static void check_format(const std::string& path);

  /// The text write() writes to `path`: csv(), json() or svg() by its extension.
  /// @param path the file to be written
  /// @throws InvalidInput for an extension other than .csv, .json and .svg
  std::string text_for(const std::string& path) const;

  /// The text write_csv / write_json / write_svg would write.
  std::string csv() const;
  std::string json() const; ///< as csv(), JSON
  std::string svg() const;  ///< as csv(), the SVG picture

  /// Number of recorded iterations.
  size_t size() const { return iterations_.size(); }
  /// True before the first record().
  bool empty() const { return iterations_.empty(); }
  /// The recorded iteration numbers, in order.
  const std::vector<int>& iterations() const { return iterations_; }
  /// RMS edge length of the initial mesh (0 until a mesh with edges is recorded).
  double length_scale() const { return scale_; }
  /// Feature counts of record `r` (index into iterations()) per bin of `m`.
  /// @param r the record, in [0, size())
  /// @param m the measure
  const std::vector<size_t>& counts(size_t r, Measure m) const;
  /// Number of features of record `r` for measure `m`.
  /// @param r the record, in [0, size())
  /// @param m the measure
  size_t total(size_t r, Measure m) const;
  /// 100 * count / total per bin (all 0 when there are no features).
  /// @param r the record, in [0, size())
  /// @param m the measure
  std::vector<double> percent(size_t r, Measure m) const;

private:
  using Counts = std::array<std::vector<size_t>, kNumMeasures>;
  std::vector<int> iterations_;
  std::vector<Counts> counts_;
  double scale_ = 0;
};

} // namespace vm
