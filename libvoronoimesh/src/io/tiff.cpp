/// @file io/tiff.cpp
/// TIFF stacks (.tif, .tiff), as Fiji/ImageJ, micro-CT and FIB-SEM software and
/// segmentation tools save label volumes: one page (image file directory) per z
/// slice, read with libtiff (strips or tiles, any compression and predictor it
/// decodes, either byte order, BigTIFF). Voxel (i, j, k) is column i, row j (from
/// the top, as ImageJ counts them) of page k. The voxel size is an OME-TIFF's
/// (PhysicalSizeX/Y/Z of its OME-XML) or ImageJ's (its description's `spacing=`
/// along z, the X/YResolution tags in pixels per unit); any other TIFF says none
/// (Volume::spacing_stated), and its voxels are 1 x 1 x 1.

#include "voronoimesh/io/volume.hpp"

#include "core/huge_pages.hpp"
#include "core/input_file.hpp"
#include "core/memory.hpp"
#include "core/text.hpp"
#include "io/voxel_data.hpp"
#include "voronoimesh/core/errors.hpp"

#include <tiffio.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;
using detail::VoxelType;

struct TiffClose {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
struct OptionsFree {
  void operator()(TIFFOpenOptions* o) const { TIFFOpenOptionsFree(o); }
};

/// libtiff's error messages are kept (the last one names what failed), not
/// printed: an error is one line naming the file. Warnings (unknown tags, as
/// every writer adds its own) say nothing about the voxels and are dropped.
int keep_error(TIFF*, void* last, const char*, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  *static_cast<std::string*>(last) = text;
  return 1;
}
int drop_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

/// What a page holds per pixel and how it is laid out.
struct PageLayout {
  uint32_t width = 0, height = 0;
  uint16_t bits = 0, format = 0, samples = 0;
  bool operator==(const PageLayout&) const = default;
};

PageLayout layout_of(TIFF* t) {
  PageLayout p;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &p.width);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &p.height);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &p.bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &p.format);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &p.samples);
  return p;
}

VoxelType voxel_type(const std::string& path, const PageLayout& p) {
  if (p.samples != 1)
    throw InvalidInput(located(path, cat("has ", p.samples, " samples per pixel (RGB or channels); a volume of labels "
                                                           "has one value per voxel")));
  const std::map<std::pair<int, int>, VoxelType> types = {
      {{SAMPLEFORMAT_UINT, 8}, VoxelType::u8},     {{SAMPLEFORMAT_INT, 8}, VoxelType::i8},
      {{SAMPLEFORMAT_UINT, 16}, VoxelType::u16},   {{SAMPLEFORMAT_INT, 16}, VoxelType::i16},
      {{SAMPLEFORMAT_UINT, 32}, VoxelType::u32},   {{SAMPLEFORMAT_INT, 32}, VoxelType::i32},
      {{SAMPLEFORMAT_IEEEFP, 32}, VoxelType::f32}, {{SAMPLEFORMAT_IEEEFP, 64}, VoxelType::f64}};
  const auto it = types.find({p.format, p.bits});
  if (it == types.end())
    throw InvalidInput(located(path, cat("holds ", p.bits, "-bit ",
                                         p.format == SAMPLEFORMAT_IEEEFP ? "real" : "integer",
                                         " samples; supported: 8, 16 and 32-bit integers, 32 and 64-bit reals")));
  return it->second;
}

/// ImageJ's description, KEY=VALUE lines ("ImageJ=1.54f", "images=40",
/// "slices=40", "unit=micron", "spacing=0.5"), or empty for another writer's.
std::map<std::string, std::string> imagej_fields(TIFF* t) {
  std::map<std::string, std::string> fields;
  const char* text = nullptr;
  if (!TIFFGetField(t, TIFFTAG_IMAGEDESCRIPTION, &text) || !text || std::strncmp(text, "ImageJ=", 7) != 0)
    return fields;
  for (const char* line = text; *line;) {
    const char* end = std::strchr(line, '\n');
    const std::string entry(line, end ? size_t(end - line) : std::strlen(line));
    if (const size_t eq = entry.find('='); eq != std::string::npos) fields[entry.substr(0, eq)] = entry.substr(eq + 1);
    if (!end) break;
    line = end + 1;
  }
  return fields;
}

/// The attributes of the Pixels element of an OME-TIFF's OME-XML description
/// (SizeZ, SizeC, SizeT, PhysicalSizeX, ...), or empty for another writer's.
std::map<std::string, std::string> ome_pixels(TIFF* t) {
  std::map<std::string, std::string> attributes;
  const char* text = nullptr;
  if (!TIFFGetField(t, TIFFTAG_IMAGEDESCRIPTION, &text) || !text) return attributes;
  const std::string_view xml(text);
  if (xml.find("<OME") == std::string_view::npos && xml.find(":OME") == std::string_view::npos) return attributes;
  size_t at = xml.find("<Pixels ");
  if (at == std::string_view::npos) at = xml.find(":Pixels "); // a prefixed element, <ome:Pixels
  const size_t end = at == std::string_view::npos ? at : xml.find('>', at);
  if (end == std::string_view::npos) return attributes;
  const std::string_view element = xml.substr(at, end - at);
  for (size_t eq = element.find("=\""); eq != std::string_view::npos; eq = element.find("=\"", eq + 2)) {
    const size_t name = element.find_last_of(" \t\r\n", eq) + 1, close = element.find('"', eq + 2);
    if (close == std::string_view::npos) break;
    attributes.emplace(element.substr(name, eq - name), element.substr(eq + 2, close - eq - 2));
  }
  return attributes;
}

/// The voxel size an OME-TIFF's Pixels element gives, where it gives all three
/// in one unit; refuses one of several channels or time points, whose pages are
/// not all z slices, or whose pages are not its SizeZ (a multi-file dataset).
std::optional<Vec3> ome_voxel_size(const std::string& path, const std::map<std::string, std::string>& ome,
                                   tdir_t pages) {
  auto get = [&](const char* key) {
    const auto it = ome.find(key);
    return it == ome.end() ? std::string() : it->second;
  };
  for (const auto& [key, what] : {std::pair{"SizeC", " channels"}, std::pair{"SizeT", " time points"}})
    if (const std::string n = get(key); !n.empty() && n != "1")
      throw InvalidInput(located(path, cat("an OME-TIFF of ", n, what, "; a volume of labels has one channel at one "
                                                                "time")));
  if (const std::string z = get("SizeZ"); !z.empty() && z != std::to_string(pages))
    throw InvalidInput(located(path, cat("its OME-XML says SizeZ=", z, ", but it has ", pages,
                                         " pages (one file of a multi-file OME-TIFF dataset?)")));
  auto unit = [&](const std::string& size_key) { // OME's default unit is the micrometre
    const std::string u = get((size_key + "Unit").c_str());
    return u.empty() ? std::string("\u00b5m") : u;
  };
  static const char* const axes[] = {"X", "Y", "Z"};
  Vec3 size;
  for (int a = 0; a < 3; ++a) {
    const std::string key = cat("PhysicalSize", axes[a]);
    if (!detail::parse_number(get(key.c_str()), size[a]) || !(size[a] > 0)) return std::nullopt;
    if (unit(key) != unit("PhysicalSizeX"))
      throw InvalidInput(located(path, cat("its OME-XML gives the voxel size in ", unit("PhysicalSizeX"), " and ",
                                           unit(key), ": give it with --voxel-size")));
  }
  return size;
}

/// The pixel size along x or y: the inverse of ImageJ's resolution tag.
double pixel_size(const std::string& path, TIFF* t, ttag_t tag, const char* axis) {
  float per_unit = 0;
  if (!TIFFGetField(t, tag, &per_unit)) return 1;
  if (!(std::isfinite(per_unit) && per_unit > 0))
    throw InvalidInput(located(path, cat("its ", axis, " resolution is ", per_unit, " pixels per unit, must be > 0")));
  return 1.0 / double(per_unit);
}

/// The most bytes `stored` bytes of strips or tiles decode to under `compression`:
/// none 1:1, PackBits 128 from 2, deflate 1032:1 (max_inflated_bytes()), LZW 4096:1
/// (one 12-bit code stands for at most 4096 bytes); none for other schemes (LZMA,
/// ZSTD, JPEG...), which only the memory check bounds.
std::optional<uint64_t> most_decoded_bytes(uint16_t compression, uint64_t stored) {
  const uint64_t huge = std::numeric_limits<uint64_t>::max() / 4096;
  switch (compression) {
  case COMPRESSION_NONE: return stored;
  case COMPRESSION_PACKBITS: return std::min(stored, huge) * 64 + 128;
  case COMPRESSION_ADOBE_DEFLATE:
  case COMPRESSION_DEFLATE: return detail::max_inflated_bytes(stored);
  case COMPRESSION_LZW: return std::min(stored, huge) * 4096;
  default: return std::nullopt;
  }
}

/// Refuses a stack whose pages are unlike the first, or whose strips or tiles
/// could not hold the samples their headers describe (a few hundred corrupt
/// bytes claiming gigabytes), before anything is allocated for them. Leaves the
/// first page current.
void check_pages(const std::string& path, TIFF* t, tdir_t pages, const PageLayout& first, uint64_t page_bytes,
                 uint64_t file_bytes) {
  for (tdir_t page = 0; page < pages; ++page) {
    // Page after page: TIFFSetDirectory(k) walks the chain from the first page each time.
    if (page == 0 ? !TIFFSetDirectory(t, 0) : !TIFFReadDirectory(t))
      throw InvalidInput(located(path, cat("page ", page + 1, " cannot be read")));
    if (const PageLayout here = layout_of(t); !(here == first))
      throw InvalidInput(located(path, cat("page ", page + 1, " is ", here.width, " x ", here.height, " of ",
                                           here.bits, "-bit samples, page 1 ", first.width, " x ", first.height,
                                           " of ", first.bits,
                                           ": a volume's slices are alike (a thumbnail or preview page?)")));
    uint16_t compression = COMPRESSION_NONE;
    TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
    const auto at_most = most_decoded_bytes(compression, file_bytes);
    if (!at_most) continue;
    if (page_bytes > *at_most)
      throw InvalidInput(located(path, cat("page ", page + 1, " describes ", page_bytes, " bytes of samples, more "
                                           "than the file's ", file_bytes, " bytes can hold (corrupt sizes?)")));
    uint64_t stored = 0;
    const uint32_t striles = TIFFIsTiled(t) ? TIFFNumberOfTiles(t) : TIFFNumberOfStrips(t);
    for (uint32_t s = 0; s < striles && stored <= file_bytes; ++s) stored += TIFFGetStrileByteCount(t, s);
    if (page_bytes > *most_decoded_bytes(compression, std::min(stored, file_bytes)))
      throw InvalidInput(located(path, cat("page ", page + 1, " describes ", page_bytes, " bytes of samples, more "
                                           "than its ", stored,
                                           " bytes of strips or tiles can hold (corrupt sizes?)")));
  }
  TIFFSetDirectory(t, 0);
}

/// Reads the current page's pixels into `out` (rows of `row_bytes`, top first),
/// strip by strip or tile by tile.
void read_page(const std::string& path, TIFF* t, const PageLayout& p, size_t row_bytes, unsigned char* out,
               const std::string& last_error, int64_t page) {
  auto failed = [&](const char* what) {
    return InvalidInput(located(path, cat("page ", page + 1, ": cannot decode its ", what, " (",
                                          last_error.empty() ? "corrupt data" : last_error, ")")));
  };
  const size_t pixel_bytes = row_bytes / p.width;
  if (!TIFFIsTiled(t)) {
    uint32_t rows_per_strip = 0;
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &rows_per_strip);
    rows_per_strip = rows_per_strip == 0 ? p.height : std::min(rows_per_strip, p.height); // 0: corrupt
    for (uint32_t row = 0; row < p.height; row += rows_per_strip) {
      const size_t bytes = size_t(std::min(rows_per_strip, p.height - row)) * row_bytes;
      if (TIFFReadEncodedStrip(t, TIFFComputeStrip(t, row, 0), out + size_t(row) * row_bytes, tmsize_t(bytes)) < 0)
        throw failed("strips");
    }
    return;
  }
  uint32_t tile_width = 0, tile_height = 0;
  TIFFGetField(t, TIFFTAG_TILEWIDTH, &tile_width);
  TIFFGetField(t, TIFFTAG_TILELENGTH, &tile_height);
  if (tile_width == 0 || tile_height == 0) throw failed("tiles");
  std::vector<unsigned char> tile(size_t(TIFFTileSize(t)));
  for (uint32_t y = 0; y < p.height; y += tile_height)
    for (uint32_t x = 0; x < p.width; x += tile_width) {
      if (TIFFReadEncodedTile(t, TIFFComputeTile(t, x, y, 0, 0), tile.data(), tmsize_t(tile.size())) < 0)
        throw failed("tiles");
      const size_t columns = std::min(tile_width, p.width - x) * pixel_bytes;
      for (uint32_t r = 0; r < tile_height && y + r < p.height; ++r)
        std::memcpy(out + size_t(y + r) * row_bytes + x * pixel_bytes, tile.data() + r * tile_width * pixel_bytes,
                    columns);
    }
}

} // namespace

Volume read_tiff(const std::string& path) {
  std::string last_error;
  const std::unique_ptr<TIFFOpenOptions, OptionsFree> options(TIFFOpenOptionsAlloc());
  TIFFOpenOptionsSetErrorHandlerExtR(options.get(), keep_error, &last_error);
  TIFFOpenOptionsSetWarningHandlerExtR(options.get(), drop_warning, nullptr);
  const std::unique_ptr<TIFF, TiffClose> t(TIFFOpenExt(path.c_str(), "r", options.get()));
  if (!t) {
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
      std::fclose(f);
      throw InvalidInput(
          located(path, cat("not a TIFF file (", last_error.empty() ? "no TIFF header" : last_error, ")")));
    }
    throw IoError(located(path, cat("cannot open (", std::strerror(errno), ")")));
  }
  const PageLayout first = layout_of(t.get());
  const VoxelType type = voxel_type(path, first);
  const auto imagej = imagej_fields(t.get());
  const tdir_t pages = TIFFNumberOfDirectories(t.get());
  // A page directory that cannot be read ends the count early (a truncated file): refused, not a shorter stack.
  if (!last_error.empty())
    throw InvalidInput(located(path, cat("truncated or corrupt: the directory after page ", pages,
                                         " cannot be read (", last_error, ")")));
  if (const auto images = imagej.find("images"); images != imagej.end() && images->second != std::to_string(pages))
    throw InvalidInput(located(path, cat("ImageJ says it holds ", images->second, " images, but it has ", pages,
                                         " pages (a stack over 4 GB that ImageJ saved without a page for each "
                                         "slice?): save it as NRRD or NIfTI")));
  for (const char* key : {"channels", "frames"})
    if (const auto it = imagej.find(key); it != imagej.end() && it->second != "1")
      throw InvalidInput(located(path, cat("an ImageJ hyperstack of ", it->second, " ", key,
                                           "; a volume of labels has one channel and one frame")));
  if (pages < 2)
    throw InvalidInput(located(path, "has one page, a 2-D image; a volume is a stack of pages, one per slice"));

  Volume v;
  v.size = {int64_t(first.width), int64_t(first.height), int64_t(pages)};
  Eigen::Matrix3d steps = Eigen::Matrix3d::Identity();
  const auto ome = ome_pixels(t.get());
  const std::optional<Vec3> ome_size = ome.empty() ? std::nullopt : ome_voxel_size(path, ome, pages);
  if (ome_size) {
    steps = ome_size->asDiagonal();
  } else if (!imagej.empty()) {
    steps(0, 0) = pixel_size(path, t.get(), TIFFTAG_XRESOLUTION, "x");
    steps(1, 1) = pixel_size(path, t.get(), TIFFTAG_YRESOLUTION, "y");
    if (const auto spacing = imagej.find("spacing"); spacing != imagej.end() &&
                                                     !detail::parse_number(spacing->second, steps(2, 2)))
      throw InvalidInput(located(path, cat("ImageJ's spacing=", spacing->second, " is not a number")));
  } else {
    v.spacing_stated = false;
  }
  detail::set_voxel_axes(v, steps, Vec3::Zero(), path);

  const size_t row_bytes = size_t(first.width) * size_t(detail::voxel_type_bytes(type));
  const uint64_t needed = detail::voxel_data_bytes(path, v, type);
  // The samples, then their labels or values: before a corrupt size asks for more than there is.
  detail::refuse_beyond_memory(double(needed) + 4.0 * double(v.voxel_count()), path,
                               cat("reading ", v.voxel_count(), " voxels"));
  check_pages(path, t.get(), pages, first, uint64_t(first.height) * row_bytes, detail::require_regular_file(path));
  std::string data;
  detail::resize_on_huge_pages(data, size_t(needed));
  for (tdir_t page = 0; page < pages; ++page) {
    if (page > 0 && !TIFFReadDirectory(t.get()))
      throw InvalidInput(located(path, cat("page ", page + 1, " cannot be read (", last_error, ")")));
    read_page(path, t.get(), first, row_bytes,
              reinterpret_cast<unsigned char*>(data.data()) + size_t(page) * first.height * row_bytes, last_error,
              page);
  }
  // libtiff hands the samples over in this machine's byte order.
  detail::decode_voxels(v, reinterpret_cast<const unsigned char*>(data.data()), type,
                        std::endian::native == std::endian::big, path);
  return v;
}

} // namespace vm::io
