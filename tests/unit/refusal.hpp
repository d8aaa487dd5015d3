#pragma once
/// @file refusal.hpp
/// The message a reader refuses a file with, for tests of bad input.

#include "voronoimesh/core/errors.hpp"

#include <gtest/gtest.h>

#include <string>

namespace vm::test {

/// The message of the error `read()` throws: an IoError when `io_error`, else
/// an InvalidInput (the other one fails the test); "" when it throws nothing.
template <class Read> std::string refusal(Read read, bool io_error = false) {
  try {
    read();
  } catch (const IoError& e) {
    EXPECT_TRUE(io_error) << e.what();
    return e.what();
  } catch (const InvalidInput& e) {
    EXPECT_FALSE(io_error) << e.what();
    return e.what();
  }
  return "";
}

} // namespace vm::test
