/// @file io/nrrd.cpp
/// NRRD volumes through Teem's nrrdLoad, which handles attached and detached
/// data (.nrrd/.nhdr), raw, gzip and bzip2 encodings and both endiannesses;
/// this file checks what Teem accepts but a volume must not be; what Teem
/// must not be given is screened first (nrrd_header_screen.hpp), and whether
/// the data files can hold the sizes is checked before Teem allocates them
/// (nrrd_data_files.hpp).

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "core/memory.hpp"
#include "core/text.hpp"
#include "io/nrrd_data_files.hpp"
#include "io/nrrd_header_screen.hpp"
#include "io/slicer_segments.hpp"

#include <teem/nrrd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;

/// Owns a Nrrd and frees it and its data however we leave.
struct NrrdDeleter {
  void operator()(Nrrd* n) const { nrrdNuke(n); }
};
using NrrdPtr = std::unique_ptr<Nrrd, NrrdDeleter>;

/// Frees the state of a header-only nrrdLoad, closing the data file Teem kept open.
struct HeaderStateDeleter {
  void operator()(NrrdIoState* io) const {
    if (io->dataFile) std::fclose(io->dataFile);
    nrrdIoStateNix(io);
  }
};

/// Teem's error text, which spans several lines ("[nrrd] nrrdLoad: ..."), as the
/// last (innermost, most specific) line.
std::string teem_error() {
  char* err = biffGetDone(NRRD);
  std::string text = err ? err : "unknown error";
  free(err);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (const size_t nl = text.rfind('\n'); nl != std::string::npos) text.erase(0, nl + 1);
  if (const size_t close = text.find("] "); text.starts_with("[") && close != std::string::npos) text.erase(0, close + 2);
  return text;
}

bool is_integer_type(int type) {
  switch (type) {
  case nrrdTypeChar: case nrrdTypeUChar: case nrrdTypeShort: case nrrdTypeUShort:
  case nrrdTypeInt: case nrrdTypeUInt: case nrrdTypeLLong: case nrrdTypeULLong:
    return true;
  default:
    return false;
  }
}

/// Converts the samples to int32 labels, refusing values int32 cannot hold
/// (only 32- and 64-bit types can have them).
void copy_labels(const std::string& path, const Nrrd& n, size_t count, std::vector<int32_t>& out) {
  out.resize(count);
  auto copy = [&]<class T>(const T* data) {
    for (size_t i = 0; i < count; ++i) {
      const T v = data[i];
      if constexpr (sizeof(T) >= 4) {
        if (std::cmp_less(v, std::numeric_limits<int32_t>::min()) || std::cmp_greater(v, std::numeric_limits<int32_t>::max()))
          throw InvalidInput(located(path, cat("label ", std::to_string(v), " at sample ", i,
                                               " does not fit in 32 bits")));
      }
      out[i] = int32_t(v);
    }
  };
  switch (n.type) {
  case nrrdTypeChar: return copy(static_cast<const signed char*>(n.data));
  case nrrdTypeUChar: return copy(static_cast<const unsigned char*>(n.data));
  case nrrdTypeShort: return copy(static_cast<const int16_t*>(n.data));
  case nrrdTypeUShort: return copy(static_cast<const uint16_t*>(n.data));
  case nrrdTypeInt: return copy(static_cast<const int32_t*>(n.data));
  case nrrdTypeUInt: return copy(static_cast<const uint32_t*>(n.data));
  case nrrdTypeLLong: return copy(static_cast<const int64_t*>(n.data));
  default: return copy(static_cast<const uint64_t*>(n.data));
  }
}

/// Converts real samples to float, refusing NaN and infinities and values a
/// float cannot hold.
void copy_values(const std::string& path, const Nrrd& n, size_t count, std::vector<float>& out) {
  out.resize(count);
  auto copy = [&]<class T>(const T* data) {
    for (size_t i = 0; i < count; ++i) {
      if (!std::isfinite(data[i]) || std::abs(data[i]) > std::numeric_limits<float>::max())
        throw InvalidInput(located(path, cat("value ", double(data[i]), " at sample ", i, " is not a finite float")));
      out[i] = float(data[i]);
    }
  };
  if (n.type == nrrdTypeFloat) return copy(static_cast<const float*>(n.data));
  return copy(static_cast<const double*>(n.data));
}

/// Spacing, direction and origin of the three spatial axes starting at `first`.
void read_geometry(const std::string& path, const Nrrd& n, unsigned first, Volume& v) {
  if (n.spaceDim != 0 && n.spaceDim != 3)
    throw InvalidInput(located(path, cat("its space has ", n.spaceDim, " dimensions; a volume needs 3")));
  for (unsigned a = 0; a < 3; ++a) {
    double spacing = 0;
    double dir[NRRD_SPACE_DIM_MAX];
    const int status = nrrdSpacingCalculate(&n, first + a, &spacing, dir);
    switch (status) {
    case nrrdSpacingStatusNone:
      spacing = 1;
      v.spacing_stated = false;
      break;
    case nrrdSpacingStatusScalarNoSpace: break;
    case nrrdSpacingStatusDirection: v.direction.col(a) = Vec3(dir[0], dir[1], dir[2]); break;
    default:
      throw InvalidInput(located(path, cat("axis ", first + a, " has both 'spacings' and 'space directions'")));
    }
    if (!(std::isfinite(spacing) && spacing > 0))
      throw InvalidInput(located(path, cat("axis ", first + a, " has spacing ", spacing, "; it must be positive")));
    v.spacing[a] = spacing;
  }
  if (n.spaceDim == 3) {
    for (int a = 0; a < 3; ++a)
      if (std::isfinite(n.spaceOrigin[a])) v.origin[a] = n.spaceOrigin[a];
  }
}

/// The frame its `space` field names, if one voronoimesh can convert between.
WorldFrame world_frame(const Nrrd& n) {
  switch (n.space) {
  case nrrdSpaceRightAnteriorSuperior: return WorldFrame::ras;
  case nrrdSpaceLeftPosteriorSuperior:
  case nrrdSpaceScannerXYZ: return WorldFrame::lps; // scanner-xyz is LPS, Teem's enum says
  default: return WorldFrame::unknown;
  }
}

/// The value of a key/value pair of the header ("key:=value"), if present.
std::optional<std::string> header_value(const Nrrd& n, const std::string& key) {
  char* value = nrrdKeyValueGet(&n, key.c_str()); // a copy, ours to free
  if (!value) return std::nullopt;
  std::string text = value;
  free(value);
  return text;
}

} // namespace

Volume read_nrrd(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw IoError(located(path, "cannot open (No such file or directory)"));
  // Before Teem reads the header: what its data file names must be safe for Teem.
  const std::vector<std::filesystem::path> detached = nrrd::screen_data_files(path);
  NrrdPtr n(nrrdNew());
  {
    // The header first: a corrupt or absurd size is refused before Teem allocates it.
    std::unique_ptr<NrrdIoState, HeaderStateDeleter> header_only(nrrdIoStateNew());
    header_only->skipData = 1;
    header_only->keepNrrdDataFileOpen = 1; // where a single file's data starts, for check_data_fits
    if (nrrdLoad(n.get(), path.c_str(), header_only.get()) != 0)
      throw InvalidInput(located(path, "not a readable NRRD volume: " + teem_error()));
    // Block samples' size is the file's to choose: refused before it counts.
    if (n->type == nrrdTypeBlock) throw InvalidInput(located(path, "has type 'block'; expected integers or reals"));
    double elements = 1;
    for (unsigned a = 0; a < n->dim; ++a) elements *= double(n->axis[a].size);
    // Teem's copy and ours (4 bytes per sample) live together while converting.
    detail::refuse_beyond_memory(elements * double(nrrdTypeSize[n->type] + 4), path,
                                 cat("reading ", elements, " samples"));
    // Below the memory, so the counts fit in 64 bits.
    nrrd::check_data_fits(path, *header_only, detached, uint64_t(elements), nrrdTypeSize[n->type]);
  }
  if (nrrdLoad(n.get(), path.c_str(), nullptr) != 0)
    throw InvalidInput(located(path, "not a readable NRRD volume: " + teem_error()));

  // A 4th axis is allowed first only, as the components (one per phase of a
  // distance grid): it must be the fastest so each voxel's values lie together.
  if (n->dim != 3 && n->dim != 4)
    throw InvalidInput(located(path, cat("has ", n->dim, " dimensions; a volume needs 3 (or 4 with the components first)")));
  const unsigned first = n->dim - 3;
  if (n->dim == 4 && nrrdKindIsDomain(n->axis[0].kind))
    throw InvalidInput(located(path, cat("has 4 spatial axes; a 4th axis must be the first and hold components "
                                         "(kind 'vector' or 'list'), not kind '",
                                         airEnumStr(nrrdKind, n->axis[0].kind), "'")));
  for (unsigned a = first; a < n->dim; ++a)
    if (n->axis[a].kind != nrrdKindUnknown && !nrrdKindIsDomain(n->axis[a].kind))
      throw InvalidInput(located(path, cat("axis ", a, " has kind '", airEnumStr(nrrdKind, n->axis[a].kind),
                                           "', not a spatial axis; only the first of 4 axes may hold components")));

  Volume v;
  v.components = n->dim == 4 ? int(n->axis[0].size) : 1;
  for (unsigned a = 0; a < 3; ++a) {
    v.size[a] = int64_t(n->axis[first + a].size);
    if (v.size[a] < 1) throw InvalidInput(located(path, cat("axis ", first + a, " is empty")));
  }
  read_geometry(path, *n, first, v);
  v.world = world_frame(*n);
  v.segments = slicer::read_segments([&](const std::string& key) { return header_value(*n, key); }, v.components, path);

  const size_t count = size_t(v.voxel_count()) * size_t(v.components);
  v.integer = is_integer_type(n->type);
  if (v.integer)
    copy_labels(path, *n, count, v.labels);
  else
    copy_values(path, *n, count, v.values);
  if (!v.segments.empty()) {
    if (!v.integer) throw InvalidInput(located(path, "is a segmentation (it lists segments) but holds reals, not labels"));
    n.reset(); // Teem's copy of the data, before flattening makes another
    slicer::flatten_segment_layers(v, path);
  }
  return v;
}

} // namespace vm::io
