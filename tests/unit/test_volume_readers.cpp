// The NIfTI, MetaImage and INR readers: small volumes with known voxels and
// geometry written through the formats' own libraries (nifti2_io, zlib) or
// byte by byte, read back and compared; then broken files, each of which must
// be refused with a message naming the file and the problem.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "refusal.hpp"

#include <gtest/gtest.h>
#include <nifti2_io.h>
#include <zlib.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

using namespace vm;
namespace fs = std::filesystem;

namespace {

constexpr int64_t NX = 5, NY = 4, NZ = 3, NV = NX * NY * NZ;

/// Voxel n's known label: distinct everywhere, some negative for signed types.
int32_t label_at(int64_t n, bool is_signed) { return int32_t(n) - (is_signed ? 30 : 0); }
/// Voxel n's known real value (exact in float), component c.
double value_at(int64_t n, int c = 0) { return 0.25 * double(n) - 3.5 + 100.0 * c; }

/// The bytes of `values` as T, in the given byte order.
template <class T>
std::string encode(const std::vector<double>& values, bool big_endian) {
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

std::vector<double> labels(bool is_signed, int64_t n = NV) {
  std::vector<double> out;
  for (int64_t i = 0; i < n; ++i) out.push_back(label_at(i, is_signed));
  return out;
}

/// Values interleaved per voxel, `components` per voxel.
std::vector<double> values(int components = 1) {
  std::vector<double> out;
  for (int64_t i = 0; i < NV; ++i)
    for (int c = 0; c < components; ++c) out.push_back(value_at(i, c));
  return out;
}

std::string zlib_compress(const std::string& raw) {
  uLongf size = compressBound(uLong(raw.size()));
  std::string out(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                      uLong(raw.size()), 9),
            Z_OK);
  out.resize(size);
  return out;
}

/// A rotation with no axis-aligned column, so that swapped rows or columns show.
Eigen::Matrix3d rotation() {
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

void expect_size(const io::Volume& v, int components = 1) {
  EXPECT_EQ(v.size, (std::array<int64_t, 3>{NX, NY, NZ}));
  EXPECT_EQ(v.components, components);
}

void expect_labels(const io::Volume& v, bool is_signed) {
  ASSERT_TRUE(v.integer);
  ASSERT_EQ(v.labels.size(), size_t(NV));
  EXPECT_TRUE(v.values.empty());
  for (int64_t n = 0; n < NV; ++n) ASSERT_EQ(v.labels[n], label_at(n, is_signed)) << "voxel " << n;
}

void expect_values(const io::Volume& v, int components = 1) {
  ASSERT_FALSE(v.integer);
  ASSERT_EQ(v.values.size(), size_t(NV * components));
  EXPECT_TRUE(v.labels.empty());
  for (int64_t n = 0; n < NV; ++n)
    for (int c = 0; c < components; ++c)
      ASSERT_EQ(v.values[n * components + c], float(value_at(n, c))) << "voxel " << n << " component " << c;
}

void expect_geometry(const io::Volume& v, const Vec3& spacing, const Vec3& origin,
                     const Eigen::Matrix3d& direction = Eigen::Matrix3d::Identity(), double tol = 1e-12) {
  EXPECT_LT((v.spacing - spacing).norm(), tol) << v.spacing.transpose();
  EXPECT_LT((v.origin - origin).norm(), tol) << v.origin.transpose();
  EXPECT_LT((v.direction - direction).norm(), tol) << v.direction;
}

// ---------------------------------------------------------------- NIfTI

struct NiftiFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using Nim = std::unique_ptr<nifti_image, NiftiFree>;

/// A NIfTI-1 image of NX x NY x NZ (x `components` in dim[5]) holding `raw`
/// (in NIfTI's order, components slowest), with pixdim 1.5 x 2 x 0.5 and no
/// transform; `file_type` is NIFTI_FTYPE_NIFTI1_1 (.nii) or _1_2 (.hdr/.img).
Nim make_nifti(int datatype, const std::string& raw, int components = 1, int64_t nt = 1) {
  const int64_t dims[8] = {components > 1 ? 5 : nt > 1 ? 4 : 3, NX, NY, NZ, nt, components, 1, 1};
  Nim nim(nifti_make_new_nim(dims, datatype, 1));
  EXPECT_EQ(size_t(nim->nvox) * size_t(nim->nbyper), raw.size());
  std::memcpy(nim->data, raw.data(), raw.size());
  nim->pixdim[1] = nim->dx = 1.5;
  nim->pixdim[2] = nim->dy = 2;
  nim->pixdim[3] = nim->dz = 0.5;
  nim->qform_code = nim->sform_code = 0;
  return nim;
}

void write_nifti(nifti_image* nim, const std::string& file, int file_type = NIFTI_FTYPE_NIFTI1_1) {
  nim->nifti_type = file_type;
  ASSERT_EQ(nifti_set_filenames(nim, file.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  ASSERT_TRUE(fs::exists(file)) << file;
}

TEST_F(VolumeReaders, nifti_sform_int16) {
  Nim nim = make_nifti(DT_INT16, encode<int16_t>(labels(true), false));
  // The sform differs from the pixdims and a qform, so reading either shows.
  const Vec3 spacing(0.7, 1.3, 2.9), origin(-12.5, 7.25, 3);
  const Eigen::Matrix3d steps = rotation() * spacing.asDiagonal();
  nim->sform_code = NIFTI_XFORM_SCANNER_ANAT;
  nim->qform_code = NIFTI_XFORM_SCANNER_ANAT;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) nim->sto_xyz.m[r][c] = steps(r, c);
    nim->sto_xyz.m[r][3] = origin[r];
  }
  write_nifti(nim.get(), path("a.nii"));
  const io::Volume v = io::read_nifti(path("a.nii"));
  expect_size(v);
  expect_labels(v, true);
  // The file keeps the sform in float32.
  expect_geometry(v, spacing, origin, rotation(), 1e-6);
}

TEST_F(VolumeReaders, nifti_gz_qform_float32) {
  Nim nim = make_nifti(DT_FLOAT32, encode<float>(values(), false));
  // 90 degrees about z: quaternion (cos 45, 0, 0, sin 45).
  nim->qform_code = NIFTI_XFORM_ALIGNED_ANAT;
  nim->quatern_b = nim->quatern_c = 0;
  nim->quatern_d = std::sqrt(0.5);
  nim->qoffset_x = 4;
  nim->qoffset_y = -5;
  nim->qoffset_z = 6;
  nim->qfac = 1;
  write_nifti(nim.get(), path("b.nii.gz"));
  ASSERT_EQ(read(path("b.nii.gz")).substr(0, 2), "\x1f\x8b"); // really compressed
  const io::Volume v = io::read_nifti(path("b.nii.gz"));
  expect_size(v);
  expect_values(v);
  Eigen::Matrix3d rz;
  rz << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expect_geometry(v, Vec3(1.5, 2, 0.5), Vec3(4, -5, 6), rz, 1e-6);
}

TEST_F(VolumeReaders, nifti_pair_pixdim_only_uint8_and_float64) {
  Nim nim = make_nifti(DT_UINT8, encode<uint8_t>(labels(false), false));
  write_nifti(nim.get(), path("c.hdr"), NIFTI_FTYPE_NIFTI1_2);
  ASSERT_TRUE(fs::exists(path("c.img")));
  io::Volume v = io::read_nifti(path("c.hdr"));
  expect_size(v);
  expect_labels(v, false);
  expect_geometry(v, Vec3(1.5, 2, 0.5), Vec3::Zero());

  Nim d = make_nifti(DT_FLOAT64, encode<double>(values(), false));
  write_nifti(d.get(), path("d.nii"));
  v = io::read_nifti(path("d.nii"));
  expect_values(v);
}

TEST_F(VolumeReaders, nifti2_reads_too) {
  // nifti2_io 3.0.1 writes a NIfTI-2 file without its header; build it from the library's struct.
  Nim nim = make_nifti(DT_INT32, encode<int32_t>(labels(true), false));
  nifti_2_header hdr;
  ASSERT_EQ(nifti_convert_nim2n2hdr(nim.get(), &hdr), 0);
  std::memcpy(hdr.magic, "n+2\0\r\n\032\n", 8);
  hdr.vox_offset = 544;
  write("two.nii", std::string(reinterpret_cast<const char*>(&hdr), sizeof hdr) + std::string(4, '\0') +
                       encode<int32_t>(labels(true), false));
  ASSERT_EQ(sizeof hdr, 540u);
  const io::Volume v = io::read_nifti(path("two.nii"));
  expect_size(v);
  expect_labels(v, true);
  expect_geometry(v, Vec3(1.5, 2, 0.5), Vec3::Zero());
}

TEST_F(VolumeReaders, nifti_scaled_integers_become_values) {
  Nim nim = make_nifti(DT_UINT16, encode<uint16_t>(labels(false), false));
  nim->scl_slope = 0.5;
  nim->scl_inter = -2;
  write_nifti(nim.get(), path("s.nii"));
  const io::Volume v = io::read_nifti(path("s.nii"));
  ASSERT_FALSE(v.integer);
  ASSERT_EQ(v.values.size(), size_t(NV));
  for (int64_t n = 0; n < NV; ++n) ASSERT_EQ(v.values[n], float(0.5 * label_at(n, false) - 2));
}

TEST_F(VolumeReaders, nifti_vector_components_interleaved) {
  // NIfTI stores the component axis slowest; the Volume interleaves per voxel.
  std::vector<double> planar;
  for (int c = 0; c < 2; ++c)
    for (int64_t n = 0; n < NV; ++n) planar.push_back(value_at(n, c));
  Nim nim = make_nifti(DT_FLOAT32, encode<float>(planar, false), 2);
  nim->intent_code = NIFTI_INTENT_VECTOR;
  write_nifti(nim.get(), path("vec.nii"));
  const io::Volume v = io::read_nifti(path("vec.nii"));
  expect_size(v, 2);
  expect_values(v, 2);
}

TEST_F(VolumeReaders, nifti_big_endian) {
  // nifti2_io writes the machine's order; build a big-endian file from its header.
  Nim nim = make_nifti(DT_INT32, encode<int32_t>(labels(true), false));
  nim->iname_offset = 352;
  nifti_1_header hdr;
  ASSERT_EQ(nifti_convert_nim2n1hdr(nim.get(), &hdr), 0);
  std::memcpy(hdr.magic, "n+1\0", 4);
  hdr.vox_offset = 352;
  swap_nifti_header(&hdr, 1);
  std::string bytes(reinterpret_cast<const char*>(&hdr), sizeof hdr);
  bytes += std::string(4, '\0') + encode<int32_t>(labels(true), true);
  write("be.nii", bytes);
  const io::Volume v = io::read_nifti(path("be.nii"));
  expect_size(v);
  expect_labels(v, true);
  expect_geometry(v, Vec3(1.5, 2, 0.5), Vec3::Zero());
}

TEST_F(VolumeReaders, nifti_bad_files) {
  Nim nim = make_nifti(DT_INT16, encode<int16_t>(labels(true), false));
  write_nifti(nim.get(), path("good.nii"));
  const std::string good = read(path("good.nii"));

  write("truncated.nii", good.substr(0, good.size() - 7));
  EXPECT_REFUSED(io::read_nifti, path("truncated.nii"), "truncated");

  std::string bad_magic = good;
  bad_magic.replace(344, 4, std::string("xyz\0", 4));
  write("magic.nii", bad_magic);
  EXPECT_REFUSED(io::read_nifti, path("magic.nii"), "magic");

  write("garbage.nii", std::string(100, 'x'));
  EXPECT_REFUSED(io::read_nifti, path("garbage.nii"), "not a NIfTI file");

  Nim series = make_nifti(DT_INT16, encode<int16_t>(labels(true, NV * 2), false), 1, 2);
  write_nifti(series.get(), path("series.nii"));
  EXPECT_REFUSED(io::read_nifti, path("series.nii"), "time series (dim[4] = 2)");

  Nim wide = make_nifti(DT_INT64, encode<int64_t>(labels(true), false));
  write_nifti(wide.get(), path("int64.nii"));
  EXPECT_REFUSED(io::read_nifti, path("int64.nii"), "datatype INT64");

  std::vector<double> big = labels(false);
  big[17] = 3e9;
  Nim u32 = make_nifti(DT_UINT32, encode<uint32_t>(big, false));
  write_nifti(u32.get(), path("uint32.nii"));
  EXPECT_REFUSED(io::read_nifti, path("uint32.nii"), "label 3000000000 at voxel (2, 3, 0) is beyond the int32 range");

  Nim flat = make_nifti(DT_UINT8, encode<uint8_t>(labels(false), false));
  flat->pixdim[2] = flat->dy = 0;
  write_nifti(flat.get(), path("pixdim.nii"));
  EXPECT_REFUSED(io::read_nifti, path("pixdim.nii"), "pixdim[2] is 0");

  Nim pair = make_nifti(DT_UINT8, encode<uint8_t>(labels(false), false));
  write_nifti(pair.get(), path("pair.hdr"), NIFTI_FTYPE_NIFTI1_2);
  fs::remove(path("pair.img"));
  const std::string msg = error_of(io::read_nifti, path("pair.hdr"), true);
  EXPECT_NE(msg.find("pair.hdr"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open its image file"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pair.img"), std::string::npos) << msg;

  EXPECT_NE(error_of(io::read_nifti, path("missing.nii"), true).find("missing.nii: cannot open"), std::string::npos);
}

// ---------------------------------------------------------------- MetaImage

/// A 3-D MetaImage header for NX x NY x NZ, `extra` lines before ElementDataFile.
std::string mha_header(const std::string& type, const std::string& extra, const std::string& data_file = "LOCAL") {
  return "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\nElementType = " + type + "\n" + extra +
         "ElementDataFile = " + data_file + "\n";
}

TEST_F(VolumeReaders, metaimage_local_short_with_transform) {
  const Eigen::Matrix3d r = rotation();
  std::ostringstream m;
  m.precision(17);
  // Each run of three values is one axis direction: the columns of r.
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m << r(row, c) << ' ';
  const std::string header = mha_header("MET_SHORT", "BinaryData = True\nBinaryDataByteOrderMSB = False\n"
                                                     "ElementSpacing = 0.5 1.25 3\nOffset = -1 2.5 7\n"
                                                     "TransformMatrix = " + m.str() + "\nAnatomicalOrientation = RAI\n");
  write("a.mha", header + encode<int16_t>(labels(true), false));
  const io::Volume v = io::read_metaimage(path("a.mha"));
  expect_size(v);
  expect_labels(v, true);
  expect_geometry(v, Vec3(0.5, 1.25, 3), Vec3(-1, 2.5, 7), r);
}

TEST_F(VolumeReaders, metaimage_big_endian_float_and_uint) {
  write("f.mha", mha_header("MET_FLOAT", "ElementByteOrderMSB = True\nPosition = 1 2 3\n") +
                     encode<float>(values(), true));
  io::Volume v = io::read_metaimage(path("f.mha"));
  expect_values(v);
  expect_geometry(v, Vec3::Ones(), Vec3(1, 2, 3));

  write("u.mha", mha_header("MET_UINT", "BinaryDataByteOrderMSB = True\n") + encode<uint32_t>(labels(false), true));
  v = io::read_metaimage(path("u.mha"));
  expect_labels(v, false);
}

TEST_F(VolumeReaders, metaimage_detached_uchar_with_header_size) {
  // ElementSize stands in for a missing ElementSpacing; HeaderSize skips a preamble.
  write("d.mhd", mha_header("MET_UCHAR", "ElementSize = 2 3 4\nHeaderSize = 10\n", "d.raw"));
  write("d.raw", std::string(10, 'p') + encode<uint8_t>(labels(false), false));
  io::Volume v = io::read_metaimage(path("d.mhd"));
  expect_size(v);
  expect_labels(v, false);
  expect_geometry(v, Vec3(2, 3, 4), Vec3::Zero());

  // HeaderSize = -1: the data are the last bytes of the file.
  write("e.mhd", mha_header("MET_CHAR", "HeaderSize = -1\n", "e.raw"));
  write("e.raw", std::string(33, 'p') + encode<int8_t>(labels(true), false));
  v = io::read_metaimage(path("e.mhd"));
  expect_labels(v, true);
}

TEST_F(VolumeReaders, metaimage_compressed) {
  const std::string z = zlib_compress(encode<double>(values(), false));
  write("c.mha", mha_header("MET_DOUBLE", "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) +
                                              "\n") +
                     z);
  io::Volume v = io::read_metaimage(path("c.mha"));
  expect_values(v);

  // Detached, without CompressedDataSize: the whole file.
  const std::string zu = zlib_compress(encode<uint16_t>(labels(false), false));
  write("c.mhd", mha_header("MET_USHORT", "CompressedData = True\n", "c.zraw"));
  write("c.zraw", zu);
  v = io::read_metaimage(path("c.mhd"));
  expect_labels(v, false);
}

TEST_F(VolumeReaders, metaimage_2d_channels) {
  // NDims 2 is one slice; two channels interleave per pixel.
  std::vector<double> data;
  for (int64_t n = 0; n < NX * NY; ++n)
    for (int c = 0; c < 2; ++c) data.push_back(value_at(n, c));
  write("p.mha", "ObjectType = Image\nNDims = 2\nDimSize = 5 4\nElementSpacing = 0.5 0.25\nOffset = 1 2\n"
                 "TransformMatrix = 0 1 -1 0\nElementNumberOfChannels = 2\nElementType = MET_FLOAT\n"
                 "ElementDataFile = LOCAL\n" +
                     encode<float>(data, false));
  const io::Volume v = io::read_metaimage(path("p.mha"));
  EXPECT_EQ(v.size, (std::array<int64_t, 3>{NX, NY, 1}));
  EXPECT_EQ(v.components, 2);
  ASSERT_EQ(v.values.size(), data.size());
  for (size_t i = 0; i < data.size(); ++i) ASSERT_EQ(v.values[i], float(data[i]));
  Eigen::Matrix3d d;
  d << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expect_geometry(v, Vec3(0.5, 0.25, 1), Vec3(1, 2, 0), d);
}

TEST_F(VolumeReaders, metaimage_bad_files) {
  const std::string data = encode<int16_t>(labels(true), false);
  write("dims.mha", "ObjectType = Image\nNDims = 3\nDimSize = 5 4\nElementType = MET_SHORT\nElementDataFile = LOCAL\n" +
                        data);
  EXPECT_REFUSED(io::read_metaimage, path("dims.mha"), "DimSize has 2 values, NDims is 3");

  write("trunc.mha", mha_header("MET_SHORT", "") + data.substr(1));
  EXPECT_REFUSED(io::read_metaimage, path("trunc.mha"), "truncated");

  write("long.mha", mha_header("MET_SHORT", "") + data + "xx");
  EXPECT_REFUSED(io::read_metaimage, path("long.mha"), "holds 122 bytes of voxel data, the header describes 120");

  write("nodata.mhd", mha_header("MET_SHORT", "", "absent.raw"));
  const std::string msg = error_of(io::read_metaimage, path("nodata.mhd"), true);
  EXPECT_NE(msg.find("nodata.mhd"), std::string::npos) << msg;
  EXPECT_NE(msg.find("absent.raw: cannot open"), std::string::npos) << msg;

  write("list.mhd", mha_header("MET_SHORT", "", "LIST"));
  EXPECT_REFUSED(io::read_metaimage, path("list.mhd"), "LIST");

  // The data file is read whole: a device or a pipe would never end.
  write("zero.mhd", mha_header("MET_SHORT", "", "/dev/zero"));
  EXPECT_NE(error_of(io::read_metaimage, path("zero.mhd"), true).find("zero.mhd: ElementDataFile /dev/zero is not a "
                                                                       "regular file"),
            std::string::npos);

  write("long64.mha", mha_header("MET_LONG_LONG", "") + data + data + data + data);
  EXPECT_REFUSED(io::read_metaimage, path("long64.mha"), "ElementType MET_LONG_LONG is not supported");

  write("mesh.mha", "ObjectType = Mesh\nNDims = 3\nElementDataFile = LOCAL\n");
  EXPECT_REFUSED(io::read_metaimage, path("mesh.mha"), "ObjectType is 'Mesh', not Image");

  write("spacing.mha", mha_header("MET_SHORT", "ElementSpacing = 1 0 1\n") + data);
  EXPECT_REFUSED(io::read_metaimage, path("spacing.mha"), "ElementSpacing value 0 is not > 0");

  write("garbage.mha", std::string("\x89PNG\r\n\x1a\n", 8) + data);
  EXPECT_REFUSED(io::read_metaimage, path("garbage.mha"), "not a MetaImage header");

  write("noend.mha", "ObjectType = Image\nNDims = 3\n");
  EXPECT_REFUSED(io::read_metaimage, path("noend.mha"), "no ElementDataFile");

  write("twice.mha", "NDims = 3\nNDims = 3\nElementDataFile = LOCAL\n");
  EXPECT_REFUSED(io::read_metaimage, path("twice.mha"), "NDims is given twice");

  // Compressed data that stops early, is corrupt, or holds too much.
  const std::string z = zlib_compress(data);
  write("ztrunc.mha", mha_header("MET_SHORT", "CompressedData = True\n") + z.substr(0, z.size() / 2));
  EXPECT_REFUSED(io::read_metaimage, path("ztrunc.mha"), "truncated");
  std::string corrupt = z;
  corrupt[z.size() / 2] ^= 0x55;
  corrupt[z.size() / 2 + 1] ^= 0x55;
  write("zcorrupt.mha", mha_header("MET_SHORT", "CompressedData = True\n") + corrupt);
  EXPECT_NE(error_of(io::read_metaimage, path("zcorrupt.mha")).find("zcorrupt.mha: "), std::string::npos);
  write("zlong.mha", mha_header("MET_UCHAR", "CompressedData = True\n") + z);
  EXPECT_REFUSED(io::read_metaimage, path("zlong.mha"), "holds more than the 60 bytes");

  // A corrupt header asking for terabytes is refused before any allocation.
  write("huge.mha", "ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 100000\nElementType = MET_UCHAR\n"
                    "CompressedData = True\nElementDataFile = LOCAL\n" +
                        z);
  EXPECT_REFUSED(io::read_metaimage, path("huge.mha"), "more than");
  write("overflow.mha", "ObjectType = Image\nNDims = 3\nDimSize = 4000000000 4000000000 4000000000\n"
                        "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n");
  EXPECT_REFUSED(io::read_metaimage, path("overflow.mha"), "overflows");
}

// ---------------------------------------------------------------- INR

/// An INRIMAGE-4 header of NX x NY x NZ with `fields`, padded to 256 bytes.
std::string inr_header(const std::string& fields, const std::string& dims = "XDIM=5\nYDIM=4\nZDIM=3\n") {
  std::string h = "#INRIMAGE-4#{\n" + dims + fields;
  const size_t body = h.size() + 4;
  h += std::string((256 - body % 256) % 256, '\n') + "##}\n";
  EXPECT_EQ(h.size() % 256, 0u);
  return h;
}

void write_gz(const std::string& file, const std::string& bytes) {
  gzFile g = gzopen(file.c_str(), "wb");
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(gzwrite(g, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
  ASSERT_EQ(gzclose(g), Z_OK);
}

TEST_F(VolumeReaders, inr_uchar_little_endian_with_origin) {
  write("a.inr", inr_header("VDIM=1\nTYPE=unsigned fixed\nPIXSIZE=8 bits\nSCALE=2**0\nCPU=decm\nVX=0.5 \nVY=1.5\n"
                            "VZ=2.5\nTX=-3\nTY=4.25\nTZ=10\n#a comment\n") +
                     encode<uint8_t>(labels(false), false));
  const io::Volume v = io::read_inr(path("a.inr"));
  expect_size(v);
  expect_labels(v, false);
  expect_geometry(v, Vec3(0.5, 1.5, 2.5), Vec3(-3, 4.25, 10));
}

TEST_F(VolumeReaders, inr_big_endian_short_and_int) {
  write("s.inr", inr_header("TYPE=signed fixed\nPIXSIZE=16 bits\nCPU=sun\n") + encode<int16_t>(labels(true), true));
  io::Volume v = io::read_inr(path("s.inr"));
  expect_labels(v, true);
  expect_geometry(v, Vec3::Ones(), Vec3::Zero());
  write("i.inr", inr_header("TYPE=signed fixed\nPIXSIZE=32 bits\nCPU=sgi\n") + encode<int32_t>(labels(true), true));
  expect_labels(io::read_inr(path("i.inr")), true);
  write("u.inr", inr_header("TYPE=unsigned fixed\nPIXSIZE=16 bits\nCPU=pc\n") + encode<uint16_t>(labels(false), false));
  expect_labels(io::read_inr(path("u.inr")), false);
}

TEST_F(VolumeReaders, inr_gz_float_vectors_and_double) {
  write_gz(path("f.inr.gz"),
           inr_header("VDIM=2\nTYPE=float\nPIXSIZE=32 bits\nCPU=decm\nVX=2\nVY=2\nVZ=3\n") + encode<float>(values(2), false));
  io::Volume v = io::read_inr(path("f.inr.gz"));
  expect_size(v, 2);
  expect_values(v, 2);
  expect_geometry(v, Vec3(2, 2, 3), Vec3::Zero());

  write_gz(path("d.inr.gz"), inr_header("TYPE=float\nPIXSIZE=64 bits\nCPU=sun\n") + encode<double>(values(), true));
  expect_values(io::read_inr(path("d.inr.gz")));
}

TEST_F(VolumeReaders, inr_bad_files) {
  const std::string data = encode<uint16_t>(labels(false), false);
  const std::string fields = "TYPE=unsigned fixed\nPIXSIZE=16 bits\nCPU=decm\n";

  write("magic.inr", "#INRIMAGE-3#{\n" + inr_header(fields).substr(14) + data);
  EXPECT_REFUSED(io::read_inr, path("magic.inr"), "no #INRIMAGE-4#{ magic");

  write("trunc.inr", inr_header(fields) + data.substr(3));
  EXPECT_REFUSED(io::read_inr, path("trunc.inr"), "truncated");

  write("long.inr", inr_header(fields) + data + "x");
  EXPECT_REFUSED(io::read_inr, path("long.inr"), "holds 121 bytes of voxel data, the header describes 120");

  write("packed.inr", inr_header("TYPE=packed\nPIXSIZE=1 bits\n") + data);
  EXPECT_REFUSED(io::read_inr, path("packed.inr"), "TYPE=packed with PIXSIZE=1 bits is not supported");

  write("cpu.inr", inr_header("TYPE=unsigned fixed\nPIXSIZE=16 bits\n") + data);
  EXPECT_REFUSED(io::read_inr, path("cpu.inr"), "no CPU line");

  write("vx.inr", inr_header(fields + "VX=0\n") + data);
  EXPECT_REFUSED(io::read_inr, path("vx.inr"), "VX=0 is not > 0");

  write("xo.inr", inr_header(fields + "XO=3\n") + data);
  EXPECT_REFUSED(io::read_inr, path("xo.inr"), "XO=3 is not supported");

  write("dim.inr", inr_header(fields, "XDIM=5\nYDIM=-4\nZDIM=3\n") + data);
  EXPECT_REFUSED(io::read_inr, path("dim.inr"), "YDIM=-4 is not a positive integer");

  write("noz.inr", inr_header(fields, "XDIM=5\nYDIM=4\n") + data);
  EXPECT_REFUSED(io::read_inr, path("noz.inr"), "no ZDIM");

  std::string unpadded = "#INRIMAGE-4#{\nXDIM=5\nYDIM=4\nZDIM=3\n" + fields + "##}\n" + data;
  write("unpadded.inr", unpadded);
  EXPECT_REFUSED(io::read_inr, path("unpadded.inr"), "256-byte boundary");

  write("short.inr", "#INRIMAGE-4#{\nXDIM=5\n");
  EXPECT_REFUSED(io::read_inr, path("short.inr"), "truncated header");

  write_gz(path("gztrunc.inr.gz"), inr_header(fields) + data);
  const std::string gz = read(path("gztrunc.inr.gz"));
  write("gztrunc.inr.gz", gz.substr(0, gz.size() - 12));
  EXPECT_REFUSED(io::read_inr, path("gztrunc.inr.gz"), "gztrunc.inr.gz: ");

  write("huge.inr", inr_header(fields, "XDIM=100000\nYDIM=100000\nZDIM=100000\n") + data);
  EXPECT_REFUSED(io::read_inr, path("huge.inr"), "truncated");

  EXPECT_NE(error_of(io::read_inr, path("missing.inr"), true).find("missing.inr: cannot open"), std::string::npos);
}

} // namespace
