// NRRD data in files of its own ("data file:" as one name, a LIST, a SKIPLIST
// or a numbered pattern) and compressed NRRD data: every form reads the same
// volume; sizes its files cannot hold, and patterns Teem cannot expand safely,
// are refused before anything is allocated, with the file named. (gzip and
// bzip2 streams are made as the fuzz targets make theirs, input_layouts.hpp.)

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "input_layouts.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

using namespace vm;

namespace {

/// A 4 x 3 x 2 uchar volume: labels 0..23, two slices of 12.
const std::string header = "type: uchar\ndimension: 3\nsizes: 4 3 2\n";
std::string slice(int k) {
  std::string s(12, '\0');
  std::iota(s.begin(), s.end(), char(12 * k));
  return s;
}
const std::string samples = slice(0) + slice(1);

using fuzz::bzip2;
using fuzz::gzip;

class NrrdDataFiles : public test::ScratchDir {
protected:
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }

  /// The message read_nrrd refuses `file` with, as IoError when `io_error`.
  static std::string error_of(const std::string& file, bool io_error = false) {
    const std::string message = test::refusal([&] { io::read_nrrd(file); }, io_error);
    EXPECT_NE(message, "") << file << " was read";
    return message;
  }
};

#define EXPECT_HAS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

void expect_the_volume(const io::Volume& v) {
  EXPECT_EQ(v.size, (std::array<int64_t, 3>{4, 3, 2}));
  ASSERT_EQ(v.labels.size(), 24u);
  for (int i = 0; i < 24; ++i) EXPECT_EQ(v.labels[size_t(i)], i);
}

} // namespace

TEST_F(NrrdDataFiles, every_form_of_data_file_reads_the_same_volume) {
  write("one.raw", samples);
  write("s000.raw", slice(0));
  write("s001.raw", slice(1));
  write("skips.raw", "xyz" + slice(0) + "ab" + slice(1));
  write("z1.gz", gzip(slice(0)));
  write("z0.gz", gzip(slice(1)));
  write("lines.bz2", "a text line\n" + bzip2("sk" + samples));
  const std::vector<std::pair<std::string, std::string>> headers = {
      {"one.nhdr", "encoding: raw\ndata file: one.raw\n"},
      {"absolute.nhdr", "encoding: raw\ndata file: " + path("one.raw") + "\n"},
      {"list.nhdr", "encoding: raw\ndata file: LIST\ns000.raw\ns001.raw\n"},
      {"pattern.nhdr", "encoding: raw\ndata file: s%03d.raw 0 1 1\n"},
      {"pattern_down_gzip.nhdr", "encoding: gzip\ndata file: z%d.gz 1 0 -1 2\n"},
      {"bzip2_skips.nhdr", "encoding: bzip2\nline skip: 1\nbyte skip: 2\ndata file: lines.bz2\n"},
  };
  for (const auto& [name, fields] : headers) {
    SCOPED_TRACE(name);
    expect_the_volume(io::read_nrrd(write(name, "NRRD0004\n" + header + fields)));
  }
  // NRRD0006's SKIPLIST: a byte skip per file.
  expect_the_volume(io::read_nrrd(write(
      "skiplist.nhdr", "NRRD0006\n" + header + "encoding: raw\ndata file: SKIPLIST 2\n3 skips.raw\n17 skips.raw\n")));
  // Attached, compressed either way.
  expect_the_volume(io::read_nrrd(write("gzip.nrrd", "NRRD0004\n" + header + "encoding: gzip\n\n" + gzip(samples))));
  expect_the_volume(io::read_nrrd(write("bzip2.nrrd", "NRRD0004\n" + header + "encoding: bzip2\n\n" + bzip2(samples))));
}

// bzip2 compresses runs far beyond deflate's 1032:1: such files are inflated
// and counted before Teem allocates, so that they read when their data is all
// there and are refused when it is not.
TEST_F(NrrdDataFiles, bzip2_beyond_deflates_ratio_is_counted_before_allocating) {
  const std::string ones(64 * 64 * 64, '\1');
  const std::string bz = bzip2(ones);
  ASSERT_LT(bz.size() * 1032 + 64, ones.size()); // the counted case
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nencoding: bzip2\n";
  const io::Volume v = io::read_nrrd(write("ones.nrrd", head + "sizes: 64 64 64\n\n" + bz));
  EXPECT_EQ(v.labels, std::vector<int32_t>(ones.size(), 1));

  const std::string msg = error_of(write("short.nrrd", head + "sizes: 64 64 128\n\n" + bz));
  EXPECT_HAS(msg, "short.nrrd: truncated: the header describes 524288 samples (524288 bytes) of bzip2 data; its file "
                  "inflates to 262144 of the 524288 bytes it must hold");

  std::string corrupt = bz;
  corrupt[corrupt.size() / 2] ^= 0x5a;
  EXPECT_HAS(error_of(write("corrupt.nrrd", head + "sizes: 64 64 128\n\n" + corrupt)),
             "corrupt.nrrd: its file is not valid bzip2 data (BZ_DATA_ERROR)");
  write("d.bz2", bz);
  EXPECT_HAS(error_of(write("detached.nhdr", head + "sizes: 64 64 128\ndata file: d.bz2\n")),
             "its data file " + path("d.bz2") + " inflates to 262144 of the 524288 bytes");
}

// A header of a hundred bytes must not make Teem allocate what its data files
// cannot hold: the sum of their sizes bounds raw data, deflate's ratio gzip data.
TEST_F(NrrdDataFiles, sizes_the_data_files_cannot_hold_are_refused_naming_them) {
  write("s000.raw", slice(0));
  write("s001.raw", slice(1));
  const std::string big = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1000 1000 100\nencoding: raw\n";
  // Two slabs of 50 slices (the 3 after the numbers: each file holds 3-D data).
  EXPECT_HAS(error_of(write("pattern.nhdr", big + "data file: s%03d.raw 0 1 1 3\n")),
             "pattern.nhdr: truncated: the header describes 100000000 samples of raw data, which take at least "
             "100000000 bytes; its 2 data files (" +
                 path("s000.raw") + " ... " + path("s001.raw") + ") hold 24");
  EXPECT_HAS(error_of(write("list.nhdr", big + "data file: LIST 3\ns000.raw\ns001.raw\n")), "its 2 data files (");
  EXPECT_HAS(error_of(write("one.nhdr", big + "data file: s000.raw\n")),
             "its data file " + path("s000.raw") + " holds 12");
  write("z.gz", gzip(slice(0)));
  EXPECT_HAS(error_of(write("gzip.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1000 1000 100\n"
                                         "encoding: gzip\ndata file: z.gz\n")),
             "the header describes 100000000 samples (100000000 bytes) of gzip data; its data file " + path("z.gz") +
                 " holds ");
  // The bytes skipped count too.
  EXPECT_HAS(error_of(write("skip.nhdr", "NRRD0004\n" + header +
                                             "encoding: raw\nbyte skip: 100\ndata file: LIST\n"
                                             "s000.raw\ns001.raw\n")),
             "after skipping 200 bytes");
}

// Teem expands a pattern with sprintf into a buffer ten characters longer than
// the pattern, and counts its numbers in an int: a %40d overflowed the buffer,
// a %n wrote through a stray pointer, and a count past INT_MAX never ended.
TEST_F(NrrdDataFiles, patterns_teem_cannot_expand_safely_are_refused_before_teem_reads_them) {
  write("s1.raw", samples);
  const std::string head = "NRRD0004\n" + header + "encoding: raw\ndata file: ";
  for (const std::string pattern : {"s%40d.raw", "s%d%n.raw", "s%d%s.raw", "s%d%d.raw", "s%011d.raw"}) {
    SCOPED_TRACE(pattern);
    EXPECT_HAS(error_of(write("bad.nhdr", head + pattern + " 1 1 1\n")),
               "bad.nhdr: data file pattern '" + pattern + "' must hold one %d (or %Nd, %0Nd with N <= 10)");
  }
  EXPECT_HAS(error_of(write("overflow.nhdr", head + "s%d.raw 2147483600 2147483647 100 3\n")),
             "overflow.nhdr: data file pattern counts from 2147483600 to 2147483647 by 100, past the range of an int");
  // %% is a literal %, widths up to 10 are safe.
  write("p%0000000001.raw", samples);
  expect_the_volume(io::read_nrrd(write("percent.nhdr", head + "p%%%010d.raw 1 1 1 3\n")));
}

// When a LIST or SKIPLIST does not suit the sizes, Teem's message read past
// the end of its line buffer (found by fuzz_nrrd_detached): such lists are
// refused before Teem reads them. Teem reads every line to the end of the
// file as a name, blank ones too.
TEST_F(NrrdDataFiles, lists_that_do_not_suit_the_sizes_are_refused_before_teem_reads_them) {
  write("s000.raw", slice(0));
  write("s001.raw", slice(1));
  const std::string head = "NRRD0004\n" + header + "encoding: raw\ndata file: ";
  EXPECT_HAS(error_of(write("three.nhdr", head + "LIST\ns000.raw\ns001.raw\ns001.raw\n")),
             "three.nhdr: data file LIST names 3 files (every line to the end of the file names one, blank ones too); "
             "the sizes need 2, one per 2-D piece");
  EXPECT_HAS(error_of(write("blank.nhdr", head + "LIST\ns000.raw\ns001.raw\n\n")), "LIST names 3 files");
  EXPECT_HAS(
      error_of(write("slabs.nhdr", head + "LIST 3\ns000.raw\ns001.raw\ns001.raw\n")),
      "names 3 files (every line to the end of the file names one, blank ones too); they must share the 2 slices "
      "of the last axis evenly");
  EXPECT_HAS(error_of(write("skiplist.nhdr", "NRRD0006\n" + header +
                                                 "encoding: raw\ndata file: SKIPLIST\n"
                                                 "0 s000.raw\ns001.raw\n")),
             "skiplist.nhdr: SKIPLIST line 2 's001.raw' is not '<bytes to skip> <file name>'");
  // Teem drops a short name the end of the file cuts off, but keeps a long one;
  // and what it makes of a line with a NUL byte depends on its buffer's size.
  EXPECT_HAS(error_of(write("cut.nhdr", head + "LIST\ns000.raw\ns001.raw")),
             "cut.nhdr: data file LIST: its last line 's001.raw' does not end with a line end");
  EXPECT_HAS(error_of(write("nul.nhdr", head + "LIST\ns000.raw\ns001.raw\n" + std::string(500, '\0') + "\n")),
             "nul.nhdr: line 9 of its header holds a NUL byte");
  EXPECT_HAS(error_of(write("nul_first.nhdr", std::string(1, '\0') + "NRRD0004\n" + header)),
             "nul_first.nhdr: line 1 of its header holds a NUL byte");
}

// Each file a pattern names must be there: the first missing one is named, at
// once, however many numbers the pattern counts.
TEST_F(NrrdDataFiles, the_first_missing_file_of_a_pattern_is_named_at_once) {
  write("s000.raw", slice(0));
  write("s001.raw", slice(1));
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 3 3\nencoding: raw\ndata file: ";
  EXPECT_HAS(error_of(write("three.nhdr", head + "s%03d.raw 0 2 1\n"), true),
             "three.nhdr: cannot open data file 3 of 3 of its pattern, " + path("s002.raw"));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_HAS(error_of(write("billions.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1 1 2000000000\n"
                                             "encoding: raw\ndata file: s%03d.raw 0 1999999999 1\n"),
                      true),
             "data file 3 of 2000000000 of its pattern, " + path("s002.raw"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST_F(NrrdDataFiles, standard_input_devices_and_missing_files_are_not_data_files) {
  const std::string head = "NRRD0004\n" + header + "encoding: raw\ndata file: ";
  EXPECT_HAS(error_of(write("stdin.nhdr", head + "-\n")), "stdin.nhdr: data file '-' (standard input) is not read");
  EXPECT_HAS(error_of(write("zero.nhdr", head + "/dev/zero\n"), true),
             "zero.nhdr: its data file /dev/zero is not a regular file");
  EXPECT_HAS(error_of(write("gone.nhdr", head + "LIST\ngone.raw\nother.raw\n"), true),
             "gone.nhdr: cannot open its data file " + path("gone.raw"));
}

// Teem quotes a field line it cannot parse in a message formatted into a stack
// buffer of 1025 bytes: a longer line smashed its stack (found by the fuzzer).
// Field lines are bounded; comments and key/value pairs, which Teem never
// quotes and 3D Slicer writes two kilobytes long, are not.
TEST_F(NrrdDataFiles, field_lines_are_bounded_where_teem_would_quote_them) {
  const std::string long_text(1100, 'x');
  EXPECT_HAS(error_of(write("field.nrrd", "NRRD0004\n" + long_text + ": 3\n" + header + "encoding: raw\n\n" + samples)),
             "field.nrrd: line 2 of its header is 1103 bytes long; a field line may have at most 800");
  EXPECT_HAS(error_of(write("value.nrrd", "NRRD0004\n" + header + "encoding: " + long_text + "\n\n" + samples)),
             "value.nrrd: line 5 of its header is 1110 bytes long");
  EXPECT_HAS(error_of(write("no_colon.nrrd", "NRRD0004\n" + header + long_text + "\n\n" + samples)),
             "no_colon.nrrd: line 5 of its header is 1100 bytes long");
  EXPECT_HAS(error_of(write("magic.nrrd", "NRRD0004" + long_text + "\n" + header + "encoding: raw\n\n" + samples)),
             "magic.nrrd: line 1 of its header is 1108 bytes long");
  expect_the_volume(io::read_nrrd(write("long_key_value.nrrd", "NRRD0004\n" + header + "Segmentation_Parameters:=" +
                                                                   long_text + ": and more\n# " + long_text +
                                                                   "\nencoding: raw\n\n" + samples)));
}
