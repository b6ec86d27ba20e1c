// stop_request.cpp: the flag a signal handler raises and the long loops read.
#include "flagsim/core/stop_request.hpp"

#include <gtest/gtest.h>

#include <csignal>

namespace flagsim {
namespace {

extern "C" void raise_stop(int /*signal*/) {
  request_stop();
}

TEST(StopRequest, RaisedByASignalHandlerReadByTheLoopsClearedForTheNextRun) {
  clear_stop_request();
  EXPECT_FALSE(stop_requested());
  const auto previous = std::signal(SIGUSR1, raise_stop);
  ASSERT_NE(previous, SIG_ERR);
  ASSERT_EQ(std::raise(SIGUSR1), 0);
  EXPECT_TRUE(stop_requested());
  EXPECT_TRUE(stop_requested());  // reading does not clear it
  clear_stop_request();
  EXPECT_FALSE(stop_requested());
  std::signal(SIGUSR1, previous);
}

}  // namespace
}  // namespace flagsim
