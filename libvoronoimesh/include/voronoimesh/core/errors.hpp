#pragma once
/// @file core/errors.hpp
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

/// An option of a run (run/meshing.hpp) out of range or malformed. option()
/// names it as the library does ("grid", "top_k"), problem() says what is
/// wrong, so a front end can name the option its own way (the CLI: "--grid");
/// what() is "option: problem".
class InvalidOption : public InvalidInput {
public:
  /// An option out of range or malformed; what() is located(option, problem).
  /// @param option  the option's name in the library ("grid", "top_k")
  /// @param problem what is wrong with its value
  InvalidOption(std::string option, std::string problem);
  const std::string& option() const { return option_; }   ///< the option's name in the library
  const std::string& problem() const { return problem_; } ///< what is wrong with its value

private:
  std::string option_, problem_;
};

/// A run stopped because its observer asked it to (RunObserver::stop_requested()).
class Cancelled : public Error {
public:
  /// The message is "stopped on request; nothing was written".
  Cancelled() : Error("stopped on request; nothing was written") {}
};

/// A plugin's pass failed at run time, or broke the rules of the plugin ABI (a
/// move that is not finite). The message names the plugin's file and the pass.
class PluginError : public Error {
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

/// "source: message", the one-line form every error takes. Control characters
/// (a newline in a file name, a key or a quoted value) are escaped as `\xNN`, so
/// the result is always one line.
/// @param source  the file, option or object at fault
/// @param message the problem
/// @return "source: message", control characters escaped
std::string located(const std::string& source, const std::string& message);

} // namespace vm
