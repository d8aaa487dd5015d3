// The NIfTI reader: small volumes with known voxels and geometry written through
// nifti2_io (or byte by byte for what it does not write), read back and
// compared; then broken files, each refused with a message naming the file and
// the problem.

#include "volume_files.hpp"

#include <nifti2_io.h>

using namespace vm;
using namespace vm::volume_test;

namespace {

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

TEST_F(VolumeReaders, nifti_vox_offset_where_no_data_can_start_is_refused) {
  // nifti2_io reads such files from byte 352 on: shifted data, no error of its own.
  Nim nim = make_nifti(DT_INT16, encode<int16_t>(labels(true), false));
  write_nifti(nim.get(), path("good.nii"));
  const std::string good = read(path("good.nii"));
  for (const float offset : {1e30f, std::nanf(""), 100.0f, 351.0f, 352.5f, float(good.size() + 1)}) {
    std::string bad = good;
    std::memcpy(bad.data() + offsetof(nifti_1_header, vox_offset), &offset, sizeof offset);
    write("offset.nii", bad);
    EXPECT_REFUSED(io::read_nifti, path("offset.nii"), "vox_offset");
  }
  EXPECT_NO_THROW(io::read_nifti(path("good.nii")));
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

} // namespace
