#pragma once
/// @file io/nrrd_header_screen.hpp
/// What a NRRD header must not hand Teem (Debian 12's libteem2): checked on
/// the header's text before nrrdLoad reads it. Teem expands a "data file:"
/// pattern ("slice%03d.raw 0 99 1") with sprintf, unchecked, into a buffer ten
/// characters longer than the pattern, and counts its numbers in an int; and
/// when a LIST or SKIPLIST of data files does not suit the sizes, its error
/// message reads past the end of its line buffer. The fuzzer found the last;
/// a %40d overflowed the buffer, a %n wrote through a stray pointer, and a
/// count past INT_MAX never ended. It also found a long field line that
/// overflowed the buffer Teem formats its error messages in.

#include <filesystem>
#include <string>
#include <vector>

namespace vm::io::nrrd {

/// The detached data files the "data file:" field of the NRRD header at
/// `path` names (one name, a LIST or SKIPLIST, or a pattern), in Teem's order,
/// relative names under the header's folder; empty when the data is attached
/// or Teem will refuse the field itself. Call before any nrrdLoad of `path`.
///
/// Throws InvalidInput when a pattern holds anything but one %d (or %Nd, %0Nd
/// with N <= 10) and %%, or counting past its last number overflows an int;
/// when a LIST or SKIPLIST names more or fewer files than the sizes need (every
/// line to the end of the file names one, blank ones too, as Teem reads it), or
/// a SKIPLIST line is not "<skip> <name>"; for the data file "-" (Teem would
/// read standard input); for a header line other than a comment or a key/value
/// pair longer than 800 bytes (Teem's error messages quote such lines into a
/// stack buffer of 1025 bytes). Throws IoError naming the first data file that is not
/// there or not a regular file (a device or a pipe has no size), which also
/// bounds the work of a pattern of four billion numbers.
std::vector<std::filesystem::path> screen_data_files(const std::string& path);

} // namespace vm::io::nrrd
