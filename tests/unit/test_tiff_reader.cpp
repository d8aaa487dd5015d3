// The TIFF stack reader: stacks written with libtiff itself (strips and tiles,
// compressed, big-endian, BigTIFF, ImageJ's voxel size), read back and compared
// voxel by voxel; then the files a TIFF reader meets that are no volume, each
// refused with a message naming the file and the problem.

#include "volume_files.hpp"

#include <tiffio.h>

using namespace vm;
using namespace vm::volume_test;

namespace {

/// How a test stack is written.
struct Stack {
  const char* mode = "w";        ///< libtiff's: "wb" big-endian, "w8" BigTIFF
  uint16_t compression = COMPRESSION_NONE;
  uint32_t rows_per_strip = 1;   ///< strips of so many rows, unless `tile`
  uint32_t tile = 0;             ///< square tiles of this side (a multiple of 16)
  std::string description;       ///< the ImageDescription tag, e.g. ImageJ's
  float resolution[2] = {0, 0};  ///< X/YResolution, pixels per unit (0: none)
  int pages = int(NZ);           ///< pages written (the first `pages` slices)
  uint16_t samples = 1;          ///< samples per pixel (each the voxel's value)
  int64_t width = NX;            ///< the last page's width (another makes it unlike the others)
};

/// Writes `values` (voxel n = i + NX * (j + NY * k)) as a TIFF of samples of T,
/// page k holding slice k, row j of it holding voxels (0..NX-1, j, k).
template <class T>
std::string write_stack(const std::string& path, const std::vector<double>& values, const Stack& s = {}) {
  TIFF* t = TIFFOpen(path.c_str(), s.mode);
  EXPECT_NE(t, nullptr);
  const uint16_t format = std::is_floating_point_v<T> ? SAMPLEFORMAT_IEEEFP
                          : std::is_signed_v<T>       ? SAMPLEFORMAT_INT
                                                      : SAMPLEFORMAT_UINT;
  for (int k = 0; k < s.pages; ++k) {
    const uint32_t width = uint32_t(k + 1 == s.pages ? s.width : NX);
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, width);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, uint32_t(NY));
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, uint16_t(8 * sizeof(T)));
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, format);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, s.samples);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, s.samples == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_COMPRESSION, s.compression);
    if (k == 0 && !s.description.empty()) TIFFSetField(t, TIFFTAG_IMAGEDESCRIPTION, s.description.c_str());
    if (s.resolution[0] > 0) {
      TIFFSetField(t, TIFFTAG_XRESOLUTION, s.resolution[0]);
      TIFFSetField(t, TIFFTAG_YRESOLUTION, s.resolution[1]);
      TIFFSetField(t, TIFFTAG_RESOLUTIONUNIT, RESUNIT_NONE);
    }
    std::vector<T> page(size_t(width) * NY * s.samples);
    for (int64_t j = 0; j < NY; ++j)
      for (int64_t i = 0; i < std::min<int64_t>(width, NX); ++i)
        for (int c = 0; c < s.samples; ++c)
          page[size_t((j * width + i) * s.samples + c)] = T(values[size_t(i + NX * (j + NY * k))]);
    const size_t row_bytes = size_t(width) * s.samples * sizeof(T);
    if (s.tile > 0) {
      TIFFSetField(t, TIFFTAG_TILEWIDTH, s.tile);
      TIFFSetField(t, TIFFTAG_TILELENGTH, s.tile);
      std::vector<T> tile(size_t(s.tile) * s.tile * s.samples); // one tile covers the small page
      for (int64_t j = 0; j < NY; ++j)
        std::memcpy(&tile[size_t(j) * s.tile * s.samples], &page[size_t(j * width) * s.samples], row_bytes);
      EXPECT_GE(TIFFWriteEncodedTile(t, 0, tile.data(), tmsize_t(tile.size() * sizeof(T))), 0);
    } else {
      TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, s.rows_per_strip);
      for (uint32_t row = 0, strip = 0; row < NY; row += s.rows_per_strip, ++strip) {
        const size_t rows = std::min<size_t>(s.rows_per_strip, size_t(NY) - row);
        const T* first = &page[size_t(row) * width * s.samples];
        EXPECT_GE(TIFFWriteEncodedStrip(t, strip, const_cast<T*>(first), tmsize_t(rows * row_bytes)), 0);
      }
    }
    TIFFWriteDirectory(t);
  }
  TIFFClose(t);
  return path;
}

TEST_F(VolumeReaders, tiff_stacks_in_strips_and_tiles_compressed_or_not) {
  struct Case {
    const char* what;
    io::Volume read;
    bool is_signed;
  };
  const Case cases[] = {
      {"uchar strips of 3 rows, deflate",
       io::read_tiff(write_stack<uint8_t>(path("a.tif"), labels(false),
                                          {.compression = COMPRESSION_ADOBE_DEFLATE, .rows_per_strip = 3})),
       false},
      {"ushort, big-endian, LZW",
       io::read_tiff(
           write_stack<uint16_t>(path("b.tif"), labels(false), {.mode = "wb", .compression = COMPRESSION_LZW})),
       false},
      {"int tiles, BigTIFF",
       io::read_tiff(write_stack<int32_t>(path("c.tiff"), labels(true), {.mode = "w8", .tile = 16})), true},
      {"short, packbits",
       io::read_tiff(write_stack<int16_t>(path("d.tif"), labels(true), {.compression = COMPRESSION_PACKBITS})), true}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    expect_size(c.read);
    expect_labels(c.read, c.is_signed);
    expect_geometry(c.read, Vec3::Ones(), Vec3::Zero());
    EXPECT_FALSE(c.read.spacing_stated); // another writer's TIFF says no voxel size
  }
  const io::Volume reals = io::read_tiff(write_stack<float>(path("f.tif"), values(), {.rows_per_strip = 2}));
  expect_values(reals);
}

// ImageJ's voxel size: X/YResolution in pixels per unit, spacing= along z.
TEST_F(VolumeReaders, tiff_voxel_size_from_imagej) {
  const Stack imagej{.description = "ImageJ=1.54f\nimages=3\nslices=3\nunit=micron\nspacing=2.5\nloop=false\n",
                     .resolution = {2, 4}};
  const io::Volume v = io::read_tiff(write_stack<uint8_t>(path("ij.tif"), labels(false), imagej));
  expect_labels(v, false);
  expect_geometry(v, Vec3(0.5, 0.25, 2.5), Vec3::Zero());
  EXPECT_TRUE(v.spacing_stated);
  // read_volume() knows both extensions, in any case.
  EXPECT_EQ(io::read_volume(write_stack<uint8_t>(path("IJ.TIFF"), labels(false), imagej)).spacing, v.spacing);
}

/// An OME-TIFF's description: the OME-XML of one image whose Pixels element has `pixels`.
std::string ome_xml(const std::string& pixels) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?><OME xmlns=\"http://www.openmicroscopy.org/Schemas/OME/2016-06\">"
         "<Image ID=\"Image:0\"><Pixels DimensionOrder=\"XYZCT\" ID=\"Pixels:0\" " + pixels +
         " SizeX=\"5\" SizeY=\"4\" Type=\"uint8\"><TiffData/></Pixels></Image></OME>";
}

// OME-TIFF (Bio-Formats, Fiji's OME export, microscopes): the voxel size from
// PhysicalSizeX/Y/Z; pages that are not all z slices of one channel at one time refused.
TEST_F(VolumeReaders, tiff_voxel_size_and_dimensions_from_ome_xml) {
  const std::string sizes = "PhysicalSizeX=\"0.5\" PhysicalSizeY=\"0.25\" PhysicalSizeZ=\"2\" ";
  const io::Volume v = io::read_tiff(write_stack<uint8_t>(
      path("a.ome.tif"), labels(false), {.description = ome_xml(sizes + "SizeC=\"1\" SizeT=\"1\" SizeZ=\"3\"")}));
  expect_labels(v, false);
  expect_geometry(v, Vec3(0.5, 0.25, 2), Vec3::Zero());
  EXPECT_TRUE(v.spacing_stated);
  const io::Volume no_sizes = io::read_tiff(
      write_stack<uint8_t>(path("b.ome.tif"), labels(false), {.description = ome_xml("SizeC=\"1\" SizeZ=\"3\"")}));
  EXPECT_FALSE(no_sizes.spacing_stated);
  EXPECT_REFUSED(io::read_tiff,
                 write_stack<uint8_t>(path("c.ome.tif"), labels(false),
                                      {.description = ome_xml("SizeC=\"3\" SizeT=\"1\" SizeZ=\"1\"")}),
                 "an OME-TIFF of 3 channels");
  EXPECT_REFUSED(io::read_tiff,
                 write_stack<uint8_t>(path("d.ome.tif"), labels(false), {.description = ome_xml("SizeZ=\"30\"")}),
                 "its OME-XML says SizeZ=30, but it has 3 pages");
  EXPECT_REFUSED(io::read_tiff,
                 write_stack<uint8_t>(path("e.ome.tif"), labels(false),
                                      {.description = ome_xml(sizes + "PhysicalSizeZUnit=\"nm\" SizeZ=\"3\"")}),
                 "gives the voxel size in \u00b5m and nm: give it with --voxel-size");
}

TEST_F(VolumeReaders, tiff_files_that_are_no_volume_are_refused) {
  EXPECT_REFUSED(io::read_tiff, write_stack<uint8_t>(path("one.tif"), labels(false), {.pages = 1}),
                 "has one page, a 2-D image; a volume is a stack of pages");
  EXPECT_REFUSED(io::read_tiff, write_stack<uint8_t>(path("rgb.tif"), labels(false), {.samples = 3}),
                 "has 3 samples per pixel");
  EXPECT_REFUSED(io::read_tiff, write_stack<uint8_t>(path("thumb.tif"), labels(false), {.width = 2}),
                 "page 3 is 2 x 4 of 8-bit samples, page 1 5 x 4 of 8: a volume's slices are alike");
  EXPECT_REFUSED(io::read_tiff,
                 write_stack<uint8_t>(path("hyper.tif"), labels(false),
                                      {.description = "ImageJ=1.54f\nimages=3\nchannels=3\nslices=1\n"}),
                 "an ImageJ hyperstack of 3 channels");
  EXPECT_REFUSED(io::read_tiff,
                 write_stack<uint8_t>(path("big.tif"), labels(false), {.description = "ImageJ=1.54f\nimages=300\n"}),
                 "ImageJ says it holds 300 images, but it has 3 pages");
  EXPECT_REFUSED(io::read_tiff, write("text.tif", "not a tiff at all\n"), "not a TIFF file");
  EXPECT_NE(error_of(io::read_tiff, path("missing.tif"), true).find("cannot open"), std::string::npos);
  // Truncated: the last strips cut off.
  const std::string whole = read(write_stack<uint16_t>(path("whole.tif"), labels(false)));
  const std::string cut = write("cut.tif", whole.substr(0, whole.size() - 40));
  EXPECT_NE(error_of(io::read_tiff, cut).find("cut.tif"), std::string::npos);
}

} // namespace
