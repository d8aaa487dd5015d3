#pragma once
/// @file errors.hpp
/// The exceptions voronoimesh throws. Every message is one line that names the
/// file or parameter at fault, so the CLI can print it as it is.

#include <stdexcept>
#include <string>

namespace vm {

/// Base of every voronoimesh exception.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Input that cannot be used: a malformed scene, an unknown phase kind, a bad
/// parameter value. The message names the source (file or option) and the problem.
class InvalidInput : public Error {
public:
  using Error::Error;
};

/// A file could not be read or written.
class IoError : public Error {
public:
  using Error::Error;
};

/// A mesh failed a topological check it must pass (a bug, or unusable input).
class TopologyError : public Error {
public:
  using Error::Error;
};

/// "source: message", the one-line form every error takes.
std::string located(const std::string& source, const std::string& message);

} // namespace vm
