/// @file io/nifti.cpp
/// NIfTI (.nii, .nii.gz, .hdr/.img pairs; NIfTI-2 as well) through the NIfTI
/// reference library nifti2_io, which also reads NIfTI-1 files, decompresses
/// them through znzlib and swaps bytes to the machine's order. Coordinates are
/// the file's own world space (RAS+ for scanner data) in its xyz_units
/// (usually mm), not converted.

#include "voronoimesh/io/volume.hpp"

#include "core/input_file.hpp"
#include "core/text.hpp"
#include "io/voxel_data.hpp"
#include "voronoimesh/core/errors.hpp"

#include <nifti2_io.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

namespace vm::io {

namespace {

using detail::cat;

struct NiftiFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
struct CFree {
  void operator()(char* p) const { std::free(p); }
};

/// Throws IoError unless `file` can be opened, with the system's reason, and
/// InvalidInput unless it is a regular file (a device would be read without end).
void require_readable(const std::string& path, const std::string& file) {
  std::error_code missing;
  if (file != path && std::filesystem::exists(file, missing)) { // a missing one: opening it below says so
    try {
      detail::require_regular_file(file);
    } catch (const IoError& e) {
      throw IoError(located(path, cat("its image file ", e.what())));
    }
  }
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) {
    const std::string reason = std::strerror(errno);
    throw IoError(file == path ? located(path, cat("cannot open (", reason, ")"))
                               : located(path, cat("cannot open its image file ", file, " (", reason, ")")));
  }
  std::fclose(f);
}

detail::VoxelType voxel_type(const std::string& path, int datatype) {
  using detail::VoxelType;
  switch (datatype) {
  case DT_UINT8: return VoxelType::u8;
  case DT_INT8: return VoxelType::i8;
  case DT_UINT16: return VoxelType::u16;
  case DT_INT16: return VoxelType::i16;
  case DT_UINT32: return VoxelType::u32;
  case DT_INT32: return VoxelType::i32;
  case DT_FLOAT32: return VoxelType::f32;
  case DT_FLOAT64: return VoxelType::f64;
  default:
    throw InvalidInput(located(path, cat("datatype ", nifti_datatype_string(datatype), " (", datatype,
                                         ") is not supported (8/16/32-bit integers, float32, float64)")));
  }
}

/// Size and components: three spatial axes, and dim[5] as the values per voxel
/// (NIfTI's place for vectors); a time axis or dims 6-7 are refused.
void read_dims(const std::string& path, const nifti_image& nim, Volume& v) {
  // dim[i] beyond dim[0] is unused and may hold anything (0 for a 3-D file).
  auto dim = [&](int i) { return i <= nim.dim[0] ? nim.dim[i] : int64_t(1); };
  if (dim(4) > 1)
    throw InvalidInput(located(path, cat("is a 4-D time series (dim[4] = ", dim(4),
                                         "); only 3-D volumes, with vector components in dim[5], are read")));
  if (dim(6) > 1 || dim(7) > 1)
    throw InvalidInput(located(path, cat("has dim[6] = ", dim(6), ", dim[7] = ", dim(7), "; only 3-D volumes are read")));
  v.size = {dim(1), dim(2), dim(3)};
  if (dim(5) > std::numeric_limits<int>::max())
    throw InvalidInput(located(path, cat("dim[5] = ", dim(5), " is too large")));
  v.components = int(dim(5));
}

/// The header as the file holds it (bytes swapped to the machine's order):
/// nifti2_io's own checks let an ANALYZE header without the NIfTI magic pass,
/// and it turns a non-positive voxel size into 1 when it fills a nifti_image.
class RawHeader {
public:
  RawHeader(const std::string& path, const char* header_name)
      : raw_(nifti_read_header(header_name, &version_, 0), std::free) {
    if (!raw_ || (version_ != 1 && version_ != 2))
      throw InvalidInput(located(path, "not a NIfTI file (no valid 348- or 540-byte header)"));
    // nifti_read_header leaves the bytes as the file holds them: a header of the
    // other byte order shows its size swapped, and is swapped here.
    const int size = version_ == 2 ? n2()->sizeof_hdr : n1()->sizeof_hdr;
    if (size != (version_ == 2 ? 540 : 348)) swap_nifti_header(raw_.get(), version_);
    const char* m = version_ == 2 ? n2()->magic : n1()->magic;
    if (m[0] != 'n' || (m[1] != '+' && m[1] != 'i') || m[2] != char('0' + version_) || m[3] != '\0')
      throw InvalidInput(located(path, cat("no NIfTI-", version_, " magic ('n+", version_, "', 'ni", version_,
                                           "'): an ANALYZE 7.5 file (undefined orientation) or a corrupt header")));
  }

  /// Throws unless pixdim[1..3] are positive.
  void check_pixdim(const std::string& path) const {
    for (int a = 1; a <= 3; ++a) {
      const double d = version_ == 2 ? n2()->pixdim[a] : n1()->pixdim[a];
      if (!(d > 0) || !std::isfinite(d))
        throw InvalidInput(located(path, cat("pixdim[", a, "] is ", d, ", must be > 0")));
    }
  }

  /// Throws unless vox_offset, where the voxel data starts, is a whole number of
  /// bytes the image file of `size` bytes holds (-1: not known, gzipped): in a single .nii file at least
  /// past the header and its 4 extension bytes (352 for NIfTI-1, 544 for
  /// NIfTI-2), in the .img of a pair 0 or more. nifti2_io reads a NaN, huge or
  /// too small offset from just past the header: shifted data, not an error.
  void check_vox_offset(const std::string& path, int64_t size) const {
    const double offset = version_ == 2 ? double(n2()->vox_offset) : double(n1()->vox_offset);
    const bool single = (version_ == 2 ? n2()->magic : n1()->magic)[1] == '+';
    const double least = !single ? 0 : version_ == 2 ? 544 : 352;
    const bool beyond = size >= 0 && offset > double(size);
    if (!std::isfinite(offset) || offset != std::floor(offset) || offset < least || beyond)
      throw InvalidInput(located(path, cat("vox_offset ", offset, " is not where voxel data can start: a whole ",
                                           "number ",
                                           single ? cat("from ", least, " (past the header)") : std::string("from 0"),
                                           size >= 0 ? cat(" to the image file's ", size, " bytes") : std::string())));
  }

private:
  const nifti_1_header* n1() const { return static_cast<const nifti_1_header*>(raw_.get()); }
  const nifti_2_header* n2() const { return static_cast<const nifti_2_header*>(raw_.get()); }

  int version_ = 0;
  std::unique_ptr<void, void (*)(void*)> raw_;
};

/// The index-to-space map: the sform when sform_code > 0, else the qform when
/// qform_code > 0, else the voxel sizes alone (NIfTI's "method 1", which
/// places the voxels in no anatomical frame).
void read_geometry(const std::string& path, const RawHeader& raw, const nifti_image& nim, Volume& v) {
  if (nim.sform_code <= 0) raw.check_pixdim(path);
  Eigen::Matrix3d steps = Eigen::Matrix3d::Zero();
  Vec3 origin = Vec3::Zero();
  if (nim.sform_code > 0 || nim.qform_code > 0) {
    const nifti_dmat44& m = nim.sform_code > 0 ? nim.sto_xyz : nim.qto_xyz;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) steps(r, c) = m.m[r][c];
      origin[r] = m.m[r][3];
    }
    v.world = WorldFrame::ras;
  } else {
    steps.diagonal() = Vec3(nim.pixdim[1], nim.pixdim[2], nim.pixdim[3]);
  }
  detail::set_voxel_axes(v, steps, origin, path);
}

/// NIfTI stores components as the slowest axis (x, y, z, t, u); a Volume
/// interleaves them per voxel.
std::string interleave(const unsigned char* data, int64_t voxels, int components, int bytes) {
  std::string out(size_t(voxels) * size_t(components) * size_t(bytes), '\0');
  for (int c = 0; c < components; ++c)
    for (int64_t i = 0; i < voxels; ++i)
      std::memcpy(&out[(size_t(i) * components + c) * bytes], data + (size_t(c) * voxels + i) * bytes, bytes);
  return out;
}

/// Applies scl_slope/scl_inter (trivial when the slope is 0, or 1 with no
/// intercept); scaled integers become real values.
void apply_scaling(const std::string& path, const nifti_image& nim, Volume& v) {
  const double slope = nim.scl_slope, inter = nim.scl_inter;
  if (slope == 0 || (slope == 1 && inter == 0)) return;
  if (!std::isfinite(slope) || !std::isfinite(inter))
    throw InvalidInput(located(path, cat("scl_slope ", slope, " / scl_inter ", inter, " are not finite")));
  auto scaled = [&](double x) {
    const double y = slope * x + inter;
    if (std::abs(y) > double(std::numeric_limits<float>::max()))
      throw InvalidInput(located(path, cat("scaled value ", y, " is beyond float range")));
    return float(y);
  };
  if (v.integer) {
    v.values.resize(v.labels.size());
    for (size_t i = 0; i < v.labels.size(); ++i) v.values[i] = scaled(v.labels[i]);
    v.labels = {};
    v.integer = false;
  } else {
    for (float& x : v.values) x = scaled(x);
  }
}

} // namespace

Volume read_nifti(const std::string& path) {
  nifti_set_debug_level(0); // failures are reported here, as one line each
  require_readable(path, path);
  std::unique_ptr<char, CFree> header_name(nifti_findhdrname(path.c_str()));
  if (!header_name) throw InvalidInput(located(path, "no NIfTI header found for it"));
  const RawHeader raw(path, header_name.get());
  std::unique_ptr<nifti_image, NiftiFree> nim(nifti_image_read(header_name.get(), 0));
  if (!nim) throw InvalidInput(located(path, "invalid NIfTI header (dim, datatype or vox_offset out of range)"));
  Volume v;
  read_dims(path, *nim, v);
  const detail::VoxelType type = voxel_type(path, nim->datatype);
  const uint64_t needed = detail::voxel_data_bytes(path, v, type);
  read_geometry(path, raw, *nim, v);

  // Check the data's length against the file before the library allocates it.
  if (!nim->iname) throw InvalidInput(located(path, "no image file found for this header"));
  require_readable(path, nim->iname);
  const int64_t file_size = nifti_get_filesize(nim->iname);
  if (file_size < 0) throw IoError(located(path, cat("cannot read the size of ", nim->iname)));
  raw.check_vox_offset(path, nifti_is_gzfile(nim->iname) ? -1 : file_size);
  if (nifti_is_gzfile(nim->iname))
    detail::check_inflatable(path, needed, uint64_t(file_size));
  else if (const auto held = uint64_t(std::max<int64_t>(0, file_size - nim->iname_offset)); held < needed)
    detail::check_voxel_data_length(path, needed, held); // NIfTI allows bytes after the data, not fewer
  if (nifti_image_load(nim.get()) != 0)
    throw InvalidInput(located(path, cat("truncated or corrupt: cannot read the ", needed, " bytes of voxel data")));

  const auto* data = static_cast<const unsigned char*>(nim->data);
  std::string interleaved;
  if (v.components > 1) {
    interleaved = interleave(data, v.voxel_count(), v.components, nim->nbyper);
    data = reinterpret_cast<const unsigned char*>(interleaved.data());
  }
  detail::decode_voxels(v, data, type, std::endian::native == std::endian::big, path);
  apply_scaling(path, *nim, v);
  return v;
}

} // namespace vm::io
