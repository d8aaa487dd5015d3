#include "fixtures.hpp"

#include "run/run_job.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/improve/offsets.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>

using namespace vm;

TEST(TriangleQuality, equilateral_is_one_and_degenerate_is_zero) {
  EXPECT_NEAR(triangle_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)), 1.0, 1e-15);
  EXPECT_NEAR(triangle_quality(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)), std::sqrt(3.0) / 2, 1e-15);
  EXPECT_EQ(triangle_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)), 0.0);
  EXPECT_EQ(triangle_quality(Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)), 0.0);
  EXPECT_EQ(triangle_quality(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(NAN, 0, 0)), 0.0);
}

TEST(Stats, closed_surface) {
  const MeshStats s = compute_stats(test::tetrahedron());
  EXPECT_EQ(s.vertices, 4u);
  EXPECT_EQ(s.triangles, 4u);
  EXPECT_EQ(s.phases, 2u);
  EXPECT_EQ(s.surfaces, 1u);
  EXPECT_EQ(s.triple_curves, 0u);
  EXPECT_EQ(s.quadruple_points, 0u);
}

TEST(Stats, two_cubes_have_three_surfaces_and_one_closed_triple_curve) {
  for (int n : {1, 3}) {
    const MeshStats s = compute_stats(test::two_cubes(n));
    EXPECT_EQ(s.phases, 3u);
    EXPECT_EQ(s.surfaces, 3u) << "n = " << n;
    EXPECT_EQ(s.triple_curves, 1u) << "n = " << n;
    EXPECT_EQ(s.quadruple_points, 0u);
    EXPECT_EQ(s.higher_order_points, 0u);
  }
}

TEST(Stats, a_pair_in_two_patches_counts_twice) {
  test::Builder b;
  test::add_tetrahedron(b, test::corner_tet(Vec3::Zero(), 1), 1, 0);
  test::add_tetrahedron(b, test::corner_tet(Vec3(3, 0, 0), 1), 1, 0);
  EXPECT_EQ(compute_stats(b.mesh).surfaces, 2u);
}

TEST(Stats, four_phase_point_splits_triple_curves_at_quadruple_points) {
  const MeshStats s = compute_stats(test::four_phase_point());
  EXPECT_EQ(s.phases, 5u);
  EXPECT_EQ(s.surfaces, 10u);
  EXPECT_EQ(s.quadruple_points, 5u); // the centroid and the 4 corners
  EXPECT_EQ(s.higher_order_points, 0u);
  EXPECT_EQ(s.triple_curves, 10u); // 4 spokes and 6 tetrahedron edges
}

TEST(Stats, triple_curve_ending_on_the_box_counts_once) {
  for (int n : {2, 6}) {
    const MeshStats s = compute_stats(test::box_t_junction(n));
    EXPECT_EQ(s.surfaces, 3u);
    EXPECT_EQ(s.triple_curves, 1u) << "n = " << n;
    EXPECT_EQ(s.quadruple_points, 0u);
  }
}

TEST(Stats, eight_blocks_meet_at_a_higher_order_point) {
  const MeshStats s = compute_stats(test::block_grains(2, 1));
  EXPECT_EQ(s.phases, 8u);
  EXPECT_EQ(s.surfaces, 12u);
  EXPECT_EQ(s.quadruple_points, 7u); // the centre (8 phases) and 6 block-edge ends on the box (4 each)
  EXPECT_EQ(s.higher_order_points, 1u);
  EXPECT_EQ(s.triple_curves, 6u); // each 4-phase edge runs between such points
}

TEST(Stats, quality_angles_and_edges_of_right_isosceles_triangles) {
  const MeshStats s = compute_stats(test::two_cubes(1));
  EXPECT_NEAR(s.min_quality, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(s.mean_quality, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_EQ(s.below_half, 0u);
  EXPECT_EQ(s.slivers, 0u);
  EXPECT_NEAR(s.min_angle_deg, 45, 1e-9);
  EXPECT_NEAR(s.max_angle_deg, 90, 1e-9);
  EXPECT_EQ(s.smallest_angles, (std::array<size_t, 6>{0, 0, 0, 0, s.triangles, 0})); // 45 degrees: [40, 50)
  EXPECT_DOUBLE_EQ(s.min_edge, 1);
  EXPECT_DOUBLE_EQ(s.max_edge, std::sqrt(2.0));
  // 20 cube edges of length 1 and 11 face diagonals of length sqrt 2.
  EXPECT_NEAR(s.rms_edge, std::sqrt((20 * 1.0 + 11 * 2.0) / 31), 1e-12);
}

TEST(Stats, slivers_are_counted) {
  test::Builder b;
  b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.01, 0), 0, 1);
  b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.4, 0), 0, 1);
  const MeshStats s = compute_stats(b.mesh);
  EXPECT_EQ(s.slivers, 1u);
  EXPECT_EQ(s.below_half, 1u);
  EXPECT_NEAR(s.max_angle_deg, 180 - 2 * std::atan(0.02) * 180 / M_PI, 1e-9);
  // Smallest angles 1.1 and 38.7 degrees.
  EXPECT_EQ(s.smallest_angles, (std::array<size_t, 6>{1, 0, 0, 1, 0, 0}));
}

TEST(Stats, a_surface_turning_back_across_an_edge_is_a_fold_and_a_crease_is_not) {
  // Triangle (0,0,0) (1,0,0) (0.5,1,0), normal +z, and one across its edge on
  // the x axis, rotated about it: 90 degrees (a crease), then 161.6 (a fold).
  for (const auto& [far, folds] : {std::pair{Vec3(0.5, -1, 0), 0u}, std::pair{Vec3(0.5, 0, 1), 0u},
                                   std::pair{Vec3(0.5, 0.9, 0.3), 1u}}) {
    test::Builder b;
    b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), 0, 1);
    b.tri(Vec3(1, 0, 0), Vec3(0, 0, 0), far, 0, 1);
    const MeshStats s = compute_stats(b.mesh);
    EXPECT_EQ(s.folds, folds) << far.transpose();
    EXPECT_NE(to_text(s).find("folds                  " + std::to_string(folds) +
                              " surface edges turning more than 150 deg\n"),
              std::string::npos)
        << to_text(s);
  }
  // Three triangles on an edge are a junction, not a surface: no fold however they turn.
  test::Builder b;
  b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), 0, 1);
  b.tri(Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0.5, 0.9, 0.3), 1, 2);
  b.tri(Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0.5, -1, 0), 0, 2);
  EXPECT_EQ(compute_stats(b.mesh).folds, 0u);
  // A corner tetrahedron's normals lie 90 and 125 degrees apart; flattened
  // (its apex 0.05 over its base) it is two sheets laid onto each other,
  // folding at the base's three edges.
  EXPECT_EQ(compute_stats(test::tetrahedron()).folds, 0u);
  test::Builder flat;
  test::add_tetrahedron(flat, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.05)}, 1, 0);
  EXPECT_EQ(compute_stats(flat.mesh).folds, 3u);
}

TEST(Stats, the_sharpest_folds_are_listed_with_their_turn_and_ends) {
  // The tetrahedron flattened to its apex 0.05 over its base folds at the
  // base's edges: each side face leans atan(0.05 / d) off the base, d the
  // apex's distance from the edge in the base plane (0.3 from both legs,
  // 0.2828 from the hypotenuse), so the surface turns 170.54 degrees at the
  // legs and 169.97 at the hypotenuse.
  test::Builder flat;
  test::add_tetrahedron(flat, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.05)}, 1, 0);
  NodeMesh& m = flat.mesh;
  m.phase_labels = {7, 9};
  const std::vector<Fold> folds = sharpest_folds(m, 5);
  ASSERT_EQ(folds.size(), 3u);
  const double leg = 180 - std::atan(0.05 / 0.3) * 180 / M_PI;
  const double hypotenuse = 180 - std::atan(0.05 / std::sqrt(0.08)) * 180 / M_PI;
  EXPECT_NEAR(folds[0].turn_deg, leg, 1e-9);
  EXPECT_NEAR(folds[1].turn_deg, leg, 1e-9);
  EXPECT_NEAR(folds[2].turn_deg, hypotenuse, 1e-9);
  for (const Fold& f : folds) {
    EXPECT_EQ(f.pair, m.pairs[f.triangles[0]]);
    EXPECT_EQ(f.pair, m.pairs[f.triangles[1]]);
    for (const TriangleCorner& end : f.ends) {
      EXPECT_EQ(end.position.z(), 0.0) << "the folding edges are the base's";
      EXPECT_EQ(end.phases, (std::vector<int32_t>{0, 1}));
      // Both triangles have both ends of the edge as corners.
      for (size_t t : f.triangles)
        EXPECT_NE(std::find(m.triangles[t].begin(), m.triangles[t].end(), end.node), m.triangles[t].end());
    }
  }
  EXPECT_EQ(sharpest_folds(m, 1).size(), 1u);
  EXPECT_TRUE(sharpest_folds(m, 0).empty());
  EXPECT_TRUE(sharpest_folds(test::tetrahedron(), 5).empty());
  // Text and JSON give the turn and the phases as the mesh's files show them.
  const std::string text = to_text(std::span(folds).first(1), m);
  EXPECT_NE(text.find(": turns 170.5 deg, between 7 and 9; length 1, triangles "), std::string::npos) << text;
  EXPECT_NE(text.find(": surface of 7, 9\n"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(to_json(compute_stats(m), {}, &m, folds));
  ASSERT_EQ(j.at("sharpest_folds").size(), 3u);
  EXPECT_EQ(j.at("sharpest_folds")[2].at("turn_deg").get<double>(), folds[2].turn_deg);
  EXPECT_EQ(j.at("sharpest_folds")[0].at("pair").get<std::vector<int32_t>>(), (std::vector<int32_t>{7, 9}));
  EXPECT_EQ(j.at("sharpest_folds")[0].at("ends").size(), 2u);
  EXPECT_FALSE(j.contains("worst_triangles"));
  EXPECT_FALSE(nlohmann::json::parse(to_json(compute_stats(m))).contains("sharpest_folds"));
}

TEST(Stats, an_equilateral_triangle_is_in_the_last_angle_bin) {
  test::Builder b;
  b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(0.75), 0), 0, 1);
  b.tri(Vec3(0, 0, 0), Vec3(1e-3, 0, 0), Vec3(0.5e-3, std::sqrt(0.75) * 1e-3, 1e-3), 0, 2);
  const MeshStats s = compute_stats(b.mesh);
  EXPECT_EQ(s.smallest_angles.back(), 1u);
  EXPECT_EQ(s.smallest_angles[4], 1u); // the second, tilted out of its plane: 41 degrees
  const std::string text = to_text(s);
  EXPECT_NE(text.find("smallest angle         <10/<20/<30/<40/<50/<=60 deg: 0 / 0 / 0 / 0 / 1 / 1 triangles\n"),
            std::string::npos)
      << text;
}

TEST(Stats, empty_mesh_gives_zeros) {
  const MeshStats s = compute_stats(NodeMesh{});
  EXPECT_EQ(s.triangles, 0u);
  EXPECT_EQ(s.min_quality, 0.0);
  EXPECT_EQ(s.rms_edge, 0.0);
}

TEST(Stats, text_and_json_carry_every_field) {
  const MeshStats s = compute_stats(test::four_phase_point());
  const std::string text = to_text(s);
  EXPECT_NE(text.find("surfaces               10\n"), std::string::npos) << text;
  EXPECT_NE(text.find("quadruple points       5\n"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(to_json(s));
  EXPECT_EQ(j.size(), 23u);
  EXPECT_EQ(j.at("folds").get<size_t>(), 0u);
  EXPECT_EQ(j.at("vertices").get<size_t>(), s.vertices);
  EXPECT_EQ(j.at("surfaces").get<size_t>(), 10u);
  EXPECT_EQ(j.at("triple_curves").get<size_t>(), 10u);
  EXPECT_EQ(j.at("quadruple_points").get<size_t>(), 5u);
  EXPECT_EQ(j.at("higher_order_points").get<size_t>(), 0u);
  EXPECT_EQ(j.at("min_quality").get<double>(), s.min_quality);
  EXPECT_EQ(j.at("quality_p01").get<double>(), s.quality_p01);
  EXPECT_LE(s.min_quality, s.quality_p01);
  EXPECT_LE(s.quality_p01, s.mean_quality);
  EXPECT_EQ(j.at("rms_edge").get<double>(), s.rms_edge);
  EXPECT_EQ(j.at("max_angle_deg").get<double>(), s.max_angle_deg);
  EXPECT_EQ(j.at("smallest_angle_bin_deg").get<int>(), MeshStats::kAngleBinDeg);
  EXPECT_EQ(j.at("smallest_corner_deg").get<double>(), s.smallest_corner_deg);
  EXPECT_EQ(j.at("sharp_corners").get<size_t>(), s.sharp_corners);
  EXPECT_NE(text.find("smallest corner"), std::string::npos) << text;
  EXPECT_EQ(j.at("smallest_angles").get<std::vector<size_t>>(),
            std::vector<size_t>(s.smallest_angles.begin(), s.smallest_angles.end()));
  size_t binned = 0;
  for (size_t n : s.smallest_angles) binned += n;
  EXPECT_EQ(binned, s.triangles);
}

TEST(Stats, a_closed_meshs_interfaces_are_measured_without_its_box_faces) {
  test::Builder b;
  b.tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 0, 1); // right isosceles, on the box
  b.tri(Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), 0, 2); // right isosceles, on the box
  b.tri(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5, std::sqrt(3.0) / 2, 1), 1, 2); // equilateral
  b.tri(Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0.5, 0.3, 2), 1, 2);
  const double worst_interface = triangle_quality(Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0.5, 0.3, 2));
  NodeMesh closed = b.mesh;
  closed.outside_phase = 0;
  const MeshStats s = compute_stats(closed);
  EXPECT_EQ(s.box_triangles, 2u);
  EXPECT_DOUBLE_EQ(s.interface_min_quality, worst_interface);
  EXPECT_DOUBLE_EQ(s.interface_mean_quality, (1 + worst_interface) / 2);
  EXPECT_NEAR(s.mean_quality, (2 * std::sqrt(3.0) / 2 + 1 + worst_interface) / 4, 1e-12); // all four still counted
  char line[96];
  std::snprintf(line, sizeof line, "interfaces min/mean    %.4f / %.4f (q without the 2 triangles on the box faces)\n",
                s.interface_min_quality, s.interface_mean_quality);
  EXPECT_NE(to_text(s).find(line), std::string::npos) << to_text(s);
  const auto j = nlohmann::json::parse(to_json(s));
  EXPECT_EQ(j.at("box_triangles").get<size_t>(), 2u);
  EXPECT_EQ(j.at("interface_mean_quality").get<double>(), s.interface_mean_quality);
  // A mesh that is not closed has no box faces to leave out, and says nothing of them.
  const MeshStats open = compute_stats(b.mesh);
  EXPECT_EQ(open.box_triangles, 0u);
  EXPECT_EQ(to_text(open).find("interfaces"), std::string::npos);
  EXPECT_FALSE(nlohmann::json::parse(to_json(open)).contains("box_triangles"));
}

TEST(Stats, the_first_percentile_is_the_qualitys_own) {
  // Enough triangles (thousands) that the 1st percentile is neither the minimum nor the mean.
  const NodeMesh m = test::four_spheres(16);
  const MeshStats s = compute_stats(m);
  std::vector<double> q;
  for (const auto& t : m.triangles)
    q.push_back(triangle_quality(m.points[size_t(t[0])], m.points[size_t(t[1])], m.points[size_t(t[2])]));
  std::sort(q.begin(), q.end());
  ASSERT_GT(q.size(), 1000u);
  EXPECT_EQ(s.quality_p01, q[q.size() / 100]);
  EXPECT_GT(s.quality_p01, s.min_quality);
  EXPECT_LT(s.quality_p01, s.mean_quality);
  EXPECT_EQ(nlohmann::json::parse(to_json(s)).at("quality_p01").get<double>(), s.quality_p01);
}

TEST(Stats, worst_triangles_are_the_lowest_quality_ones_in_order) {
  const NodeMesh m = test::four_spheres(16);
  std::vector<std::pair<double, size_t>> q;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    q.emplace_back(triangle_quality(m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])]), t);
  }
  std::sort(q.begin(), q.end());
  const std::vector<WorstTriangle> worst = worst_triangles(m, 25);
  ASSERT_EQ(worst.size(), 25u);
  for (size_t i = 0; i < worst.size(); ++i) {
    EXPECT_EQ(worst[i].triangle, q[i].second) << i;
    EXPECT_EQ(worst[i].quality, q[i].first) << i;
    EXPECT_EQ(worst[i].pair, m.pairs[worst[i].triangle]);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(worst[i].corners[k].node, m.triangles[worst[i].triangle][k]);
      EXPECT_EQ(worst[i].corners[k].position, m.points[size_t(worst[i].corners[k].node)]);
    }
    EXPECT_GT(worst[i].min_angle_deg, 0.0);
    EXPECT_LE(worst[i].min_angle_deg, 60.0);
  }
  EXPECT_EQ(worst_triangles(m, m.triangles.size() + 5).size(), m.triangles.size());
  EXPECT_TRUE(worst_triangles(m, 0).empty());
}

TEST(Stats, worst_triangles_say_what_meets_at_each_corner) {
  // Every triangle of four_phase_point() has a corner at the centroid (phases
  // 1-4) or is a face of the tetrahedron; corner v0 = (0, 0, 0) lies in cells
  // 2, 3 and 4 (cell i is opposite corner i - 1) and in phase 0.
  NodeMesh m = test::four_phase_point();
  m.phase_labels = {10, 20, 30, 40, 50};
  m.phase_names = {"outside", "a", "b", "c", "d"};
  bool saw_centroid = false, saw_origin = false;
  for (const WorstTriangle& w : worst_triangles(m, m.triangles.size()))
    for (const TriangleCorner& c : w.corners) {
      EXPECT_EQ(c.box_faces, 0); // the fixture's box lies far outside
      if (c.position.isApprox(Vec3::Constant(0.25))) {
        EXPECT_EQ(c.phases, (std::vector<int32_t>{1, 2, 3, 4}));
        saw_centroid = true;
      } else if (c.position.isZero()) {
        EXPECT_EQ(c.phases, (std::vector<int32_t>{0, 2, 3, 4}));
        saw_origin = true;
      }
    }
  EXPECT_TRUE(saw_centroid && saw_origin);
  // Text and JSON show the phases as the mesh's files do: labels, and names in the text.
  const std::vector<WorstTriangle> worst = worst_triangles(m, 1);
  const std::string text = to_text(worst, m);
  EXPECT_NE(text.find("triangle " + std::to_string(worst[0].triangle) + ": q "), std::string::npos) << text;
  EXPECT_NE(text.find("4-phase point of "), std::string::npos) << text;
  EXPECT_NE(text.find("a (20)"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(to_json(compute_stats(m), worst, &m));
  ASSERT_EQ(j.at("worst_triangles").size(), 1u);
  const auto& first = j.at("worst_triangles")[0];
  EXPECT_EQ(first.at("triangle").get<size_t>(), worst[0].triangle);
  EXPECT_EQ(first.at("quality").get<double>(), worst[0].quality);
  EXPECT_EQ(first.at("pair").get<std::vector<int32_t>>(),
            (std::vector<int32_t>{m.label_of(worst[0].pair[0]), m.label_of(worst[0].pair[1])}));
  for (size_t k = 0; k < 3; ++k) {
    std::vector<int32_t> labels;
    for (int32_t p : worst[0].corners[k].phases) labels.push_back(m.label_of(p));
    EXPECT_EQ(first.at("corners")[k].at("phases").get<std::vector<int32_t>>(), labels);
  }
  EXPECT_FALSE(nlohmann::json::parse(to_json(compute_stats(m))).contains("worst_triangles"));
}

TEST(Stats, worst_triangles_count_the_box_faces_a_corner_lies_on) {
  // box_t_junction(2): the triple curve x = y = 1/2 runs from z = 0 to z = 1;
  // its end (1/2, 1/2, 0) lies on one box face, (1/2, 0, 0) on two.
  const NodeMesh m = test::box_t_junction(2);
  std::map<std::array<double, 3>, const TriangleCorner*> at;
  const std::vector<WorstTriangle> worst = worst_triangles(m, m.triangles.size());
  for (const WorstTriangle& w : worst)
    for (const TriangleCorner& c : w.corners) at[{c.position.x(), c.position.y(), c.position.z()}] = &c;
  ASSERT_TRUE(at.count({0.5, 0.5, 0.0}) && at.count({0.5, 0.0, 0.0}) && at.count({0.5, 0.5, 0.5}));
  EXPECT_EQ(at.at({0.5, 0.5, 0.0})->box_faces, 1);
  EXPECT_EQ(at.at({0.5, 0.5, 0.0})->phases, (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(at.at({0.5, 0.0, 0.0})->box_faces, 2);
  EXPECT_EQ(at.at({0.5, 0.5, 0.5})->box_faces, 0);
  EXPECT_NE(to_text(worst, m).find("triple curve of 0, 1, 2, on a box face"), std::string::npos);
}

// A surface's corner at a junction point is its fan's angles there, summed:
// on the box T-junction every surface meets the box edges and the curve's
// ends at right angles, in one triangle (n = 2) or several (n = 6).
TEST(Stats, surface_corners_at_junction_points_sum_their_fans) {
  for (int n : {2, 6}) {
    const MeshStats s = compute_stats(test::box_t_junction(n));
    EXPECT_NEAR(s.smallest_corner_deg, 90, 1e-9) << "n = " << n;
    EXPECT_EQ(s.sharp_corners, 0u);
  }
  // A surface alone in the plane (no junction point) has no corner to report.
  EXPECT_EQ(compute_stats(test::tetrahedron()).smallest_corner_deg, 180);
}

// In four_phase_point() every node is a junction point and every surface one
// triangle, so each angle of each triangle is a whole corner: squashed toward
// a flat tetrahedron, the smallest corner is the smallest angle, the sharp
// corners are the angles below 10 degrees, and each worst triangle names the
// corner that bounds it.
TEST(Stats, a_triangle_filling_a_whole_corner_is_bounded_by_it) {
  NodeMesh m = test::four_phase_point();
  for (Vec3& p : m.points)
    if (p.isApprox(Vec3(0, 0, 1))) p = Vec3(0, 0, 0.08);
  size_t below_10 = 0;
  for (const auto& t : m.triangles)
    for (size_t k = 0; k < 3; ++k) {
      const Vec3 u = m.points[size_t(t[(k + 1) % 3])] - m.points[size_t(t[k])],
                 v = m.points[size_t(t[(k + 2) % 3])] - m.points[size_t(t[k])];
      below_10 += std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / std::numbers::pi < 10;
    }
  const MeshStats s = compute_stats(m);
  EXPECT_LT(s.min_angle_deg, 10);
  EXPECT_NEAR(s.smallest_corner_deg, s.min_angle_deg, 1e-9);
  EXPECT_GT(below_10, 0u);
  EXPECT_EQ(s.sharp_corners, below_10);
  const std::vector<WorstTriangle> worst = worst_triangles(m, m.triangles.size());
  for (const WorstTriangle& w : worst) {
    ASSERT_GE(w.corner_node, 0) << "triangle " << w.triangle;
    EXPECT_NEAR(w.corner_deg, w.min_angle_deg, 1e-9);
  }
  EXPECT_NE(to_text(worst, m).find("whole corner at node " + std::to_string(worst[0].corner_node)), std::string::npos);
  const auto j = nlohmann::json::parse(to_json(s, worst, &m));
  EXPECT_EQ(j.at("worst_triangles")[0].at("corner_deg").get<double>(), worst[0].corner_deg);
}

// A run ends with a note on its slivers: how many, and how many fill a whole
// corner (the squashed tetrahedron above: every one); none without slivers.
TEST(Stats, the_sliver_note_counts_the_slivers_that_fill_whole_corners) {
  NodeMesh m = test::four_phase_point();
  EXPECT_EQ(detail::sliver_note(m), "");
  for (Vec3& p : m.points)
    if (p.isApprox(Vec3(0, 0, 1))) p = Vec3(0, 0, 0.01);
  const size_t slivers = compute_stats(m).slivers;
  ASSERT_GT(slivers, 0u);
  const std::string note = detail::sliver_note(m);
  const std::string count = std::to_string(slivers);
  EXPECT_EQ(note.rfind(count + " triangles are slivers (q below 0.1, the worst ", 0), 0u) << note;
  EXPECT_NE(note.find("); " + count + " of them fill their surface's whole corner"), std::string::npos) << note;
  EXPECT_NE(note.find("stats --worst " + count + "`"), std::string::npos) << note;
  // Slivers off junction points (a surface's own nodes squeezed together) fill none.
  NodeMesh flat = test::tetrahedron();
  flat.points[0] = 0.5 * (flat.points[1] + flat.points[2]) + Vec3(1e-3, 1e-3, 1e-3);
  const std::string none = detail::sliver_note(flat);
  EXPECT_NE(none.find("); none fills its surface's whole corner at a junction point; `voronoimesh stats --worst "),
            std::string::npos)
      << none;
}

// A triangle whose smallest angle shares its corner with others (or lies off
// junction points) is not bounded by a corner: on the T-junction's right
// isosceles triangles none is.
TEST(Stats, a_triangle_sharing_its_corner_names_none) {
  const NodeMesh m = test::box_t_junction(6);
  for (const WorstTriangle& w : worst_triangles(m, m.triangles.size())) {
    if (w.corner_node < 0) {
      EXPECT_TRUE(std::isnan(w.corner_deg));
      continue;
    }
    EXPECT_NEAR(w.corner_deg, w.min_angle_deg, 1e-9) << "triangle " << w.triangle;
  }
  const auto j = nlohmann::json::parse(to_json(compute_stats(m), worst_triangles(m, 1), &m));
  const auto& first = j.at("worst_triangles")[0];
  if (first.at("corner_node").get<int>() < 0) EXPECT_TRUE(first.at("corner_deg").is_null());
}

// A junction node is measured to where its phases meet (Newton's method run to
// its end), and counted apart where they meet nowhere near: four Voronoi cells
// whose seeds form a regular tetrahedron meet at its centre, 0.06 from the
// node; with a fifth seed at the centre, whose cell leads there, they meet
// nowhere (the mesh's point would be a topology finer than its grid).
TEST(Offsets, a_junction_node_whose_phases_meet_nowhere_near_is_counted_apart) {
  const Vec3 centre(0.5, 0.5, 0.5), node = centre + Vec3(0.05, 0.03, -0.02);
  auto seeds = [&](bool fifth) {
    std::string phases;
    const int corners[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (const auto& c : corners) {
      const Vec3 p = centre + 0.15 * Vec3(c[0], c[1], c[2]);
      phases += std::string(phases.empty() ? "" : ", ") + R"({"kind": "seeds", "points": [[)" +
                std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + "]]}";
    }
    if (fifth) phases += R"(, {"kind": "seeds", "points": [[0.5, 0.5, 0.5]]})";
    return parse_scene(R"({"domain": {"min": [0,0,0], "max": [1,1,1]}, "grid": 8, "phases": [)" + phases + "]}",
                       "inline");
  };
  // Node 0 lies on a triangle of cells 0|1 and one of 2|3: its phases are all four.
  NodeMesh m;
  m.domain = Box{Vec3::Zero(), Vec3::Ones()};
  m.points = {node, node + Vec3(0.1, 0, 0), node + Vec3(0, 0.1, 0), node + Vec3(0, 0, 0.1), node + Vec3(0.1, 0.1, 0)};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  m.pairs = {{0, 1}, {2, 3}};
  const InterfaceOffsets meet = interface_offsets(m, *seeds(false).field);
  EXPECT_EQ(meet[2].nodes, 1u);
  EXPECT_EQ(meet[2].unresolved, 0u);
  EXPECT_EQ(meet[2].farthest, 0);
  EXPECT_NEAR(meet[2].max, (node - centre).norm(), 1e-6);
  const InterfaceOffsets nowhere = interface_offsets(m, *seeds(true).field);
  EXPECT_EQ(nowhere[2].nodes, 1u);
  EXPECT_EQ(nowhere[2].unresolved, 1u);
  EXPECT_EQ(nowhere[2].farthest, -1);
  EXPECT_NE(to_text(nowhere, m, 0.1).find("1 whose phases meet nowhere near them"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(to_json(nowhere, m, 0.1))["quadruple_point"]["unresolved"].get<int>(), 1);
}

// interface_offsets() measures how far nodes lie from where their phases are
// equal: on the meshed four spheres every class is within a small share of h
// (the paper's projection puts them there), and a surface node pushed 0.3 h
// across its sphere becomes the farthest surface node, 0.3 h off.
TEST(Offsets, measure_how_far_nodes_lie_from_their_interface) {
  const Scene scene = test::example_scene("four_spheres.json", 24);
  const double h = scene.grid.h();
  NodeMesh m = mesh_scene(scene);
  const InterfaceOffsets before = interface_offsets(m, *scene.field);
  EXPECT_GT(before[0].nodes, 1000u);
  EXPECT_GT(before[1].nodes, 50u);
  EXPECT_EQ(before[2].nodes, 5u); // the scene's five quadruple points (Stats.closed_surface counts them)
  for (const NodeOffsets& o : before) {
    EXPECT_LT(o.max, 0.05 * h);
    EXPECT_LE(o.rms, o.max);
  }
  // A surface node inside the domain, moved along its pair's gradient difference.
  std::vector<std::set<int32_t>> phases(m.points.size());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int32_t v : m.triangles[t]) phases[size_t(v)].insert(m.pairs[t].begin(), m.pairs[t].end());
  size_t n = 0;
  while (phases[n].size() != 2) ++n;
  const std::vector<int32_t> pair(phases[n].begin(), phases[n].end());
  const Vec3 normal =
      (scene.field->gradient(pair[1], m.points[n]) - scene.field->gradient(pair[0], m.points[n])).normalized();
  m.points[n] += 0.3 * h * normal;
  const InterfaceOffsets after = interface_offsets(m, *scene.field);
  EXPECT_EQ(after[0].farthest, int32_t(n));
  EXPECT_NEAR(after[0].max, 0.3 * h, 0.01 * h);
  EXPECT_EQ(after[1].max, before[1].max); // the other classes are as they were
  // The text names the farthest node; the JSON gives the offsets in h too.
  EXPECT_NE(to_text(after, m, h).find("node " + std::to_string(n)), std::string::npos);
  const std::pair<std::string, std::string> more[] = {{"offsets", to_json(after, m, h)}};
  const auto j = nlohmann::json::parse(to_json(compute_stats(m), {}, &m, {}, more));
  EXPECT_NEAR(j["offsets"]["surface"]["max_h"].get<double>(), 0.3, 0.01);
  EXPECT_EQ(j["offsets"]["surface"]["farthest"]["node"].get<int>(), int(n));
  EXPECT_EQ(j["offsets"]["quadruple_point"]["nodes"].get<int>(), 5);
}
