#include "flagsim/core/run_status.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

TEST(RunStatus, TheContractsWordsAndExitCodes) {
  EXPECT_EQ(to_string(RunState::kRunning), "running");
  EXPECT_EQ(to_string(RunState::kComplete), "complete");
  EXPECT_EQ(to_string(RunState::kDiverged), "diverged");
  EXPECT_EQ(to_string(RunState::kInterrupted), "interrupted");
  EXPECT_EQ(RunStatus{}.exit_code(), ExitCode::kSuccess);  // complete unless told otherwise
  EXPECT_EQ((RunStatus{RunState::kDiverged, "NaN"}).exit_code(), ExitCode::kDiverged);
  EXPECT_EQ((RunStatus{RunState::kInterrupted, "SIGINT"}).exit_code(), ExitCode::kInterrupted);
  EXPECT_TRUE(RunStatus{}.complete());
  EXPECT_FALSE((RunStatus{RunState::kDiverged, ""}).complete());
}

}  // namespace
}  // namespace flagsim
