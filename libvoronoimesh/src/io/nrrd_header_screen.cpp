#include "io/nrrd_header_screen.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <teem/nrrd.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string_view>

namespace vm::io::nrrd {

namespace fs = std::filesystem;
using detail::cat;

namespace {

/// A line of the header: the text between line ends ("\n", "\r\n" or a lone
/// "\r", as Teem's airOneLine reads them), or text the end of the file cuts off.
struct Line {
  std::string text;
  bool ended = true; ///< false when the end of the file cut it off
};

std::optional<Line> next_line(std::istream& in) {
  Line line;
  int c;
  while ((c = in.get()) != EOF && c != '\n' && c != '\r') line.text += char(c);
  if (c == EOF && line.text.empty()) return std::nullopt;
  if (c == '\r' && in.peek() == '\n') in.get();
  line.ended = c != EOF;
  return line;
}

/// Throws unless `line` (number `number` of the header at `path`) is free of
/// NUL bytes: Teem reads a long line in pieces and joins them as C strings, so
/// what it makes of a line with a NUL depends on its buffer's size.
void require_no_nul(const std::string& path, const Line& line, int number) {
  if (line.text.find('\0') != std::string::npos)
    throw InvalidInput(located(path, cat("line ", number, " of its header holds a NUL byte")));
}

/// Teem formats each of its error messages with vsprintf into a stack buffer of
/// 1025 bytes (biff's _HACK_STRLEN), and a message may quote a header line whole
/// (a field it cannot parse, a value it refuses). A longer line smashed the
/// stack (the fuzzer found it). Each message quotes one line at most, in at most
/// 150 bytes of its own text, so lines up to this length are safe.
constexpr size_t kLongestQuotedLine = 800;

/// Throws when `line` (number `number`) is longer than Teem can quote. Comments
/// and key/value pairs ("key:=value", where ":=" comes before any ": ") are
/// never quoted, so they may be as long as they are: 3D Slicer writes
/// key/value pairs of two kilobytes.
void require_quotable(const std::string& path, const Line& line, int number) {
  const std::string& text = line.text;
  if (text.size() <= kLongestQuotedLine || text.starts_with('#')) return;
  if (text.substr(0, text.find(": ")).find(":=") != std::string::npos) return;
  throw InvalidInput(located(path, cat("line ", number, " of its header is ", text.size(),
                                       " bytes long; a field line may have at most ", kLongestQuotedLine,
                                       " (Teem would overflow its message buffer quoting it)")));
}

/// The header fields the screen needs, found as Teem finds them (the name
/// before the first ": ", matched by Teem's own nrrdField enum), and for a
/// LIST or SKIPLIST every line after the "data file:" one.
struct Header {
  std::optional<std::string> dimension, sizes, data_file;
  std::vector<std::string> list;
};

/// True when Teem reads the value of "data file:" as a pattern: its first %
/// that is not %% is followed by digits and 'd' (Teem's _nrrdContainsPercentThisAndMore).
bool teem_sees_pattern(std::string_view value) {
  size_t at = 0;
  while ((at = value.find('%', at)) != std::string_view::npos && at + 1 < value.size() && value[at + 1] == '%') at += 2;
  if (at == std::string_view::npos || at + 1 >= value.size()) return false;
  const size_t end = value.find_first_not_of("0123456789", at + 1);
  return end != std::string_view::npos && value[end] == 'd';
}

/// True when Teem reads the value of "data file:" as a LIST or SKIPLIST (it compares the start only).
bool teem_sees_list(std::string_view value) {
  return !teem_sees_pattern(value) && (value.starts_with("LIST") || value.starts_with("SKIPLIST"));
}

/// Reads the header at `path` up to its "data file:" line (and for a list the
/// file's remaining lines), the blank line that ends it, or a line Teem refuses.
/// A line the end of the file cuts off is read too: Teem drops a short one but
/// keeps a long one. Names in a list must end with a line end.
Header read_header(const std::string& path) {
  Header h;
  std::ifstream in(path, std::ios::binary);
  int number = 1;
  const auto magic = next_line(in);
  if (!magic) return h;
  require_no_nul(path, *magic, number);
  require_quotable(path, *magic, number);
  if (!magic->text.starts_with("NRRD")) return h;
  while (const auto line = next_line(in)) {
    require_no_nul(path, *line, ++number);
    require_quotable(path, *line, number);
    const std::string& text = line->text;
    if (text.empty()) break;
    if (text.front() == '#') continue;
    const size_t colon = text.find(": ");
    if (colon == std::string::npos) {
      if (text.find(":=") == std::string::npos) break;
      continue;
    }
    const size_t start = text.find_first_not_of(" \t", colon + 2);
    const std::string value = start == std::string::npos ? "" : text.substr(start);
    switch (airEnumVal(nrrdField, text.substr(0, colon).c_str())) {
    case nrrdField_dimension: h.dimension = value; break;
    case nrrdField_sizes: h.sizes = value; break;
    case nrrdField_data_file:
      h.data_file = value;
      if (teem_sees_list(value))
        while (const auto name = next_line(in)) {
          require_no_nul(path, *name, ++number);
          if (!name->ended)
            throw InvalidInput(
                located(path, cat("data file ", value.starts_with("LIST") ? "LIST" : "SKIPLIST", ": its last line '",
                                  name->text, "' does not end with a line end (Teem would drop or misread it)")));
          h.list.push_back(name->text);
        }
      return h;
    default: break;
    }
  }
  return h;
}

/// A pattern's file names: `before` + the number as `conversion` prints it + `after`.
struct Pattern {
  std::string before, conversion, after;
  std::string name(int number) const {
    char digits[32];
    std::snprintf(digits, sizeof digits, conversion.c_str(), number);
    return before + digits + after;
  }
};

/// `format` split around its one %d, %Nd or %0Nd (N <= 10: Teem's buffer holds
/// ten characters more than the format), with %% as %; nullopt for any other
/// use of % (Teem hands the format to sprintf with one int argument).
std::optional<Pattern> parse_pattern(std::string_view format) {
  Pattern p;
  bool converted = false;
  for (size_t i = 0; i < format.size(); ++i) {
    std::string& out = converted ? p.after : p.before;
    if (format[i] != '%') {
      out += format[i];
    } else if (i + 1 < format.size() && format[i + 1] == '%') {
      out += '%';
      ++i;
    } else {
      const size_t end = format.find_first_not_of("0123456789", i + 1);
      if (converted || end == std::string_view::npos || format[end] != 'd') return std::nullopt;
      const std::string_view digits = format.substr(i + 1, end - i - 1);
      const std::string_view width = digits.substr(std::min(digits.size(), digits.find_first_not_of('0')));
      if (width.size() > 2 || (!width.empty() && std::stoi(std::string(width)) > 10)) return std::nullopt;
      p.conversion = std::string(digits.starts_with('0') ? "%0" : "%") + std::string(width) + "d";
      converted = true;
      i = end;
    }
  }
  if (!converted) return std::nullopt;
  return p;
}

/// `name` resolved as Teem opens it (relative to the header's folder unless
/// absolute), after throwing IoError unless it is a regular file; `what`
/// describes it in the message.
fs::path data_file(const std::string& path, const std::string& name, const std::string& what) {
  if (name == "-")
    throw InvalidInput(located(path, "data file '-' (standard input) is not read; name the file that holds the data"));
  const fs::path file = fs::path(name).is_absolute() ? fs::path(name) : fs::path(path).parent_path() / name;
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status))
    throw IoError(located(path, cat("cannot open ", what, " ", file.string(), " (No such file or directory)")));
  if (!fs::is_regular_file(status))
    throw IoError(located(path, cat(what, " ", file.string(), " is not a regular file")));
  return file;
}

std::vector<fs::path> pattern_files(const std::string& path, const std::string& value) {
  // Teem's reading: the pattern up to the first blank, then min, max and step.
  const size_t blank = value.find_first_of(" \t");
  const std::string format = value.substr(0, blank);
  const std::optional<Pattern> pattern = parse_pattern(format);
  if (!pattern)
    throw InvalidInput(located(path, cat("data file pattern '", format,
                                         "' must hold one %d (or %Nd, %0Nd with N <= 10) and no other % than %%")));
  int min = 0, max = 0, step = 0;
  const std::string numbers = blank == std::string::npos ? "" : value.substr(blank);
  if (std::sscanf(numbers.c_str(), "%d %d %d", &min, &max, &step) != 3 || step == 0 || (max > min && step < 0) ||
      (max < min && step > 0))
    return {}; // Teem refuses these, or counts no file
  const int64_t count = (int64_t(max) - min) / step + 1;
  if (const int64_t past = min + count * step; past > INT_MAX || past < INT_MIN)
    throw InvalidInput(located(path, cat("data file pattern counts from ", min, " to ", max, " by ", step,
                                         ", past the range of an int (Teem's counter would overflow)")));
  std::vector<fs::path> files;
  for (int64_t k = 0; k < count; ++k)
    files.push_back(data_file(path, pattern->name(int(min + k * step)),
                              cat("data file ", k + 1, " of ", count, " of its pattern,")));
  return files;
}

/// The axis sizes of `h`, parsed as Teem parses them; nullopt where Teem
/// refuses them itself before it reads a list.
std::optional<std::vector<uint64_t>> sizes_of(const Header& h) {
  unsigned dim = 0;
  if (!h.dimension || !h.sizes || std::sscanf(h.dimension->c_str(), "%u", &dim) != 1 || dim < 1 || dim > NRRD_DIM_MAX)
    return std::nullopt;
  std::vector<uint64_t> sizes;
  size_t at = 0;
  while ((at = h.sizes->find_first_not_of(" \t", at)) != std::string::npos) {
    const size_t end = std::min(h.sizes->size(), h.sizes->find_first_of(" \t", at));
    unsigned long long size = 0;
    if (std::sscanf(h.sizes->substr(at, end - at).c_str(), "%llu", &size) != 1 || size < 1) return std::nullopt;
    sizes.push_back(size);
    at = end;
  }
  if (sizes.size() != dim) return std::nullopt;
  return sizes;
}

std::vector<fs::path> list_files(const std::string& path, const Header& h) {
  const std::optional<std::vector<uint64_t>> sizes = sizes_of(h);
  if (!sizes) return {};
  const bool skiplist = h.data_file->starts_with("SKIPLIST");
  const std::string kind = skiplist ? "SKIPLIST" : "LIST";
  // Each file holds a piece of this many dimensions: given after the word, else one less than the volume's.
  unsigned piece_dim = unsigned(sizes->size()) - 1;
  if (const std::string rest = h.data_file->substr(kind.size());
      !rest.empty() && (std::sscanf(rest.c_str(), "%u", &piece_dim) != 1 || piece_dim < 1 || piece_dim > sizes->size()))
    return {}; // Teem refuses this before it reads the names
  std::vector<std::string> names;
  for (size_t i = 0; i < h.list.size(); ++i) {
    const std::string& line = h.list[i];
    if (!skiplist) {
      names.push_back(line);
      continue;
    }
    long skip = 0;
    const size_t space = line.find(' ');
    if (std::sscanf(line.c_str(), "%ld", &skip) != 1 || space == std::string::npos || space + 1 == line.size())
      throw InvalidInput(
          located(path, cat("SKIPLIST line ", i + 1, " '", line, "' is not '<bytes to skip> <file name>'")));
    names.push_back(line.substr(space + 1));
  }
  // No name at all reads the data after the header, as one file.
  const uint64_t count = std::max<uint64_t>(names.size(), 1);
  if (piece_dim < sizes->size()) {
    uint64_t pieces = 1;
    for (size_t a = piece_dim; a < sizes->size(); ++a)
      if (__builtin_mul_overflow(pieces, (*sizes)[a], &pieces)) return {}; // Teem refuses such sizes
    if (count != pieces)
      throw InvalidInput(located(path, cat("data file ", kind, " names ", count, count == 1 ? " file" : " files",
                                           " (every line to the end of the file names one, blank ones too); the sizes ",
                                           "need ", pieces, ", one per ", piece_dim, "-D piece")));
  } else if (const uint64_t slices = sizes->back(); count > slices || slices % count != 0) {
    throw InvalidInput(located(path, cat("data file ", kind, " names ", count, count == 1 ? " file" : " files",
                                         " (every line to the end of the file names one, blank ones too); they must ",
                                         "share the ", slices, " slices of the last axis evenly")));
  }
  std::vector<fs::path> files;
  for (const std::string& name : names) files.push_back(data_file(path, name, "its data file"));
  return files;
}

} // namespace

std::vector<fs::path> screen_data_files(const std::string& path) {
  const Header h = read_header(path);
  if (!h.data_file) return {};
  if (teem_sees_pattern(*h.data_file)) return pattern_files(path, *h.data_file);
  if (teem_sees_list(*h.data_file)) return list_files(path, h);
  return {data_file(path, *h.data_file, "its data file")};
}

} // namespace vm::io::nrrd
