#include "flagsim/core/stage_times.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace flagsim {
namespace {

// Sleeps for `ms` milliseconds: a stage of known length.
void sleep_ms(int ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

TEST(StageLaps, EachRunGetsTheTimeSinceTheRunBeforeIt) {
  // Stages of 20 and 5 ms back to back, twice: each gets at least its own
  // time (a sleep lasts at least as long as asked), and the short one less
  // than the long one (a busy machine can lengthen either, by far less than 30 ms).
  StageTimes times;
  const int first = times.add("first"), second = times.add("second");
  StageLaps laps(&times);
  for (int round = 0; round < 2; ++round) {
    laps.run(first, [] { sleep_ms(20); });
    laps.run(second, [] { sleep_ms(5); });
  }
  EXPECT_GE(times.seconds()[first], 0.040);
  EXPECT_GE(times.seconds()[second], 0.010);
  EXPECT_LT(times.seconds()[second], times.seconds()[first]);
}

TEST(StageLaps, AStageNotRegisteredCountsNowhere) {
  StageTimes times;
  const int timed = times.add("timed");
  StageLaps laps(&times);
  laps.run(-1, [] { sleep_ms(20); });
  laps.run(timed, [] { sleep_ms(5); });
  EXPECT_GE(times.seconds()[timed], 0.005);
  EXPECT_LT(times.seconds()[timed], 0.025);  // not also the untimed 20 ms before it
}

TEST(StageLaps, WithoutTimesItOnlyRunsTheWork) {
  int ran = 0;
  StageLaps laps(nullptr);
  laps.run(-1, [&] { ++ran; });
  laps.run(3, [&] { ++ran; });
  EXPECT_EQ(ran, 2);
}

}  // namespace
}  // namespace flagsim
