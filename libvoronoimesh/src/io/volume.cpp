/// @file io/volume.cpp
/// Picks a volume reader by the file's extension.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "core/input_file.hpp"
#include "core/text.hpp"

#include <algorithm>
#include <array>
#include <string_view>

namespace vm::io {

namespace {

using detail::lower;

struct Format {
  std::string_view extension; ///< lower case, with the dot
  Volume (*read)(const std::string&);
};

/// Every extension read_volume() knows (.hdr: the header of a NIfTI .hdr/.img pair).
constexpr std::array<Format, 12> formats{{{".nrrd", read_nrrd},
                                         {".nhdr", read_nrrd},
                                         {".nii", read_nifti},
                                         {".nii.gz", read_nifti},
                                         {".hdr", read_nifti},
                                         {".mha", read_metaimage},
                                         {".mhd", read_metaimage},
                                         {".inr", read_inr},
                                         {".inr.gz", read_inr},
                                         {".dream3d", read_dream3d},
                                         {".tif", read_tiff},
                                         {".tiff", read_tiff}}};

/// The format whose extension ends `path` (longest match, so ".nii.gz" wins over ".gz").
const Format* format_of(const std::string& path) {
  const std::string p = lower(path);
  const Format* best = nullptr;
  for (const Format& f : formats)
    if (p.ends_with(f.extension) && (!best || f.extension.size() > best->extension.size())) best = &f;
  return best;
}

} // namespace

bool is_volume_file(const std::string& path) { return format_of(path) != nullptr; }

Volume read_volume(const std::string& path) {
  const Format* f = format_of(path);
  if (!f)
    throw InvalidInput(
        located(path, "not a volume file (expected .nrrd, .nhdr, .nii, .nii.gz, .hdr, .mha, .mhd, .inr, .inr.gz, .dream3d, "
                     ".tif or .tiff)"));
  detail::require_regular_file(path); // the files it names are checked by its reader
  return f->read(path);
}

} // namespace vm::io
