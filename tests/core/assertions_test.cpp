// The project's preconditions are `assert`s (STYLE.md: our own bugs). This
// says which builds check them: scripts/test_asserts.sh builds without
// NDEBUG and must see a broken precondition stop the program; the Release
// build (NDEBUG) skips, saying so.
#include <gtest/gtest.h>

#include "flagsim/core/lattice.hpp"

namespace flagsim {
namespace {

TEST(Assertions, ABrokenPreconditionStopsTheProgramWhereTheyAreOn) {
#ifdef NDEBUG
  GTEST_SKIP() << "NDEBUG: assertions are off in this build; scripts/test_asserts.sh runs them";
#else
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(Lattice::rectangle(1, 5, 1.0, 1.0, Vec3::Zero()), "rows >= 2");
#endif
}

}  // namespace
}  // namespace flagsim
