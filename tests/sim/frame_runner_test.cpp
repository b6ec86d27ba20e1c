#include "flagsim/sim/frame_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "flagsim/core/stop_request.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace flagsim::sim {
namespace {

Scene small_scene(std::vector<std::string> more = {}) {
  more.insert(more.begin(), "flag.fine=[33,49]");
  return parse_scene(default_scene_toml(), kDefaultSceneName, more);
}

// Keeps what it is given; refuses frame `refuse_at` (never, by default).
class Keeper final : public FrameSink {
 public:
  explicit Keeper(int refuse_at = -1) : refuse_at_(refuse_at) {}
  bool take(const Simulation& simulation, const CheckedFrame& frame) override {
    if (frame.index == refuse_at_) return false;
    indices.push_back(frame.index);
    times.push_back(frame.time_s);
    strains.push_back(frame.strain.max);
    positions.emplace_back(simulation.positions().begin(), simulation.positions().end());
    node_strain_sizes.push_back(frame.node_strain.size());
    return true;
  }
  std::vector<int> indices;
  std::vector<double> times, strains;
  std::vector<std::vector<Vec3>> positions;
  std::vector<std::size_t> node_strain_sizes;

 private:
  int refuse_at_;
};

TEST(FrameRunner, EveryFrameGoesToEverySinkInOrderAsTheSimulationSteppedByHand) {
  const Scene scene = small_scene();
  const auto run = make_simulation(scene);
  Keeper first, second;
  FrameSink* const sinks[] = {&first, &second};
  const FrameRunResult result = run_frames(*run, scene, 0, 6, sinks, {.node_strain = true});
  EXPECT_EQ(result.end, FrameRunEnd::kComplete);
  EXPECT_EQ(result.frame, 5);
  EXPECT_EQ(first.indices, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(second.indices, first.indices);
  // Times are n / fps, not a sum of substeps.
  for (int i = 0; i < 6; ++i) EXPECT_EQ(first.times[std::size_t(i)], i / scene.fps);
  // The frames are the ones a caller stepping the simulation itself gets, bit for bit,
  // and the strain the one link_strain measures there.
  const auto by_hand = make_simulation(scene);
  for (int i = 0; i < 6; ++i) {
    if (i > 0) by_hand->advance_frame(nullptr);
    const std::span<const Vec3> x = by_hand->positions();
    EXPECT_TRUE(std::equal(x.begin(), x.end(), first.positions[std::size_t(i)].begin())) << i;
    EXPECT_EQ(first.strains[std::size_t(i)], link_strain(by_hand->lattice(), x).max) << i;
    EXPECT_EQ(first.node_strain_sizes[std::size_t(i)], x.size());
  }
  // Going on from where it stopped: the frames after, as one run of them all.
  Keeper rest;
  FrameSink* const more[] = {&rest};
  EXPECT_EQ(run_frames(*run, scene, 6, 8, more).end, FrameRunEnd::kComplete);
  by_hand->advance_frame(nullptr);
  by_hand->advance_frame(nullptr);
  EXPECT_EQ(rest.indices, (std::vector<int>{6, 7}));
  EXPECT_EQ(rest.node_strain_sizes, (std::vector<std::size_t>{0, 0}));  // not asked for
  EXPECT_TRUE(
      std::equal(rest.positions[1].begin(), rest.positions[1].end(), by_hand->positions().begin()));
}

TEST(FrameRunner, ADivergedFrameEndsTheRunUntakenWithItsReason) {
  // A strain limit below what the wind pulls: the first frame past it is not taken.
  const Scene scene = small_scene({"limits.max_strain=0.004"});
  const auto run = make_simulation(scene);
  Keeper sink;
  FrameSink* const sinks[] = {&sink};
  const FrameRunResult result = run_frames(*run, scene, 0, 60, sinks);
  ASSERT_EQ(result.end, FrameRunEnd::kDiverged);
  EXPECT_GT(result.frame, 0);
  EXPECT_EQ(int(sink.indices.size()), result.frame);  // frames 0 .. frame - 1
  ASSERT_TRUE(result.divergence);
  EXPECT_EQ(result.divergence->cause, Divergence::Cause::kStrain);
  EXPECT_EQ(result.divergence->limit, 0.004);
  EXPECT_GT(result.divergence->value, 0.004);
  for (double strain : sink.strains) EXPECT_LE(strain, 0.004);
}

TEST(FrameRunner, ASinkThatRefusesAFrameEndsTheRunThereAndLaterSinksNeverSeeIt) {
  const Scene scene = small_scene();
  const auto run = make_simulation(scene);
  Keeper refusing(3), after;
  FrameSink* const sinks[] = {&refusing, &after};
  const FrameRunResult result = run_frames(*run, scene, 0, 10, sinks);
  EXPECT_EQ(result.end, FrameRunEnd::kStoppedBySink);
  EXPECT_EQ(result.frame, 3);
  EXPECT_EQ(refusing.indices, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(after.indices, refusing.indices);
}

TEST(FrameRunner, AStopRequestEndsTheRunAfterAWholeFrameOrSaysTheFrameWasCutShort) {
  const Scene scene = small_scene();
  // Raised before frame 0: frame 0 (no stepping) is taken, then the run ends.
  {
    const auto run = make_simulation(scene);
    Keeper sink;
    FrameSink* const sinks[] = {&sink};
    request_stop();
    const FrameRunResult result = run_frames(*run, scene, 0, 5, sinks);
    EXPECT_EQ(result.end, FrameRunEnd::kInterruptedAfter);
    EXPECT_EQ(result.frame, 0);
    EXPECT_EQ(sink.indices, (std::vector<int>{0}));
    // From a later frame on: the stepping sees the request and returns early,
    // so the frame it was making is not a frame; nothing is taken.
    Keeper later;
    FrameSink* const more[] = {&later};
    const FrameRunResult cut = run_frames(*run, scene, 1, 5, more);
    EXPECT_EQ(cut.end, FrameRunEnd::kInterruptedDuring);
    EXPECT_EQ(cut.frame, 1);
    EXPECT_TRUE(later.indices.empty());
    clear_stop_request();
  }
  // The last frame asked for is whole: a request then changes nothing.
  const auto run = make_simulation(scene);
  Keeper sink;
  FrameSink* const sinks[] = {&sink};
  request_stop();
  EXPECT_EQ(run_frames(*run, scene, 0, 1, sinks).end, FrameRunEnd::kComplete);
  clear_stop_request();
}

}  // namespace
}  // namespace flagsim::sim
