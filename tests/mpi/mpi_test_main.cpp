// main() of the MPI tests: every rank runs every test in the same order (each
// test makes the same collective calls on all ranks); rank 0 prints the report.

#include "mpi_test_helpers.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

using vm::test::rank;

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 prints the report; the others print their failures.
  if (rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int failed = RUN_ALL_TESTS();
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
