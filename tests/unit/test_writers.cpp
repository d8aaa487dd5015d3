// Tests of write_mesh() and write_per_phase_stl(): each format's content on the
// four-sphere scene, phase labels in every format, and failures that leave no file.

#include "fixtures.hpp"
#include "scratch_dir.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/mesh/junctions.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace vm;
namespace fs = std::filesystem;

namespace {

class Writers : public test::ScratchDir {
protected:
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  /// Writes `m` to `name` and returns the file's content.
  std::string written(const NodeMesh& m, const std::string& name) const {
    io::write_mesh(m, path(name));
    return read_bytes(path(name));
  }
};

/// The whitespace-separated words of `text` after the line `keyword` (up to `count` of them).
std::vector<std::string> words_after(const std::string& text, const std::string& keyword, size_t count) {
  const size_t at = text.find("\n" + keyword + "\n");
  std::vector<std::string> words;
  if (at == std::string::npos) return words;
  std::istringstream in(text.substr(at + keyword.size() + 2));
  std::string w;
  while (words.size() < count && in >> w) words.push_back(w);
  return words;
}

/// A triangle as three points, compared up to rotation (orientation kept).
using Corners = std::array<Vec3, 3>;

Corners corners(const NodeMesh& m, size_t t) {
  const auto& tri = m.triangles[t];
  return {m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])]};
}

/// The rotation of `c` that starts at its lexicographically smallest corner,
/// so equal oriented triangles compare equal.
std::array<std::array<double, 3>, 3> oriented_key(const Corners& c) {
  std::array<std::array<double, 3>, 3> k{};
  for (size_t i = 0; i < 3; ++i) k[i] = {c[i].x(), c[i].y(), c[i].z()};
  std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
  return k;
}

Corners rounded_to_float(Corners c) {
  for (Vec3& p : c) p = p.cast<float>().cast<double>();
  return c;
}

/// Triangles of a binary or ASCII STL file.
std::vector<Corners> read_stl(const std::string& p) {
  const std::string data = test::ScratchDir::read_bytes(p);
  std::vector<Corners> tris;
  if (data.rfind("solid ", 0) == 0) {
    std::istringstream in(data);
    std::string w;
    Corners c;
    size_t k = 0;
    while (in >> w)
      if (w == "vertex") {
        in >> c[k].x() >> c[k].y() >> c[k].z();
        if (++k == 3) tris.push_back(c), k = 0;
      }
    return tris;
  }
  uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);
  EXPECT_EQ(data.size(), 84 + 50 * size_t(n)) << p;
  for (uint32_t i = 0; i < n; ++i) {
    float v[12];
    std::memcpy(v, data.data() + 84 + 50 * size_t(i), sizeof v);
    tris.push_back({Vec3(v[3], v[4], v[5]), Vec3(v[6], v[7], v[8]), Vec3(v[9], v[10], v[11])});
    const Vec3 n_file(v[0], v[1], v[2]), n_geom = (tris.back()[1] - tris.back()[0]).cross(tris.back()[2] - tris.back()[0]);
    EXPECT_GT(n_file.dot(n_geom), 0) << p << " facet " << i << ": the stored normal disagrees with the corner order";
  }
  return tris;
}

/// The mesh with labels 0, 10, 20, ... in place of phase ids 0, 1, 2, ...
NodeMesh relabelled(NodeMesh m) {
  for (size_t p = 0; p < m.phase_names.size(); ++p) m.phase_labels.push_back(int32_t(10 * p));
  return m;
}

const std::vector<std::string> kAllExtensions{".ply", ".obj", ".stl", ".msh", ".vtu", ".vtp", ".mesh"};

} // namespace

TEST_F(Writers, known_extensions) {
  EXPECT_EQ(io::output_extensions(), kAllExtensions);
  EXPECT_NO_THROW(io::check_output_format("out.MSH"));
  EXPECT_NO_THROW(io::check_output_format("dir.v2/out.mesh"));
}

TEST_F(Writers, unknown_extension_lists_the_known_ones_and_writes_nothing) {
  for (const char* name : {"m.xyz", "m", "m.ply.gz"}) {
    const std::string p = path(name);
    try {
      io::write_mesh(test::tetrahedron(), p);
      FAIL() << name << ": no error";
    } catch (const InvalidInput& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(p + ": ", 0), 0u) << msg;
      EXPECT_NE(msg.find("(known: .ply, .obj, .stl, .msh, .vtu, .vtp, .mesh)"), std::string::npos) << msg;
    }
  }
  EXPECT_TRUE(files().empty());
}

TEST_F(Writers, malformed_meshes_are_refused_before_any_file_is_made) {
  NodeMesh fewer_pairs = test::tetrahedron();
  fewer_pairs.pairs.pop_back();
  NodeMesh bad_node = test::tetrahedron();
  bad_node.triangles[2][1] = 4;
  NodeMesh bad_pair = test::tetrahedron();
  bad_pair.pairs[0] = {1, 0};
  for (const NodeMesh* m : {&fewer_pairs, &bad_node, &bad_pair})
    for (const std::string& ext : kAllExtensions) {
      EXPECT_THROW(io::write_mesh(*m, path("m" + ext)), IoError) << ext;
      EXPECT_THROW(io::write_per_phase_stl(*m, path("phases")), IoError) << ext;
    }
  EXPECT_TRUE(files().empty());
}

TEST_F(Writers, unwritable_path_names_the_file_and_leaves_nothing) {
  for (const std::string& ext : kAllExtensions) {
    const std::string p = path("missing/m" + ext);
    try {
      io::write_mesh(test::tetrahedron(), p);
      FAIL() << ext << ": no error";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("missing/m"), std::string::npos) << e.what();
    }
  }
  fs::path blocker = dir_ / "file";
  std::ofstream(blocker) << "x";
  EXPECT_THROW(io::write_per_phase_stl(test::tetrahedron(), (blocker / "phases").string()), IoError);
  EXPECT_EQ(files(), std::vector<std::string>{"file"});
}

TEST_F(Writers, obj_has_one_group_per_phase_pair) {
  const NodeMesh m = test::four_spheres();
  EXPECT_EQ(io::write_mesh(m, path("m.obj")), std::vector<std::string>{path("m.obj")});
  std::istringstream in(read_bytes(path("m.obj")));
  std::vector<Vec3> points;
  std::map<std::string, std::multiset<std::array<std::array<double, 3>, 3>>> groups;
  std::string group, line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v") {
      Vec3 p;
      words >> p.x() >> p.y() >> p.z();
      points.push_back(p);
    } else if (kind == "g") {
      words >> group;
      EXPECT_EQ(groups.count(group), 0u) << "group " << group << " split";
      groups[group];
    } else if (kind == "f") {
      int a, b, c;
      words >> a >> b >> c;
      groups[group].insert(oriented_key({points.at(size_t(a - 1)), points.at(size_t(b - 1)), points.at(size_t(c - 1))}));
    }
  }
  ASSERT_EQ(points.size(), m.num_nodes());
  for (size_t n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(points[n], m.points[n]) << "exact coordinates";
  std::map<std::string, std::multiset<std::array<std::array<double, 3>, 3>>> want;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const PhasePair& p = m.pairs[t];
    want[std::to_string(p[0]) + "-" + m.phase_names[size_t(p[0])] + "_" + std::to_string(p[1]) + "-" +
         m.phase_names[size_t(p[1])]]
        .insert(oriented_key(corners(m, t)));
  }
  EXPECT_EQ(groups.size(), 10u);
  EXPECT_TRUE(groups == want) << "each face in the group of its pair, oriented as in the mesh";
  EXPECT_TRUE(groups.count("1-sphere1_2-sphere2"));
}

TEST_F(Writers, stl_writes_one_file_per_phase_pair_named_after_it) {
  const NodeMesh m = test::four_spheres();
  for (bool ascii : {false, true}) {
    fs::remove_all(dir_ / "out");
    fs::create_directories(dir_ / "out");
    const std::vector<std::string> written = io::write_mesh(m, path("out/surf.stl"), io::WriteOptions{ascii});
    ASSERT_EQ(written.size(), 10u);
    EXPECT_FALSE(fs::exists(path("out/surf.stl"))) << "no file at the path itself";
    EXPECT_EQ(written[0], path("out/surf_0-outside_1-sphere1.stl"));
    std::map<std::string, std::multiset<std::array<std::array<double, 3>, 3>>> want, got;
    for (size_t t = 0; t < m.num_triangles(); ++t) {
      const PhasePair& p = m.pairs[t];
      const std::string name = path("out/surf_" + std::to_string(p[0]) + "-" + m.phase_names[size_t(p[0])] + "_" +
                                    std::to_string(p[1]) + "-" + m.phase_names[size_t(p[1])] + ".stl");
      want[name].insert(oriented_key(ascii ? corners(m, t) : rounded_to_float(corners(m, t))));
    }
    for (const std::string& f : written) {
      const std::string data = read_bytes(f);
      EXPECT_EQ(data.rfind("solid", 0) == 0, ascii) << f << ": a binary header must not start with 'solid'";
      for (const Corners& c : read_stl(f)) got[f].insert(oriented_key(c));
    }
    EXPECT_TRUE(got == want) << (ascii ? "ascii" : "binary") << ": normals from the first phase into the second";
  }
}

TEST_F(Writers, per_phase_stl_files_are_closed_and_oriented_outward) {
  const NodeMesh m = test::four_spheres();
  const std::vector<std::string> written = io::write_per_phase_stl(m, path("new/phases"), io::WriteOptions{true});
  ASSERT_EQ(written.size(), 5u);
  std::vector<double> volume;
  for (size_t p = 0; p < 5; ++p) {
    EXPECT_EQ(written[p], path("new/phases/phase_" + std::to_string(p) + "-" + m.phase_names[p] + ".stl"));
    const std::vector<Corners> tris = read_stl(written[p]);
    size_t want = 0;
    for (const PhasePair& pr : m.pairs) want += pr[0] == int32_t(p) || pr[1] == int32_t(p);
    EXPECT_EQ(tris.size(), want);
    // Closed and consistently oriented: every directed edge once, and its reverse once.
    std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> directed;
    double v = 0;
    for (const Corners& c : tris) {
      for (size_t k = 0; k < 3; ++k) {
        const Vec3 &a = c[k], &b = c[(k + 1) % 3];
        ++directed[{{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}}];
      }
      v += c[0].dot(c[1].cross(c[2])) / 6;
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1) << "phase " << p << ": an edge used twice in one direction";
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "phase " << p << ": an open edge";
    }
    volume.push_back(v);
  }
  // Outward normals: positive volume for the spheres; the outside's boundary
  // (the union of the spheres, seen from outside) encloses minus their total.
  double spheres = 0;
  for (size_t p = 1; p < 5; ++p) {
    EXPECT_GT(volume[p], 0.02) << "phase " << p;
    spheres += volume[p];
  }
  EXPECT_NEAR(volume[0], -spheres, 1e-12);
}

TEST_F(Writers, msh_writes_each_node_once_with_physical_groups) {
  const NodeMesh m = test::four_spheres();
  const Junctions j = find_junctions(m);
  const std::string text = written(m, "m.msh");
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n25\n", 0), 0u);
  EXPECT_NE(text.find("2 5 \"1-sphere1_2-sphere2\"\n"), std::string::npos) << "surfaces numbered by pair";
  EXPECT_NE(text.find("\"0-outside_1-sphere1_2-sphere2\"\n"), std::string::npos);
  EXPECT_NE(text.find("\"1-sphere1_2-sphere2_3-sphere3_4-sphere4\"\n"), std::string::npos);

  std::istringstream in(text.substr(text.find("$Nodes\n") + 7));
  size_t blocks, count, min_tag, max_tag;
  in >> blocks >> count >> min_tag >> max_tag;
  EXPECT_EQ(count, m.num_nodes());
  EXPECT_EQ(min_tag, 1u);
  EXPECT_EQ(max_tag, m.num_nodes());
  EXPECT_EQ(blocks, 5u + 10u + 10u);
  std::vector<int> seen(m.num_nodes() + 1, 0);
  for (size_t b = 0; b < blocks; ++b) {
    int dim, tag, parametric;
    size_t n;
    in >> dim >> tag >> parametric >> n;
    std::vector<size_t> tags(n);
    for (size_t& t : tags) in >> t;
    for (size_t t : tags) {
      Vec3 p;
      in >> p.x() >> p.y() >> p.z();
      ASSERT_TRUE(t >= 1 && t <= m.num_nodes());
      ++seen[t];
      EXPECT_EQ(p, m.points[t - 1]);
      // The entity of lowest dimension holding the node.
      EXPECT_EQ(dim, std::max(0, 4 - j.order(t - 1))) << "node " << t;
    }
  }
  EXPECT_EQ(std::count(seen.begin() + 1, seen.end(), 1), std::ptrdiff_t(m.num_nodes())) << "each node once";

  std::istringstream el(text.substr(text.find("$Elements\n") + 10));
  size_t elements, first, last;
  el >> blocks >> elements >> first >> last;
  size_t curve_edges = 0;
  for (const TripleCurve& c : j.curves) curve_edges += c.num_edges();
  EXPECT_EQ(elements, 5 + curve_edges + m.num_triangles());
  EXPECT_EQ(first, 1u);
  EXPECT_EQ(last, elements);
  std::map<int, size_t> by_type;
  std::multiset<std::array<std::array<double, 3>, 3>> triangles, want;
  for (size_t b = 0; b < blocks; ++b) {
    int dim, tag, type;
    size_t n;
    el >> dim >> tag >> type >> n;
    by_type[type] += n;
    const size_t per = type == 15 ? 1 : type == 1 ? 2 : 3;
    for (size_t i = 0; i < n; ++i) {
      size_t id, v[3];
      el >> id;
      for (size_t k = 0; k < per; ++k) el >> v[k];
      if (type == 2) triangles.insert(oriented_key({m.points[v[0] - 1], m.points[v[1] - 1], m.points[v[2] - 1]}));
      if (type == 15) EXPECT_EQ(j.order(v[0] - 1), 4);
    }
  }
  for (size_t t = 0; t < m.num_triangles(); ++t) want.insert(oriented_key(corners(m, t)));
  EXPECT_EQ(by_type[15], 5u);
  EXPECT_EQ(by_type[1], curve_edges);
  EXPECT_TRUE(triangles == want) << "every triangle once, oriented as in the mesh";
}

TEST_F(Writers, msh_curve_ends_on_the_box_are_model_points_without_elements) {
  const NodeMesh m = test::box_t_junction(4);
  const std::string text = written(m, "m.msh");
  // Entities: 2 points (no physical group), 1 curve bounded by them, 3 surfaces.
  std::istringstream in(text.substr(text.find("$Entities\n") + 10));
  size_t points, curves, surfaces, volumes;
  in >> points >> curves >> surfaces >> volumes;
  EXPECT_EQ(points, 2u);
  EXPECT_EQ(curves, 1u);
  EXPECT_EQ(surfaces, 3u);
  for (size_t i = 0; i < points; ++i) {
    double tag, x, y, z, physicals;
    in >> tag >> x >> y >> z >> physicals;
    EXPECT_EQ(physicals, 0) << "a box end is no quadruple point";
    EXPECT_EQ(z, double(i)) << "at z = 0 and z = 1";
  }
  double curve[7];
  for (double& v : curve) in >> v;
  size_t physicals, physical, bounding;
  int from, to;
  in >> physicals >> physical >> bounding >> from >> to;
  EXPECT_EQ(bounding, 2u);
  EXPECT_EQ(std::set<int>({std::abs(from), std::abs(to)}), (std::set<int>{1, 2}));
  EXPECT_EQ(from * to, -2) << "one end positive, the other negative";
  EXPECT_NE(text.find("$Elements\n4 "), std::string::npos) << "element blocks: the curve and 3 surfaces, no points";
  EXPECT_NE(text.find("$Nodes\n6 "), std::string::npos) << "node blocks: 2 points, the curve, 3 surfaces";
}

TEST_F(Writers, vtu_and_vtp_hold_phase_labels_and_junction_order) {
  const NodeMesh m = relabelled(test::four_spheres());
  const Junctions j = find_junctions(m);
  for (const char* ext : {".vtu", ".vtp"}) {
    const std::string text = written(m, std::string("m") + ext);
    const bool grid = std::string(ext) == ".vtu";
    EXPECT_NE(text.find(grid ? "<VTKFile type=\"UnstructuredGrid\"" : "<VTKFile type=\"PolyData\""), std::string::npos);
    EXPECT_NE(text.find("NumberOfPoints=\"" + std::to_string(m.num_nodes()) + "\""), std::string::npos);
    EXPECT_NE(text.find((grid ? "NumberOfCells=\"" : "NumberOfPolys=\"") + std::to_string(m.num_triangles()) + "\""),
              std::string::npos);
    auto array = [&](const std::string& name, size_t count) {
      const size_t at = text.find("Name=\"" + name + "\"");
      EXPECT_NE(at, std::string::npos) << name;
      std::istringstream in(text.substr(text.find('>', at) + 1));
      std::vector<long long> v(count);
      for (auto& x : v) in >> x;
      std::string end;
      in >> end;
      EXPECT_EQ(end, "</DataArray>") << name << ": wrong number of values";
      return v;
    };
    const auto order = array("junction_order", m.num_nodes());
    for (size_t n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(order[n], j.order(n));
    EXPECT_EQ(std::count(order.begin(), order.end(), 4), 5);
    const auto phase0 = array("phase0", m.num_triangles()), phase1 = array("phase1", m.num_triangles());
    for (size_t t = 0; t < m.num_triangles(); ++t) {
      EXPECT_EQ(phase0[t], 10 * m.pairs[t][0]);
      EXPECT_EQ(phase1[t], 10 * m.pairs[t][1]);
    }
    const auto connectivity = array("connectivity", 3 * m.num_triangles());
    for (size_t i = 0; i < connectivity.size(); ++i) ASSERT_EQ(connectivity[i], m.triangles[i / 3][i % 3]);
    EXPECT_EQ(array("offsets", m.num_triangles()).back(), 3 * (long long)m.num_triangles());
    if (grid) EXPECT_EQ(array("types", m.num_triangles())[0], 5);
    EXPECT_EQ(text.find("--", text.find("<!--") + 4), text.find("-->")) << "no '--' inside the comment";
    // The comment names every phase once, in order, by label and name.
    std::string phases;
    for (size_t p = 0; p < m.phase_names.size(); ++p) phases += " " + std::to_string(10 * p) + "-" + m.phase_names[p];
    EXPECT_NE(text.find("Phases:" + phases + " -->"), std::string::npos) << phases;
  }
}

TEST_F(Writers, medit_refers_to_phase_pairs_and_triples_in_its_comments) {
  const NodeMesh m = test::four_spheres();
  const Junctions j = find_junctions(m);
  const std::string text = written(m, "m.mesh");
  EXPECT_EQ(text.rfind("MeshVersionFormatted 2\nDimension 3\n", 0), 0u);
  EXPECT_NE(text.find("#   triangle ref 5: 1-sphere1_2-sphere2\n"), std::string::npos);
  EXPECT_NE(text.find("#   edge ref 1: 0-outside_1-sphere1_2-sphere2\n"), std::string::npos);
  const auto vertices = words_after(text, "Vertices", 1 + 4 * m.num_nodes());
  ASSERT_EQ(vertices.size(), 1 + 4 * m.num_nodes());
  EXPECT_EQ(std::stoul(vertices[0]), m.num_nodes());
  EXPECT_EQ(std::stod(vertices[1 + 4 * 7 + 2]), m.points[7].z());
  const auto triangles = words_after(text, "Triangles", 1 + 4 * m.num_triangles());
  ASSERT_EQ(triangles.size(), 1 + 4 * m.num_triangles());
  std::map<PhasePair, std::set<std::string>> refs;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(std::stoi(triangles[1 + 4 * t + k]), m.triangles[t][k] + 1);
    refs[m.pairs[t]].insert(triangles[4 + 4 * t]);
  }
  std::set<std::string> distinct;
  for (const auto& [pair, r] : refs) {
    EXPECT_EQ(r.size(), 1u) << "one reference per pair";
    distinct.insert(*r.begin());
  }
  EXPECT_EQ(distinct.size(), 10u);
  EXPECT_EQ(*refs[(PhasePair{1, 2})].begin(), "5");
  size_t curve_edges = 0;
  for (const TripleCurve& c : j.curves) curve_edges += c.num_edges();
  const auto edges = words_after(text, "Edges", 1 + 3 * curve_edges);
  ASSERT_EQ(edges.size(), 1 + 3 * curve_edges);
  EXPECT_EQ(std::stoul(edges[0]), curve_edges);
  for (const char* keyword : {"Corners", "RequiredVertices"}) {
    const auto corners = words_after(text, keyword, 6);
    ASSERT_EQ(corners.size(), 6u) << keyword;
    EXPECT_EQ(corners[0], "5");
    for (size_t q = 0; q < 5; ++q) EXPECT_EQ(std::stoi(corners[1 + q]), j.quadruple_points[q] + 1);
  }
  EXPECT_EQ(text.substr(text.size() - 4), "End\n");
}

TEST_F(Writers, labels_and_names_appear_in_every_format) {
  NodeMesh m = relabelled(test::four_spheres());
  m.phase_names[2] = "grain two";
  EXPECT_NE(written(m, "m.msh").find("\"10-sphere1_20-grain-two\""), std::string::npos);
  EXPECT_NE(written(m, "m.mesh").find(": 10-sphere1_20-grain-two_30-sphere3\n"), std::string::npos);
  EXPECT_NE(written(m, "m.obj").find("\ng 10-sphere1_20-grain-two\n"), std::string::npos);
  io::write_mesh(m, path("m.stl"));
  io::write_per_phase_stl(m, path("phases"));
  EXPECT_TRUE(fs::exists(path("m_10-sphere1_20-grain-two.stl")));
  EXPECT_TRUE(fs::exists(path("phases/phase_20-grain-two.stl")));
  m.phase_names.clear();
  EXPECT_NE(written(m, "m.msh").find("\"10_20\""), std::string::npos) << "labels alone without names";
}

TEST_F(Writers, ply_through_write_mesh_round_trips_labels) {
  const NodeMesh m = relabelled(test::four_spheres());
  io::write_mesh(m, path("m.ply"), io::WriteOptions{true});
  const NodeMesh back = io::read_ply(path("m.ply"));
  EXPECT_EQ(back.phase_labels, m.phase_labels);
  EXPECT_EQ(back.pairs, m.pairs);
  EXPECT_EQ(back.phase_names, m.phase_names);
  EXPECT_NE(read_bytes(path("m.ply")).find("\ncomment phase 40 sphere4\n"), std::string::npos);
}

TEST_F(Writers, colours_go_where_a_format_holds_a_table_of_them) {
  NodeMesh m = relabelled(test::four_spheres()); // labels 0, 10, 20, 30, 40
  m.phase_colors = {std::nullopt, Rgb{1, 0.5f, 0}, Rgb{0, 0.25f, 1}}; // sphere1 and sphere2; the rest none
  // VTU and VTP: one field-data table, a row (label, red, green, blue) per coloured phase.
  for (const char* name : {"m.vtu", "m.vtp"}) {
    const std::string text = written(m, name);
    EXPECT_NE(text.find("Name=\"phase_colors\" NumberOfComponents=\"4\" ComponentName0=\"label\" ComponentName1=\"red\""
                        " ComponentName2=\"green\" ComponentName3=\"blue\" NumberOfTuples=\"2\" format=\"ascii\">\n"
                        "        10 1 0.5 0\n        20 0 0.25 1\n      </DataArray>"),
              std::string::npos)
        << name;
  }
  // OBJ: a material per group in <stem>.mtl, the pair's second phase's colour, else its first's.
  EXPECT_EQ(io::write_mesh(m, path("m.obj")), (std::vector<std::string>{path("m.obj"), path("m.mtl")}));
  const std::string obj = read_bytes(path("m.obj")), mtl = read_bytes(path("m.mtl"));
  EXPECT_NE(obj.find("\nmtllib m.mtl\n"), std::string::npos);
  EXPECT_NE(obj.find("\ng 10-sphere1_20-sphere2\nusemtl 10-sphere1_20-sphere2\n"), std::string::npos);
  EXPECT_NE(mtl.find("#   10-sphere1 1 0.5 0\n#   20-sphere2 0 0.25 1\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("\nnewmtl 0-outside_10-sphere1\nKd 1 0.5 0\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("\nnewmtl 10-sphere1_20-sphere2\nKd 0 0.25 1\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("\nnewmtl 10-sphere1_30-sphere3\nKd 1 0.5 0\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("\nnewmtl 30-sphere3_40-sphere4\n"), std::string::npos) << "a material without colour";
  EXPECT_EQ(mtl.find("\nnewmtl 30-sphere3_40-sphere4\nKd"), std::string::npos);
  // Without colours, no materials at all: the OBJ is what it was.
  m.phase_colors.clear();
  EXPECT_EQ(io::write_mesh(m, path("plain.obj")), (std::vector<std::string>{path("plain.obj")}));
  EXPECT_EQ(read_bytes(path("plain.obj")).find("mtl"), std::string::npos);
  EXPECT_EQ(written(m, "plain.vtu").find("phase_colors"), std::string::npos);
}
