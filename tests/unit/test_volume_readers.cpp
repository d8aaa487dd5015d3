// The MetaImage and INR readers: small volumes with known voxels and geometry
// written byte by byte (or through zlib), read back and compared; then broken
// files, each of which must be refused with a message naming the file and the
// problem. (NIfTI: test_nifti_reader.cpp.)

#include "volume_files.hpp"

using namespace vm;
using namespace vm::volume_test;

namespace {

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
  EXPECT_TRUE(v.spacing_stated);
}

TEST_F(VolumeReaders, metaimage_big_endian_float_and_uint) {
  write("f.mha", mha_header("MET_FLOAT", "ElementByteOrderMSB = True\nPosition = 1 2 3\n") +
                     encode<float>(values(), true));
  io::Volume v = io::read_metaimage(path("f.mha"));
  expect_values(v);
  expect_geometry(v, Vec3::Ones(), Vec3(1, 2, 3));
  EXPECT_FALSE(v.spacing_stated); // no ElementSpacing nor ElementSize

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
  EXPECT_NE(error_of(io::read_metaimage, path("zero.mhd"), true)
                .find("zero.mhd: ElementDataFile /dev/zero: cannot read: it is a character device, not a regular file"),
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
  EXPECT_TRUE(v.spacing_stated);
}

TEST_F(VolumeReaders, inr_big_endian_short_and_int) {
  write("s.inr", inr_header("TYPE=signed fixed\nPIXSIZE=16 bits\nCPU=sun\n") + encode<int16_t>(labels(true), true));
  io::Volume v = io::read_inr(path("s.inr"));
  expect_labels(v, true);
  expect_geometry(v, Vec3::Ones(), Vec3::Zero());
  EXPECT_FALSE(v.spacing_stated); // no VX, VY, VZ: unit voxels, which load_input() says
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
