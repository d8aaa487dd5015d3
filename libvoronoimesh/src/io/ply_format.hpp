#pragma once
/// @file io/ply_format.hpp
/// The PLY container, shared by the mesh reader (read_ply) and the labelled
/// point reader (fields/ply_points.cpp): a strict header parser and a cursor
/// that decodes typed scalars (ascii or binary, either byte order, any scalar
/// type) and skips what the caller does not need. Counts are checked against
/// the bytes left before anything is allocated, so bad input gives an
/// IoError, never a crash.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vm::io::ply {

enum class Format { ascii, binary_le, binary_be };

enum class Kind { int_signed, int_unsigned, floating };

struct ScalarType {
  int size = 0;
  Kind kind = Kind::int_signed;
};

struct Property {
  std::string name;
  ScalarType type;                 ///< the item type for a list
  std::optional<ScalarType> count; ///< set for a list property
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;

  /// Fewest bytes (binary) one item can take: every list empty.
  uint64_t min_bytes() const;
  /// The property called `name`, or null.
  const Property* find(std::string_view name) const;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  /// Every "comment" line, for callers that store data in comments
  /// (write_ply's domain and phase names).
  std::vector<std::string> comments;
  size_t body = 0; ///< offset of the first byte after end_header

  /// The first element called `name`, or null.
  const Element* element(std::string_view name) const;
};

/// The words of a header line, split at spaces and tabs.
std::vector<std::string_view> split_words(std::string_view line);

/// True for an integral value within int32's range (indices, counts, labels).
bool is_int32(double v);

/// A whole PLY file in memory: its parsed header and a read position in the body.
class File {
public:
  /// Reads `path` and parses its header. Throws IoError naming the file.
  explicit File(const std::string& path);

  const Header& header() const { return header_; }
  const std::string& path() const { return path_; }

  /// Throws IoError "<path>: <what>".
  [[noreturn]] void fail(const std::string& what) const;

  /// Walks the body's elements in order: `read(e)` reads element e and returns
  /// true, or returns false to have it skipped. Checks each element's count
  /// against the bytes left first, and that nothing follows the last element.
  void read_body(const std::function<bool(const Element&)>& read);

  /// Reads one scalar of type t; `what()` names the item for error messages
  /// (only called on error, so building the name costs nothing otherwise).
  template <class What>
  double scalar(const ScalarType& t, const What& what) {
    double v = 0;
    std::string_view bad;
    switch (read_scalar(t, v, bad)) {
    case Status::ok: return v;
    case Status::truncated: fail("truncated in " + what());
    default: fail("bad number '" + std::string(bad.substr(0, 40)) + "' in " + what());
    }
  }
  /// An integer-valued scalar that fits int32 (indices, counts, phases).
  template <class What>
  int32_t int_scalar(const ScalarType& t, const What& what) {
    const double v = scalar(t, what);
    if (!is_int32(v)) not_int32(v, what());
    return int32_t(v);
  }
  /// Skips property p of item i of element e.
  void skip(const Element& e, uint64_t i, const Property& p);

private:
  Header parse_header();
  Property parse_property(std::string_view line, const std::vector<std::string_view>& w);
  size_t remaining() const { return data_.size() - pos_; }
  void check_fits(const Element& e);
  enum class Status { ok, truncated, bad_number };
  /// Decodes the next scalar into v; on bad_number, `bad` is the token.
  Status read_scalar(const ScalarType& t, double& v, std::string_view& bad);
  Status ascii_scalar(const ScalarType& t, double& v, std::string_view& bad);
  [[noreturn]] void not_int32(double v, const std::string& what) const;
  void check_end();

  std::string path_;
  std::string data_;
  Header header_;
  size_t pos_ = 0;
};

} // namespace vm::io::ply
