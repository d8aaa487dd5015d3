#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace vm;

namespace {

const std::string examples = VM_EXAMPLES_DIR;

/// A scene whose phase 1 is `phase` (phase 0 is a constant).
Scene one_phase(const std::string& phase) {
  return parse_scene(R"({"phases": [{"kind": "constant", "value": 0}, )" + phase + "]}", "test.json");
}

void expect_vec(const Vec3& got, const Vec3& want, double tol = 1e-15) {
  EXPECT_NEAR(got.x(), want.x(), tol);
  EXPECT_NEAR(got.y(), want.y(), tol);
  EXPECT_NEAR(got.z(), want.z(), tol);
}

/// Every phase value and gradient of two fields at a spread of points, exactly.
void expect_same_field(const PhaseField& a, const PhaseField& b) {
  ASSERT_EQ(a.num_phases(), b.num_phases());
  for (int i = 0; i < a.num_phases(); ++i) {
    EXPECT_EQ(a.phase_name(i), b.phase_name(i));
    for (double t = 0; t <= 1; t += 0.0625) {
      const Vec3 x(t, 1 - t, 0.3 + 0.4 * t);
      EXPECT_EQ(a.value(i, x), b.value(i, x));
      EXPECT_EQ(a.gradient(i, x), b.gradient(i, x));
    }
  }
}

} // namespace

TEST(Scene, defaults_are_unit_cube_and_grid_64_with_phase_names) {
  const Scene s = one_phase(R"({"kind": "constant", "value": 1})");
  EXPECT_EQ(s.grid.domain.min, Vec3(0, 0, 0));
  EXPECT_EQ(s.grid.domain.max, Vec3(1, 1, 1));
  EXPECT_EQ(s.grid.cells, (std::array<int, 3>{64, 64, 64}));
  EXPECT_EQ(s.field->num_phases(), 2);
  EXPECT_EQ(s.field->phase_name(0), "phase0");
  EXPECT_EQ(s.field->phase_name(1), "phase1");
}

TEST(Scene, domain_grid_and_names_are_read) {
  const Scene s = parse_scene(R"({"domain": {"min": [-1, -2, -3], "max": [1, 2, 3]},
      "grid": [8, 16, 4096],
      "phases": [{"name": "out", "kind": "constant", "value": 0},
                 {"name": "in", "kind": "constant", "value": 1}]})",
                              "s.json");
  EXPECT_EQ(s.grid.domain.min, Vec3(-1, -2, -3));
  EXPECT_EQ(s.grid.domain.max, Vec3(1, 2, 3));
  EXPECT_EQ(s.grid.cells, (std::array<int, 3>{8, 16, 4096}));
  EXPECT_EQ(s.field->phase_name(0), "out");
  EXPECT_EQ(s.field->phase_name(1), "in");
  EXPECT_EQ(parse_scene(R"({"grid": 1, "phases": [{"kind": "constant", "value": 0},
      {"kind": "constant", "value": 0}]})", "s.json").grid.cells, (std::array<int, 3>{1, 1, 1}));
}

TEST(Scene, constant_value_and_zero_gradient) {
  const Scene s = one_phase(R"({"kind": "constant", "value": -2.5})");
  EXPECT_EQ(s.field->value(1, Vec3(0.3, 0.1, 0.9)), -2.5);
  EXPECT_EQ(s.field->gradient(1, Vec3(0.3, 0.1, 0.9)), Vec3::Zero());
}

TEST(Scene, sphere_is_signed_distance_positive_inside) {
  const Scene s = one_phase(R"({"kind": "sphere", "center": [0.4, 0.5, 0.5], "radius": 0.2})");
  EXPECT_NEAR(s.field->value(1, Vec3(0.7, 0.5, 0.5)), -0.1, 1e-15);
  expect_vec(s.field->gradient(1, Vec3(0.7, 0.5, 0.5)), Vec3(-1, 0, 0));
  // |(0, 0.4, 0.3)| = 0.5
  EXPECT_NEAR(s.field->value(1, Vec3(0.4, 0.9, 0.8)), -0.3, 1e-15);
  expect_vec(s.field->gradient(1, Vec3(0.4, 0.9, 0.8)), Vec3(0, -0.8, -0.6));
  EXPECT_NEAR(s.field->value(1, Vec3(0.4, 0.5, 0.5)), 0.2, 1e-15);
  EXPECT_EQ(s.field->gradient(1, Vec3(0.4, 0.5, 0.5)), Vec3::Zero());
}

TEST(Scene, seeds_are_minus_distance_to_nearest_point) {
  const Scene s = one_phase(R"({"kind": "seeds", "points": [[0, 0, 0], [1, 0, 0]]})");
  // nearest is (1, 0, 0) at distance |(-0.2, 0, 0.15)| = 0.25
  EXPECT_NEAR(s.field->value(1, Vec3(0.8, 0, 0.15)), -0.25, 1e-15);
  expect_vec(s.field->gradient(1, Vec3(0.8, 0, 0.15)), Vec3(0.8, 0, -0.6));
  // nearest is (0, 0, 0) at distance |(0.3, 0.4, 0)| = 0.5
  EXPECT_NEAR(s.field->value(1, Vec3(0.3, 0.4, 0)), -0.5, 1e-15);
  expect_vec(s.field->gradient(1, Vec3(0.3, 0.4, 0)), Vec3(-0.6, -0.8, 0));
  EXPECT_EQ(s.field->value(1, Vec3(1, 0, 0)), 0);
  EXPECT_EQ(s.field->gradient(1, Vec3(1, 0, 0)), Vec3::Zero());
}

TEST(Scene, plane_is_signed_distance_along_normal_of_any_length) {
  const Scene s = one_phase(R"({"kind": "plane", "point": [0, 0, 0.5], "normal": [0, 0, 2]})");
  EXPECT_NEAR(s.field->value(1, Vec3(0.3, 0.1, 0.8)), 0.3, 1e-15);
  EXPECT_NEAR(s.field->value(1, Vec3(0.3, 0.1, 0.25)), -0.25, 1e-15);
  expect_vec(s.field->gradient(1, Vec3(0.3, 0.1, 0.8)), Vec3(0, 0, 1));
  const Scene t = one_phase(R"({"kind": "plane", "point": [1, 1, 1], "normal": [3, 4, 0]})");
  EXPECT_NEAR(t.field->value(1, Vec3(4, 5, 7)), 5, 1e-14); // (3, 4, 6) . (0.6, 0.8, 0)
  expect_vec(t.field->gradient(1, Vec3(4, 5, 7)), Vec3(0.6, 0.8, 0));
}

TEST(Scene, expr_value_and_central_difference_gradient_match_analytic) {
  const Scene s = one_phase(R"J({"kind": "expr", "expr": "x*y^2 + sin(z)"})J");
  for (const Vec3& p : {Vec3(0.3, 0.7, 0.2), Vec3(-1, 2, 3), Vec3(0.5, 0.5, 0.5)}) {
    EXPECT_NEAR(s.field->value(1, p), p.x() * p.y() * p.y() + std::sin(p.z()), 1e-15);
    expect_vec(s.field->gradient(1, p), Vec3(p.y() * p.y(), 2 * p.x() * p.y(), std::cos(p.z())), 1e-8);
  }
}

TEST(Scene, expr_constants_abs_power_and_pi) {
  const Scene s = one_phase(R"({"kind": "expr", "constants": {"r": 2, "s": 0.5}, "expr": "abs(x - r)^3 + s*pi"})");
  EXPECT_NEAR(s.field->value(1, Vec3(0.5, 0, 0)), 3.375 + 0.5 * std::numbers::pi, 1e-14);
  EXPECT_NEAR(s.field->value(1, Vec3(3, 0, 0)), 1 + 0.5 * std::numbers::pi, 1e-14);
  // d/dx |x - 2|^3 = -3 (x - 2)^2 for x < 2
  EXPECT_NEAR(s.field->gradient(1, Vec3(0.5, 0, 0)).x(), -6.75, 1e-7);
}

TEST(Scene, expr_gradient_formulas_are_used_when_given) {
  const Scene s = one_phase(R"({"kind": "expr", "expr": "x^2", "gradient": ["2*x", "y", "7"]})");
  EXPECT_EQ(s.field->gradient(1, Vec3(1.5, -3, 0)), Vec3(3, -3, 7));
}

TEST(Scene, values_agree_with_value_for_every_kind) {
  const Scene s = parse_scene(R"J({"phases": [
      {"kind": "constant", "value": 0.1},
      {"kind": "sphere", "center": [0.4, 0.5, 0.5], "radius": 0.2},
      {"kind": "seeds", "points": [[0.1, 0.2, 0.3], [0.9, 0.9, 0.9]]},
      {"kind": "plane", "point": [0, 0, 0.5], "normal": [0, 1, 1]},
      {"kind": "expr", "expr": "cos(x)*sin(y) + cos(y)*sin(z) + cos(z)*sin(x)"}]})J",
                              "all.json");
  ASSERT_EQ(s.field->num_phases(), 5);
  std::vector<double> v(5);
  const Vec3 x(0.25, 0.6, 0.8);
  s.field->values(x, v);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(v[size_t(i)], s.field->value(i, x)) << "phase " << i;
}

TEST(Scene, paper_split_sphere_example_matches_eq_6) {
  const Scene s = load_scene(examples + "/split_sphere.json");
  ASSERT_EQ(s.field->num_phases(), 3);
  const double r = 1.5 * std::numbers::pi;
  for (const Vec3& p : {Vec3(0.3, -1.2, 2.5), Vec3(4, 1, -3), Vec3(-0.7, 0.2, 0.1)}) {
    const double f = std::cos(p.x()) * std::sin(p.y()) + std::cos(p.y()) * std::sin(p.z()) +
                     std::cos(p.z()) * std::sin(p.x());
    EXPECT_NEAR(s.field->value(0, p), p.norm() - r + std::pow(std::abs(f), 3), 1e-12);
    EXPECT_NEAR(s.field->value(1, p), f * f * f, 1e-12);
    EXPECT_NEAR(s.field->value(2, p), -f * f * f, 1e-12);
  }
}

TEST(Scene, shipped_examples_load) {
  EXPECT_EQ(load_scene(examples + "/four_spheres.json").field->num_phases(), 5);
  const Scene v = load_scene(examples + "/voronoi30.json");
  EXPECT_EQ(v.field->num_phases(), 30);
  EXPECT_EQ(v.grid.cells, (std::array<int, 3>{64, 64, 64}));
}

TEST(Scene, demo_is_the_four_spheres_example) {
  const Scene demo = demo_scene();
  const Scene file = load_scene(examples + "/four_spheres.json");
  EXPECT_EQ(demo.grid.cells, file.grid.cells);
  EXPECT_EQ(demo.grid.domain.min, file.grid.domain.min);
  EXPECT_EQ(demo.grid.domain.max, file.grid.domain.max);
  expect_same_field(*demo.field, *file.field);
}

/// What a bad scene must produce: InvalidInput, one line, naming the source and the problem.
struct BadScene {
  const char* name; ///< test name suffix
  const char* text;
  std::vector<const char*> keywords;
};

/// Keeps ctest's names short: gtest_discover_tests puts the printed value into them.
void PrintTo(const BadScene& bad, std::ostream* os) { *os << bad.name; }

class SceneErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneErrors, one_line_invalid_input_naming_source_and_problem) {
  const BadScene& bad = GetParam();
  try {
    parse_scene(bad.text, "bad.json");
    FAIL() << "accepted: " << bad.text;
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("bad.json: ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    for (const char* k : bad.keywords) EXPECT_NE(what.find(k), std::string::npos) << "'" << k << "' not in: " << what;
  }
}

#define PH0 R"({"kind": "constant", "value": 0})"

INSTANTIATE_TEST_SUITE_P(
    Scene, SceneErrors,
    ::testing::Values(
        BadScene{"malformed_json", "{\"phases\": [\n  {\"kind\": \"constant\" \"value\": 0}]}", {"malformed JSON", "line 2"}},
        BadScene{"empty_text", "", {"malformed JSON"}},
        BadScene{"root_not_object", "[1, 2]", {"JSON object"}},
        BadScene{"one_phase", R"({"phases": [)" PH0 "]}", {"at least two phases"}},
        BadScene{"phases_not_array", R"({"phases": 3})", {"'phases'", "array"}},
        BadScene{"phases_missing", R"({"grid": 64})", {"missing key 'phases'"}},
        BadScene{"unknown_top_key", R"({"gird": 64, "phases": [)" PH0 "," PH0 "]}", {"unknown key 'gird'"}},
        BadScene{"grid_zero", R"({"grid": 0, "phases": [)" PH0 "," PH0 "]}", {"grid must be", "[1, 4096]"}},
        BadScene{"grid_million", R"({"grid": 1000000, "phases": [)" PH0 "," PH0 "]}", {"grid must be", "1000000"}},
        BadScene{"grid_fraction", R"({"grid": 64.5, "phases": [)" PH0 "," PH0 "]}", {"grid must be"}},
        BadScene{"grid_string", R"({"grid": "64", "phases": [)" PH0 "," PH0 "]}", {"grid must be"}},
        BadScene{"grid_two_entries", R"({"grid": [64, 64], "phases": [)" PH0 "," PH0 "]}", {"grid must be", "3"}},
        BadScene{"grid_entry_zero", R"({"grid": [64, 0, 64], "phases": [)" PH0 "," PH0 "]}", {"grid[1] must be"}},
        BadScene{"domain_empty_axis", R"({"domain": {"min": [0, 0, 1], "max": [1, 1, 1]}, "phases": [)" PH0 "," PH0 "]}",
                 {"domain", "below", "axis z"}},
        BadScene{"domain_missing_max", R"({"domain": {"min": [0, 0, 0]}, "phases": [)" PH0 "," PH0 "]}", {"domain", "missing key 'max'"}},
        BadScene{"domain_short_min", R"({"domain": {"min": [0, 0], "max": [1, 1, 1]}, "phases": [)" PH0 "," PH0 "]}",
                 {"domain", "'min'", "3 numbers"}},
        BadScene{"unknown_kind", R"({"phases": [)" PH0 R"(, {"kind": "spere", "center": [0, 0, 0], "radius": 1}]})",
                 {"phase 1", "unknown kind 'spere'", "sphere"}},
        BadScene{"kind_missing", R"({"phases": [)" PH0 R"(, {"center": [0, 0, 0]}]})", {"phase 1", "missing key 'kind'"}},
        BadScene{"phase_not_object", R"({"phases": [)" PH0 R"(, 7]})", {"phase 1", "JSON object"}},
        BadScene{"radius_missing", R"({"phases": [)" PH0 R"(, {"kind": "sphere", "center": [0, 0, 0]}]})",
                 {"phase 1", "missing key 'radius'"}},
        BadScene{"radius_string", R"({"phases": [)" PH0 R"(, {"kind": "sphere", "center": [0, 0, 0], "radius": "1"}]})",
                 {"phase 1", "'radius' must be a number"}},
        BadScene{"radius_negative", R"({"phases": [)" PH0 R"(, {"kind": "sphere", "center": [0, 0, 0], "radius": -1}]})",
                 {"phase 1", "radius", "negative"}},
        BadScene{"number_overflow", R"({"phases": [)" PH0 R"(, {"kind": "sphere", "center": [0, 0, 0], "radius": 1e999}]})",
                 {"malformed JSON", "overflow", "1e999"}},
        BadScene{"unknown_phase_key", R"({"phases": [)" PH0 R"(, {"kind": "sphere", "center": [0, 0, 0], "raduis": 1}]})",
                 {"phase 1", "unknown key 'raduis'"}},
        BadScene{"seeds_empty", R"({"phases": [)" PH0 R"(, {"kind": "seeds", "points": []}]})", {"phase 1", "points", "empty"}},
        BadScene{"seed_short", R"({"phases": [)" PH0 R"(, {"kind": "seeds", "points": [[0, 0, 0], [1, 1]]}]})",
                 {"phase 1", "points[1]"}},
        BadScene{"plane_zero_normal", R"({"phases": [)" PH0 R"(, {"kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 0]}]})",
                 {"phase 1", "normal", "zero"}},
        BadScene{"constant_missing_value", R"({"phases": [)" PH0 R"(, {"kind": "constant"}]})", {"phase 1", "missing key 'value'"}},
        BadScene{"expr_syntax", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x +"}]})", {"phase 1", "bad expr", "x +"}},
        BadScene{"expr_unknown_variable", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "q * x"}]})", {"phase 1", "bad expr", "\"q\""}},
        BadScene{"expr_two_results", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x, y"}]})", {"phase 1", "expected one"}},
        BadScene{"constant_hides_coordinate", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x", "constants": {"y": 1}}]})",
                 {"phase 1", "constant 'y'"}},
        BadScene{"constant_not_number", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x", "constants": {"r": "big"}}]})",
                 {"phase 1", "'r' must be a number"}},
        BadScene{"constants_not_object", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x", "constants": [1]}]})",
                 {"phase 1", "'constants'", "object"}},
        BadScene{"gradient_two_entries", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x", "gradient": ["1", "0"]}]})",
                 {"phase 1", "'gradient'"}},
        BadScene{"gradient_syntax", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": "x", "gradient": ["1", "0", "("]}]})",
                 {"phase 1", "gradient[2]"}},
        BadScene{"expr_not_string", R"({"phases": [)" PH0 R"(, {"kind": "expr", "expr": 3}]})", {"phase 1", "'expr' must be a string"}},
        BadScene{"duplicate_name", R"({"phases": [{"name": "a", "kind": "constant", "value": 0},
                                {"name": "a", "kind": "constant", "value": 1}]})",
                 {"phase 1", "'a'", "already used by phase 0"}},
        BadScene{"empty_name", R"({"phases": [{"name": "", "kind": "constant", "value": 0}, )" PH0 "]}", {"phase 0", "name"}},
        BadScene{"kind_with_newline", R"({"phases": [)" PH0 R"(, {"kind": "spe\nre"}]})", {"phase 1", "unknown kind"}}),
    [](const ::testing::TestParamInfo<BadScene>& info) { return std::string(info.param.name); });

TEST(Scene, missing_file_is_io_error_naming_path_and_reason) {
  const std::string path = examples + "/no_such_scene.json";
  try {
    load_scene(path);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open (No such file or directory)");
  }
  EXPECT_THROW(load_scene(examples), IoError); // a directory
}

TEST(Scene, file_name_is_the_source_of_parse_errors) {
  try {
    load_scene(examples + "/../CMakeLists.txt");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("CMakeLists.txt: malformed JSON"), std::string::npos) << e.what();
  }
}
