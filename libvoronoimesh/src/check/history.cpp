/// @file check/history.cpp
/// QualityHistory: per-iteration histograms of mesh measures and their CSV,
/// JSON and SVG forms (check/history.hpp).

#include "voronoimesh/check/history.hpp"

#include "core/staged_outputs.hpp"
#include "core/text.hpp"
#include "mesh/angle.hpp"
#include "mesh/topology.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/core/errors.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>

namespace vm {

namespace {

using detail::angle_deg;

using detail::cat;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// `n` bins of width `w` from 0, plus an overflow bin [n w, inf) if `overflow`.
MeasureBins uniform_bins(const char* key, const char* title, const char* unit, int n, double w, bool overflow) {
  MeasureBins b{key, title, unit, {}, {}};
  for (int i = 0; i < n; ++i) {
    b.lo.push_back(i * w);
    b.hi.push_back((i + 1) * w);
  }
  if (overflow) {
    b.lo.push_back(n * w);
    b.hi.push_back(kInf);
  }
  return b;
}

const char* const kLengthUnit = "x RMS edge length (initial)";

const std::array<MeasureBins, kNumMeasures>& all_bins() {
  static const std::array<MeasureBins, kNumMeasures> bins{
      uniform_bins("inradius", "Triangle inradius", kLengthUnit, 50, 0.02, true),
      uniform_bins("circumradius", "Triangle circumradius", kLengthUnit, 50, 0.05, true),
      uniform_bins("edge_length", "Edge length", kLengthUnit, 50, 0.05, true),
      uniform_bins("quality", "Triangle quality", "q", 40, 1.0 / 40, false),
      uniform_bins("angle", "Triangle angles", "degrees", 36, 5.0, false),
      uniform_bins("degree", "Vertex degree", "degree", 15, 1.0, true),
  };
  return bins;
}

std::string lower_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// ---------------------------------------------------------------------------
// SVG drawing

/// Number as SVG attribute or label text: at most `digits` significant digits.
std::string num(double v, int digits = 6) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// Discrete colour classes of the percentage legend (0 = white is not drawn).
struct ColourClass {
  double below; ///< upper bound (exclusive) of the class, in percent
  const char* colour;
  const char* label;
};
constexpr std::array<ColourClass, 6> kClasses{{
    {0.1, "#fff7bc", "&lt; 0.1%"},
    {1, "#fec44f", "0.1\u20131%"},
    {5, "#fb8b24", "1\u20135%"},
    {20, "#e34a33", "5\u201320%"},
    {50, "#a50f45", "20\u201350%"},
    {kInf, "#3b0a45", "\u2265 50%"},
}};

const char* colour_of(double percent) {
  for (const ColourClass& c : kClasses)
    if (percent < c.below) return c.colour;
  return kClasses.back().colour;
}

/// How a measure's y axis is labelled: every `every` bins, at bin edges (a
/// continuous measure) or at bin centres (an integer one).
struct YTicks {
  int every;
  bool centred;
};
YTicks y_ticks(Measure m) {
  switch (m) {
  case Measure::quality: return {10, false};
  case Measure::angle: return {6, false};
  case Measure::degree: return {1, true};
  default: return {10, false};
  }
}

/// A "nice" tick step (1, 2 or 5 times a power of ten) giving at most ~8 ticks over `span`.
double nice_step(double span) {
  if (span <= 0) return 1;
  const double raw = span / 8;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (f * p >= raw) return std::max(1.0, f * p);
  return std::max(1.0, 10 * p);
}

class Svg {
public:
  Svg(double w, double h) {
    s_ = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", num(w), "\" height=\"", num(h),
             "\" viewBox=\"0 0 ", num(w), " ", num(h),
             "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"11\">\n");
    rect(0, 0, w, h, "#ffffff");
  }
  void raw(const std::string& t) { s_ += t; }
  void rect(double x, double y, double w, double h, const char* fill, const char* extra = "") {
    s_ += cat("<rect x=\"", num(x), "\" y=\"", num(y), "\" width=\"", num(w), "\" height=\"", num(h), "\" fill=\"",
              fill, "\"", extra, "/>\n");
  }
  void line(double x1, double y1, double x2, double y2, const char* stroke = "#333333") {
    s_ += cat("<line x1=\"", num(x1), "\" y1=\"", num(y1), "\" x2=\"", num(x2), "\" y2=\"", num(y2), "\" stroke=\"",
              stroke, "\"/>\n");
  }
  /// Text anchored at (x, y); `anchor` start|middle|end; `extra` more attributes.
  void text(double x, double y, const std::string& t, const char* anchor = "start", const std::string& extra = "") {
    s_ += cat("<text x=\"", num(x), "\" y=\"", num(y), "\" text-anchor=\"", anchor, "\"", extra, ">", t, "</text>\n");
  }
  std::string finish() { return s_ + "</svg>\n"; }

private:
  std::string s_;
};

// Layout (pixels).
constexpr double kPlotW = 300, kPlotH = 210;          // heat-map area of a panel
constexpr double kLeft = 74, kRight = 22, kTop = 30, kBottom = 44; // panel margins around it
constexpr double kPanelW = kLeft + kPlotW + kRight, kPanelH = kTop + kPlotH + kBottom;
constexpr double kPage = 12, kHeader = 52, kLegend = 46;

} // namespace

size_t MeasureBins::bin_of(double value) const {
  const size_t last = lo.size() - 1;
  if (!std::isfinite(value)) return std::isnan(value) || value > 0 ? last : 0;
  const double w = hi[0] - lo[0];
  const double i = std::floor((value - lo[0]) / w + 1e-9);
  return i <= 0 ? 0 : i >= double(last) ? last : size_t(i);
}

const MeasureBins& measure_bins(Measure m) {
  return all_bins()[size_t(m)];
}

void QualityHistory::record(int iteration, const NodeMesh& m) {
  if (iteration < 0 || (!iterations_.empty() && iteration <= iterations_.back()))
    throw InvalidInput(located("quality history", cat("iteration ", iteration, " recorded after iteration ",
                                                      iterations_.empty() ? -1 : iterations_.back(),
                                                      " (iterations must increase from 0)")));
  const size_t n = m.points.size();
  std::vector<char> usable(m.triangles.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) usable[t] = detail::well_formed(m.triangles[t], n);
  const detail::EdgeTable et = detail::edge_table(m.triangles, detail::node_triangles(n, m.triangles, &usable));

  if (scale_ == 0 && et.size() > 0) {
    double sum2 = 0;
    for (const auto& [a, b] : et.nodes) sum2 += (m.points[size_t(a)] - m.points[size_t(b)]).squaredNorm();
    const double rms = std::sqrt(sum2 / double(et.size()));
    if (std::isfinite(rms) && rms > 0) scale_ = rms;
  }
  // Lengths in units of the initial RMS edge length (a zero scale only if every edge so far had length 0).
  auto rel = [this](double len) { return scale_ > 0 ? len / scale_ : len == 0 ? 0.0 : kInf; };

  Counts c;
  for (int k = 0; k < kNumMeasures; ++k) c[size_t(k)].assign(measure_bins(Measure(k)).size(), 0);
  auto add = [&c](Measure k, double v) { ++c[size_t(k)][measure_bins(k).bin_of(v)]; };

  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = m.triangles[t];
    const Vec3 &a = m.points[size_t(tri[0])], &b = m.points[size_t(tri[1])], &p = m.points[size_t(tri[2])];
    const double la = (p - b).norm(), lb = (a - p).norm(), lc = (b - a).norm();
    const double area = 0.5 * (b - a).cross(p - a).norm();
    const double perimeter = la + lb + lc;
    // r = 2A / perimeter, R = abc / 4A; a point triangle has r = R = 0, a flat one R = inf.
    add(Measure::inradius, perimeter > 0 ? rel(2 * area / perimeter) : 0.0);
    add(Measure::circumradius, perimeter > 0 ? rel(la * lb * lc / (4 * area)) : 0.0);
    add(Measure::quality, triangle_quality(a, b, p));
    add(Measure::angle, angle_deg(b - a, p - a));
    add(Measure::angle, angle_deg(p - b, a - b));
    add(Measure::angle, angle_deg(a - p, b - p));
  }
  std::vector<int> degree(n, 0);
  for (const auto& [a, b] : et.nodes) {
    add(Measure::edge_length, rel((m.points[size_t(a)] - m.points[size_t(b)]).norm()));
    ++degree[size_t(a)];
    ++degree[size_t(b)];
  }
  for (int d : degree) add(Measure::degree, d);

  iterations_.push_back(iteration);
  counts_.push_back(std::move(c));
}

const std::vector<size_t>& QualityHistory::counts(size_t r, Measure m) const {
  return counts_.at(r)[size_t(m)];
}

size_t QualityHistory::total(size_t r, Measure m) const {
  size_t sum = 0;
  for (size_t v : counts(r, m)) sum += v;
  return sum;
}

std::vector<double> QualityHistory::percent(size_t r, Measure m) const {
  const std::vector<size_t>& c = counts(r, m);
  const size_t sum = total(r, m);
  std::vector<double> p(c.size(), 0.0);
  if (sum > 0)
    for (size_t i = 0; i < c.size(); ++i) p[i] = 100.0 * double(c[i]) / double(sum);
  return p;
}

std::string QualityHistory::csv() const {
  std::string out = "measure,iteration,bin_lo,bin_hi,percent\n";
  for (int k = 0; k < kNumMeasures; ++k) {
    const MeasureBins& bins = measure_bins(Measure(k));
    for (size_t r = 0; r < size(); ++r) {
      const std::vector<double> p = percent(r, Measure(k));
      for (size_t i = 0; i < bins.size(); ++i)
        out += cat(bins.key, ",", iterations_[r], ",", num(bins.lo[i]), ",",
                   std::isinf(bins.hi[i]) ? std::string("inf") : num(bins.hi[i]), ",", num(p[i], 8), "\n");
    }
  }
  return out;
}

std::string QualityHistory::json() const {
  nlohmann::ordered_json j;
  j["length_scale"] = scale_;
  j["iterations"] = iterations_;
  j["measures"] = nlohmann::ordered_json::array();
  for (int k = 0; k < kNumMeasures; ++k) {
    const MeasureBins& bins = measure_bins(Measure(k));
    nlohmann::ordered_json mj{{"key", bins.key}, {"title", bins.title}, {"unit", bins.unit}, {"bin_lo", bins.lo}};
    nlohmann::ordered_json hi = nlohmann::ordered_json::array();
    for (double h : bins.hi) hi.push_back(std::isinf(h) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(h));
    mj["bin_hi"] = std::move(hi);
    mj["total"] = nlohmann::ordered_json::array();
    mj["count"] = nlohmann::ordered_json::array();
    mj["percent"] = nlohmann::ordered_json::array();
    for (size_t r = 0; r < size(); ++r) {
      mj["total"].push_back(total(r, Measure(k)));
      mj["count"].push_back(counts(r, Measure(k)));
      mj["percent"].push_back(percent(r, Measure(k)));
    }
    j["measures"].push_back(std::move(mj));
  }
  return j.dump(1) + "\n";
}

std::string QualityHistory::svg() const {
  const double width = 2 * kPage + 3 * kPanelW;
  const double height = kPage + kHeader + 2 * kPanelH + kLegend + kPage;
  Svg svg(width, height);
  svg.text(kPage + 8, kPage + 18, "Mesh quality and geometry by iteration", "start",
           " font-size=\"16\" font-weight=\"bold\"");
  svg.text(kPage + 8, kPage + 38,
           scale_ > 0 ? cat("Percentage of features per bin after each iteration. Lengths relative to the RMS edge "
                            "length of the initial mesh (",
                            num(scale_, 4), ").")
                      : std::string("Percentage of features per bin after each iteration."),
           "start", " font-size=\"12\" fill=\"#444444\"");

  // Horizontal extent of each iteration's column: halfway to its neighbours.
  const size_t n = size();
  std::vector<double> left(n), right(n);
  for (size_t r = 0; r < n; ++r) {
    const double it = iterations_[r];
    const double gap_before = r > 0 ? it - iterations_[r - 1] : n > 1 ? iterations_[1] - it : 1.0;
    const double gap_after = r + 1 < n ? iterations_[r + 1] - it : gap_before;
    left[r] = it - gap_before / 2;
    right[r] = it + gap_after / 2;
  }
  const double x0 = n > 0 ? left.front() : -0.5, x1 = n > 0 ? right.back() : 0.5;

  for (int k = 0; k < kNumMeasures; ++k) {
    const Measure meas = Measure(k);
    const MeasureBins& bins = measure_bins(meas);
    const double px = kPage + (k % 3) * kPanelW + kLeft;
    const double py = kPage + kHeader + (k / 3) * kPanelH + kTop;
    auto xpos = [&](double v) { return px + (v - x0) / (x1 - x0) * kPlotW; };
    const double row = kPlotH / double(bins.size());
    auto ypos = [&](size_t bin) { return py + kPlotH - double(bin) * row; }; // bottom edge of `bin`

    svg.text(px + kPlotW / 2, py - 10, bins.title, "middle", " font-size=\"13\" font-weight=\"bold\"");
    svg.rect(px, py, kPlotW, kPlotH, "#ffffff");
    svg.raw("<g shape-rendering=\"crispEdges\">\n");
    // One rectangle per run of equal colour along a row (a converged run is one).
    std::vector<std::vector<double>> p(n);
    for (size_t r = 0; r < n; ++r) p[r] = percent(r, meas);
    auto colour = [&p](size_t r, size_t i) { return p[r][i] > 0 ? colour_of(p[r][i]) : nullptr; };
    for (size_t i = 0; i < bins.size(); ++i)
      for (size_t r = 0, end; r < n; r = end) {
        for (end = r + 1; end < n && colour(end, i) == colour(r, i);) ++end;
        if (colour(r, i) != nullptr)
          svg.rect(xpos(left[r]), ypos(i + 1), xpos(right[end - 1]) - xpos(left[r]), row, colour(r, i));
      }
    svg.raw("</g>\n");
    if (n == 0) svg.text(px + kPlotW / 2, py + kPlotH / 2, "no data", "middle", " fill=\"#888888\"");
    const bool overflow = std::isinf(bins.hi.back());
    if (overflow && meas != Measure::degree) // the overflow row is set apart by a dashed line
      svg.raw(cat("<line x1=\"", num(px), "\" y1=\"", num(py + row), "\" x2=\"", num(px + kPlotW), "\" y2=\"",
                  num(py + row), "\" stroke=\"#888888\" stroke-dasharray=\"3,3\"/>\n"));
    svg.rect(px, py, kPlotW, kPlotH, "none", " stroke=\"#333333\"");

    // y axis: ticks at bin edges (continuous measures) or bin centres (degree).
    const YTicks yt = y_ticks(meas);
    const size_t regular = overflow ? bins.size() - 1 : bins.size();
    for (size_t i = 0; i <= bins.size(); i += size_t(yt.every)) {
      if (yt.centred && i == bins.size()) break;
      const double y = yt.centred ? ypos(i) - row / 2 : ypos(i);
      svg.line(px - 4, y, px, y);
      std::string label;
      if (yt.centred)
        label = i == regular ? cat(num(bins.lo[i]), "+") : num(bins.lo[i]);
      else if (i <= regular && !(overflow && i == regular))
        label = num(i < bins.size() ? bins.lo[i] : bins.hi[i - 1]);
      if (!label.empty()) svg.text(px - 7, y + 4, label, "end", yt.centred ? " font-size=\"9.5\"" : "");
    }
    if (overflow && !yt.centred)
      svg.text(px - 7, ypos(regular) - row / 2 + 3, cat("\u2265", num(bins.lo[regular])), "end", " font-size=\"9\"");
    const double ly = py + kPlotH / 2, lx = px - kLeft + 14;
    svg.text(lx, ly, bins.unit, "middle", cat(" transform=\"rotate(-90 ", num(lx), " ", num(ly), ")\""));

    // x axis: iteration ticks at "nice" multiples.
    if (n > 0) {
      const double step = nice_step(iterations_.back() - iterations_.front());
      for (double v = std::ceil(iterations_.front() / step) * step; v <= iterations_.back() + 1e-9; v += step) {
        svg.line(xpos(v), py + kPlotH, xpos(v), py + kPlotH + 4);
        svg.text(xpos(v), py + kPlotH + 16, num(v), "middle");
      }
    }
    svg.text(px + kPlotW / 2, py + kPlotH + 34, "iteration", "middle");
  }

  // Legend: one swatch per colour class, white for 0, centred under the panels.
  struct Item {
    const char* colour;
    const char* label;
  };
  std::vector<Item> items{{"#ffffff", "0"}};
  for (const ColourClass& c : kClasses) items.push_back({c.colour, c.label});
  const char* caption = "Percentage of features in the bin:";
  auto text_width = [](const char* t) { // rough width at 12 px (UTF-8 continuation bytes skipped)
    double w = 0;
    for (const char* c = t; *c != 0; ++c)
      if ((static_cast<unsigned char>(*c) & 0xC0) != 0x80) w += 7;
    return std::string_view(t).find("&lt;") != std::string_view::npos ? w - 21 : w;
  };
  double total_w = text_width(caption) + 12;
  for (const Item& it : items) total_w += 22 + 6 + text_width(it.label) + 20;
  const double ly = kPage + kHeader + 2 * kPanelH + 14;
  double lx = (width - total_w) / 2;
  svg.text(lx, ly + 12, caption, "start", " font-size=\"12\"");
  lx += text_width(caption) + 12;
  for (const Item& it : items) {
    svg.rect(lx, ly, 22, 16, it.colour, " stroke=\"#333333\" stroke-width=\"0.6\"");
    svg.text(lx + 28, ly + 12, it.label, "start", " font-size=\"12\"");
    lx += 22 + 6 + text_width(it.label) + 20;
  }
  return svg.finish();
}

void QualityHistory::write_csv(const std::string& path) const {
  detail::write_atomically(path, [&](std::ostream& f) { f << csv(); });
}

void QualityHistory::write_json(const std::string& path) const {
  detail::write_atomically(path, [&](std::ostream& f) { f << json(); });
}

void QualityHistory::write_svg(const std::string& path) const {
  detail::write_atomically(path, [&](std::ostream& f) { f << svg(); });
}

void QualityHistory::check_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".csv" && ext != ".json" && ext != ".svg")
    throw InvalidInput(located(path, "unknown history format (the extension must be .csv, .json or .svg)"));
}

std::string QualityHistory::text_for(const std::string& path) const {
  check_format(path);
  const std::string ext = lower_extension(path);
  return ext == ".csv" ? csv() : ext == ".json" ? json() : svg();
}

void QualityHistory::write(const std::string& path) const {
  const std::string text = text_for(path);
  detail::write_atomically(path, [&](std::ostream& f) { f << text; });
}

} // namespace vm
