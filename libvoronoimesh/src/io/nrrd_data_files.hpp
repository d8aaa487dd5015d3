#pragma once
/// @file io/nrrd_data_files.hpp
/// Whether a NRRD's data files can hold as many samples as its header says,
/// checked before Teem allocates them: a header of a few bytes can describe
/// gigabytes. The samples follow the header in its own file, or lie in the
/// detached files that "data file:" names (nrrd_header_screen.hpp).

#include <teem/nrrd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vm::io::nrrd {

/// Throws unless the data files of the NRRD at `path` can hold `samples`
/// values of `sample_bytes` bytes each (and the byte skips before them) in its
/// encoding: InvalidInput naming the files when raw data is shorter, hex data
/// shorter than two digits a byte, ASCII data than a character a sample, gzip
/// data than deflate's best ratio can inflate to; bzip2 data, whose runs can
/// compress millions to one, is inflated and counted (not kept) when it would
/// need a better ratio than deflate's. `io` holds the header as read by
/// nrrdLoad with skipData and keepNrrdDataFileOpen (so that dataFile is where
/// a single file's data starts); `detached` is what screen_data_files()
/// (nrrd_header_screen.hpp) returned, empty when the data is attached.
void check_data_fits(const std::string& path, NrrdIoState& io, const std::vector<std::filesystem::path>& detached,
                     uint64_t samples, uint64_t sample_bytes);

} // namespace vm::io::nrrd
