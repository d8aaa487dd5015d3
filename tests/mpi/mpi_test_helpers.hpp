#pragma once
// What the MPI tests share: the rank, examples at a grid, and a check that a
// failure reaches every rank.

#include "voronoimesh/scene.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <string>

namespace vm::test {

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

inline Scene example(const std::string& name, int grid) {
  Scene scene = load_scene(std::string(VM_EXAMPLES_DIR) + "/" + name);
  scene.grid.cells = {grid, grid, grid};
  return scene;
}

/// Runs `f` on every rank and checks that every rank throws E naming `rank`.
template <class E, class F> void expect_every_rank_throws(F&& f, const std::string& rank_text, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "rank " << rank() << " did not throw";
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(rank_text), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

} // namespace vm::test
