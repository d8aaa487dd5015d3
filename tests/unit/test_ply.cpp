#include "fixtures.hpp"
#include "scratch_dir.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/ply.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

using namespace vm;
namespace fs = std::filesystem;

namespace {

class Ply : public test::ScratchDir {
protected:
  std::string write_text(const std::string& name, const std::string& content) const {
    std::ofstream(path(name), std::ios::binary) << content;
    return path(name);
  }

  /// The IoError message read_ply gives for `p` ("" if it reads).
  static std::string error_of(const std::string& p) {
    try {
      io::read_ply(p);
    } catch (const IoError& e) {
      return e.what();
    }
    return "";
  }

};

/// A mesh whose coordinates need all 17 significant digits.
NodeMesh awkward_mesh() {
  NodeMesh m = test::four_phase_point();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& p : m.points) p += Vec3(u(rng), u(rng), u(rng)) * 1e-3 + Vec3(1.0 / 3, 12345.678901234567, -1e-300);
  m.points[0].x() = -0.0;
  m.phase_names = {"matrix", "grain one", "b", "", "d"};
  m.domain = Box{Vec3(-0.1, 1.0 / 7, -2), Vec3(3.3, 12346, 1e10)};
  m.grid_spacing = 1.0 / 3;
  return m;
}

bool bitwise_equal(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0;
}

void expect_exact(const NodeMesh& got, const NodeMesh& want) {
  ASSERT_EQ(got.points.size(), want.points.size());
  for (size_t i = 0; i < want.points.size(); ++i)
    EXPECT_TRUE(bitwise_equal(got.points[i], want.points[i])) << "node " << i;
  EXPECT_EQ(got.triangles, want.triangles);
  EXPECT_EQ(got.pairs, want.pairs);
  EXPECT_EQ(got.phase_names, want.phase_names);
  EXPECT_TRUE(bitwise_equal(got.domain.min, want.domain.min));
  EXPECT_TRUE(bitwise_equal(got.domain.max, want.domain.max));
  EXPECT_EQ(got.grid_spacing, want.grid_spacing); // all 17 digits
}

const char* const kAsciiHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                 "property double z\n";

} // namespace

TEST_F(Ply, binary_round_trip_is_bitwise_exact) {
  const NodeMesh m = awkward_mesh();
  io::write_ply(m, path("m.ply"));
  expect_exact(io::read_ply(path("m.ply")), m);
  EXPECT_EQ(read_bytes(path("m.ply")).substr(0, 36), "ply\nformat binary_little_endian 1.0\n");
}

TEST_F(Ply, ascii_round_trip_is_bitwise_exact) {
  const NodeMesh m = awkward_mesh();
  io::write_ply(m, path("m.ply"), true);
  expect_exact(io::read_ply(path("m.ply")), m);
  EXPECT_EQ(read_bytes(path("m.ply")).substr(0, 21), "ply\nformat ascii 1.0\n");
}

TEST_F(Ply, write_leaves_no_temporary_and_replaces_the_target) {
  write_text("m.ply", "old");
  io::write_ply(test::tetrahedron(), path("m.ply"));
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) files += (void(e), 1);
  EXPECT_EQ(files, 1u);
  EXPECT_EQ(io::read_ply(path("m.ply")).triangles.size(), 4u);
}

// A run killed while writing (kill -9) leaves its m.ply.tmp-<pid>; the next
// write of m.ply removes it, but not a live process's nor other files.
TEST_F(Ply, write_removes_what_killed_runs_left_and_nothing_else) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0); // its pid now belongs to no process (bar reuse within microseconds)
  const std::string dead = "m.ply.tmp-" + std::to_string(child);
  const std::string live = "m.ply.tmp-" + std::to_string(::getppid());
  for (const std::string& name : {dead, live, std::string("m.ply.tmp-x1"), std::string("n.ply.tmp-1")})
    write_text(name, "partial");
  io::write_ply(test::tetrahedron(), path("m.ply"));
  EXPECT_FALSE(fs::exists(path(dead)));
  for (const std::string& name : {live, std::string("m.ply.tmp-x1"), std::string("n.ply.tmp-1"), std::string("m.ply")})
    EXPECT_TRUE(fs::exists(path(name))) << name;
}

TEST_F(Ply, write_to_a_missing_directory_names_the_path) {
  const std::string p = path("no/such/dir/m.ply");
  try {
    io::write_ply(test::tetrahedron(), p);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(p + ": ", 0), 0u) << e.what();
  }
}

TEST_F(Ply, domain_defaults_to_the_bounding_box) {
  const std::string p =
      write_text("m.ply", std::string(kAsciiHeader) + "element face 1\nproperty list uchar int vertex_indices\n"
                                                      "property int phase0\nproperty int phase1\nend_header\n"
                                                      "0 0 0\n2 0 -1\n0 3 0\n3 0 1 2 0 1\n");
  const NodeMesh m = io::read_ply(p);
  EXPECT_EQ(m.domain.min, Vec3(0, 0, -1));
  EXPECT_EQ(m.domain.max, Vec3(2, 3, 0));
  EXPECT_EQ(m.grid_spacing, 0); // not known
  EXPECT_EQ(m.pairs[0], (PhasePair{0, 1}));
}

TEST_F(Ply, other_layouts_are_read) {
  // Big-endian, float coordinates, ushort list counts and uint indices, an
  // extra vertex property, an extra face list and an extra element.
  std::string body;
  auto be = [&body](auto v) {
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    for (size_t i = sizeof v; i-- > 0;) body += b[i];
  };
  const float xyz[3][3] = {{0, 0, 0}, {1.5f, 0, 0}, {0, 2.25f, 0}};
  for (const auto& p : xyz) {
    be(p[0]), be(p[1]), be(p[2]);
    be(uint8_t(9)); // "quality"
  }
  be(uint16_t(3)), be(uint32_t(0)), be(uint32_t(1)), be(uint32_t(2));
  be(int16_t(2)), be(uint8_t(2)), be(double(7)), be(double(8)), be(int16_t(5));
  be(int32_t(42)); // the extra element
  const std::string p = write_text(
      "be.ply", "ply\nformat binary_big_endian 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\n"
                "property float y\nproperty float z\nproperty uchar quality\nelement face 1\n"
                "property list ushort uint vertex_indices\nproperty short phase0\nproperty list uchar double "
                "normals\nproperty short phase1\nelement extra 1\nproperty int n\nend_header\n" +
                    body);
  const NodeMesh m = io::read_ply(p);
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_EQ(m.points[1], Vec3(1.5, 0, 0));
  EXPECT_EQ(m.points[2], Vec3(0, 2.25, 0));
  EXPECT_EQ(m.triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  // Labels 2 and 5 become phases 0 and 1.
  EXPECT_EQ(m.pairs[0], (PhasePair{0, 1}));
  EXPECT_EQ(m.phase_labels, (std::vector<int32_t>{2, 5}));
}

TEST_F(Ply, bad_files_give_one_line_errors_naming_the_file) {
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nproperty int phase0\n"
                            "property int phase1\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "empty file"},
      {"hello world\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\nelement vertex 1\n", "no end_header"},
      {"ply\nformat xml 1.0\nend_header\n", "unknown PLY format 'xml'"},
      {"ply\nelement vertex 0\nend_header\n", "no format line"},
      {"ply\nformat ascii 1.0\nelement vertex 0\nproperty quad x\nend_header\n", "unknown property type"},
      {"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
       "no vertex element"},
      {std::string(kAsciiHeader) + "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "face property phase0 missing (not a voronoimesh PLY?)"},
      {std::string(kAsciiHeader) + faces + "4 0 1 2 0 0 1\n", "face 0 has 4 vertices (only triangles"},
      {std::string(kAsciiHeader) + faces + "3 0 1 3 0 1\n", "vertex index 3 out of range (3 vertices)"},
      {std::string(kAsciiHeader) + faces + "3 0 1 -1 0 1\n", "vertex index -1 out of range"},
      {std::string(kAsciiHeader) + faces + "3 0 1 2 0\n", "truncated"},
      {std::string(kAsciiHeader) + faces + "3 0 1 2 0 1.5\n", "bad number '1.5' in face 0"},
      {std::string(kAsciiHeader) + faces + "3 0 1 2 0 1\n7\n", "unexpected data after the last element"},
      {"ply\nformat binary_little_endian 1.0\nelement vertex 999999999\nproperty double x\n"
       "property double y\nproperty double z\nelement face 0\nproperty list uchar int vertex_indices\n"
       "property int phase0\nproperty int phase1\nend_header\n",
       "truncated: element 'vertex' declares 999999999 items"},
      {"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
       "property double z\nelement face 0\nproperty list uchar int vertex_indices\nproperty int phase0\n"
       "property int phase1\nend_header\n1234567",
       "truncated"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string p = write_text("bad" + std::to_string(i) + ".ply", cases[i].first);
    const std::string msg = error_of(p);
    EXPECT_EQ(msg.rfind(p + ": ", 0), 0u) << "case " << i << ": " << msg;
    EXPECT_NE(msg.find(cases[i].second), std::string::npos) << "case " << i << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "case " << i << ": " << msg;
  }
  EXPECT_NE(error_of(path("missing.ply")).find("missing.ply: cannot open"), std::string::npos);
  EXPECT_NE(error_of(dir_.string()).find("is a directory"), std::string::npos);
}

TEST_F(Ply, every_truncation_of_a_valid_file_is_an_error) {
  for (bool ascii : {false, true}) {
    io::write_ply(test::two_cubes(1), path("m.ply"), ascii);
    const std::string full = read_bytes(path("m.ply"));
    // Ascii may lose trailing whitespace (or a final digit's neighbours) and stay
    // parseable only when nothing but the last newline is cut.
    for (size_t len = 0; len + 1 < full.size(); ++len) {
      const std::string p = write_text("cut.ply", full.substr(0, len));
      EXPECT_NE(error_of(p), "") << (ascii ? "ascii" : "binary") << " cut at " << len;
    }
  }
}

TEST_F(Ply, corrupted_bytes_never_crash) {
  io::write_ply(test::two_cubes(2), path("m.ply"));
  const std::string full = read_bytes(path("m.ply"));
  std::mt19937 rng(99);
  size_t errors = 0;
  for (int iter = 0; iter < 2000; ++iter) {
    std::string bytes = full;
    for (int k = 0; k < 4; ++k) bytes[rng() % bytes.size()] = char(rng());
    const std::string p = write_text("fuzz.ply", bytes);
    try {
      io::read_ply(p);
    } catch (const IoError& e) {
      ++errors;
      EXPECT_EQ(std::string(e.what()).rfind(p + ": ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(errors, 0u);
}

TEST_F(Ply, labels_round_trip_and_absent_phases_keep_their_comment) {
  NodeMesh m = test::two_cubes(1); // phases 0, 1, 2
  m.phase_labels = {1, 4, 6, 9};   // phase 3 (label 9) has no triangle
  m.phase_names = {"matrix", "", "grain", "pore"};
  for (bool ascii : {false, true}) {
    io::write_ply(m, path("m.ply"), ascii);
    const std::string text = read_bytes(path("m.ply"));
    for (const char* line : {"comment phase 1 matrix\n", "comment phase 4 \n", "comment phase 9 pore\n"})
      EXPECT_NE(text.find(line), std::string::npos) << line;
    const NodeMesh back = io::read_ply(path("m.ply"));
    expect_exact(back, m);
    EXPECT_EQ(back.phase_labels, m.phase_labels);
  }
  m.phase_labels.clear();
  m.phase_names.clear();
  io::write_ply(m, path("m.ply"));
  const NodeMesh plain = io::read_ply(path("m.ply"));
  EXPECT_TRUE(plain.phase_labels.empty()) << "identity labels are not stored";
  EXPECT_TRUE(plain.phase_names.empty()) << "no names when none were given";
  EXPECT_NE(read_bytes(path("m.ply")).find("comment phase 2 \n"), std::string::npos);
}

TEST_F(Ply, labels_without_comments_become_compact_ids) {
  const std::string p = write_text("m.ply", std::string(kAsciiHeader) +
                                                "element face 2\nproperty list uchar int vertex_indices\n"
                                                "property int phase0\nproperty int phase1\nend_header\n"
                                                "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 2 5\n3 0 2 1 -3 5\n");
  const NodeMesh m = io::read_ply(p);
  EXPECT_EQ(m.phase_labels, (std::vector<int32_t>{-3, 2, 5}));
  EXPECT_EQ(m.pairs, (std::vector<PhasePair>{{1, 2}, {0, 2}}));
  EXPECT_TRUE(m.phase_names.empty());
}

TEST_F(Ply, a_phase_described_twice_is_an_error) {
  const std::string p = write_text("m.ply", "ply\nformat ascii 1.0\ncomment phase 3 a\ncomment phase 3 b\n"
                                            "element vertex 0\nproperty double x\nproperty double y\n"
                                            "property double z\nelement face 0\nproperty list uchar int "
                                            "vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n");
  EXPECT_NE(error_of(p).find("phase 3 is described twice"), std::string::npos) << error_of(p);
}

TEST_F(Ply, colours_round_trip_on_lines_of_their_own) {
  NodeMesh m = test::two_cubes(1); // phases 0, 1, 2
  m.phase_labels = {1, 4, 6};
  m.phase_names = {"matrix", "grain one", "pore"};
  m.phase_colors = {std::nullopt, Rgb{0.3f, 0.5f, 1}}; // phase 2: past the end, no colour either
  for (bool ascii : {false, true}) {
    io::write_ply(m, path("m.ply"), ascii);
    const std::string text = read_bytes(path("m.ply"));
    EXPECT_NE(text.find("comment phase 4 grain one\ncomment phase_color 4 0.3 0.5 1\n"), std::string::npos);
    EXPECT_EQ(text.find("phase_color 1 "), std::string::npos) << "a phase without colour has no colour line";
    const NodeMesh back = io::read_ply(path("m.ply"));
    expect_exact(back, m);
    EXPECT_EQ(back.phase_colors, m.phase_colors); // the float text reads back to the same float
  }
}

TEST_F(Ply, malformed_colour_and_grid_spacing_comments_are_errors) {
  const std::string rest = "element vertex 0\nproperty double x\nproperty double y\nproperty double z\n"
                           "element face 0\nproperty list uchar int vertex_indices\nproperty int phase0\n"
                           "property int phase1\nend_header\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"comment phase 3 a\ncomment phase_color 3 0.5 0.5\n", "bad phase_color comment"},
      {"comment phase 3 a\ncomment phase_color 3 0.5 0.5 2\n", "three numbers in [0, 1]"},
      {"comment phase 3 a\ncomment phase_color x 0.5 0.5 0.5\n", "bad phase_color comment"},
      {"comment phase 3 a\ncomment phase_color 3 0 0 0\ncomment phase_color 3 1 1 1\n", "phase 3 has two colours"},
      {"comment phase 3 a\ncomment phase_color 4 0 0 0\n", "phase_color comment for label 4, which no phase has"},
      {"comment grid_spacing 0\n", "bad grid_spacing comment"},
      {"comment grid_spacing 0.1 0.2\n", "expected one positive number"},
      {"comment grid_spacing nan\n", "bad grid_spacing comment"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string p = write_text("c" + std::to_string(i) + ".ply", "ply\nformat ascii 1.0\n" + cases[i].first + rest);
    EXPECT_NE(error_of(p).find(cases[i].second), std::string::npos) << "case " << i << ": " << error_of(p);
  }
}
