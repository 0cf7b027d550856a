// The test programs' main: GoogleTest's, after the allocator tuning that
// facecap's own main does, so that the suites run the code as the tool runs
// it (without it, a synthetic 720p render's buffers fault in afresh every
// frame: TrackEval's true-landmark fit of one seed took 66 s, 17 of them in
// the kernel).
#include <gtest/gtest.h>

#include "facecap/core/allocator_tuning.hpp"

int main(int argc, char** argv) {
  facecap::keep_large_allocations_resident();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
