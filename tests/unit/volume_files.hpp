#pragma once
/// @file volume_files.hpp
/// The volume readers' tests (test_volume_readers.cpp, test_nifti_reader.cpp):
/// small volumes with known voxels and geometry, a fixture with a folder of its
/// own, and the checks that read them back.

#include "refusal.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace vm::volume_test {

namespace fs = std::filesystem;

inline constexpr int64_t NX = 5, NY = 4, NZ = 3, NV = NX * NY * NZ;

/// Voxel n's known label: distinct everywhere, some negative for signed types.
inline int32_t label_at(int64_t n, bool is_signed) { return int32_t(n) - (is_signed ? 30 : 0); }
/// Voxel n's known real value (exact in float), component c.
inline double value_at(int64_t n, int c = 0) { return 0.25 * double(n) - 3.5 + 100.0 * c; }

/// The bytes of `values` as T, in the given byte order.
template <class T>
inline std::string encode(const std::vector<double>& values, bool big_endian) {
  std::string out;
  for (double x : values) {
    const T v = T(x);
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
  }
  return out;
}

inline std::vector<double> labels(bool is_signed, int64_t n = NV) {
  std::vector<double> out;
  for (int64_t i = 0; i < n; ++i) out.push_back(label_at(i, is_signed));
  return out;
}

/// Values interleaved per voxel, `components` per voxel.
inline std::vector<double> values(int components = 1) {
  std::vector<double> out;
  for (int64_t i = 0; i < NV; ++i)
    for (int c = 0; c < components; ++c) out.push_back(value_at(i, c));
  return out;
}

inline std::string zlib_compress(const std::string& raw) {
  uLongf size = compressBound(uLong(raw.size()));
  std::string out(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                      uLong(raw.size()), 9),
            Z_OK);
  out.resize(size);
  return out;
}

/// A rotation with no axis-aligned column, so that swapped rows or columns show.
inline Eigen::Matrix3d rotation() {
  return Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
}

class VolumeReaders : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vm_volumes_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }
  std::string read(const std::string& p) const {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), {}};
  }

  /// The message `reader` throws for `p` (as InvalidInput or IoError, per
  /// `io_error`), "" if it reads.
  static std::string error_of(io::Volume (*reader)(const std::string&), const std::string& p, bool io_error = false) {
    return test::refusal([&] { reader(p); }, io_error);
  }

  fs::path dir_;
};

#define EXPECT_REFUSED(reader, file, problem)                                                                          \
  do {                                                                                                               \
    const std::string msg = error_of(reader, file);                                                                  \
    EXPECT_NE(msg.find(fs::path(file).filename().string()), std::string::npos) << msg;                               \
    EXPECT_NE(msg.find(problem), std::string::npos) << msg;                                                          \
  } while (0)

inline void expect_size(const io::Volume& v, int components = 1) {
  EXPECT_EQ(v.size, (std::array<int64_t, 3>{NX, NY, NZ}));
  EXPECT_EQ(v.components, components);
}

inline void expect_labels(const io::Volume& v, bool is_signed) {
  ASSERT_TRUE(v.integer);
  ASSERT_EQ(v.labels.size(), size_t(NV));
  EXPECT_TRUE(v.values.empty());
  for (int64_t n = 0; n < NV; ++n) ASSERT_EQ(v.labels[n], label_at(n, is_signed)) << "voxel " << n;
}

inline void expect_values(const io::Volume& v, int components = 1) {
  ASSERT_FALSE(v.integer);
  ASSERT_EQ(v.values.size(), size_t(NV * components));
  EXPECT_TRUE(v.labels.empty());
  for (int64_t n = 0; n < NV; ++n)
    for (int c = 0; c < components; ++c)
      ASSERT_EQ(v.values[n * components + c], float(value_at(n, c))) << "voxel " << n << " component " << c;
}

inline void expect_geometry(const io::Volume& v, const Vec3& spacing, const Vec3& origin,
                     const Eigen::Matrix3d& direction = Eigen::Matrix3d::Identity(), double tol = 1e-12) {
  EXPECT_LT((v.spacing - spacing).norm(), tol) << v.spacing.transpose();
  EXPECT_LT((v.origin - origin).norm(), tol) << v.origin.transpose();
  EXPECT_LT((v.direction - direction).norm(), tol) << v.direction;
}


} // namespace vm::volume_test
