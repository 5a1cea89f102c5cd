// What one answer to a committed request costs `comply run`'s reader thread (never the cycle's):
// the FR3's Cartesian wrapper on the simulated plant playing a 64-waypoint chunk, asked for n
// times (16, 50, 64) from now on, the answer alone and with its CDR encoding (what the host hands
// its transport process). Run through `BENCH_BINARY=committed_bench scripts/run-bench.sh build`.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "comply/hardware/control_loop.hpp"
#include "comply/host/committed_answers.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply/transport/cdr.hpp"

namespace {

using comply::CartesianCommand;

/// The wrapper on the plant, a chunk along x playing for 3 s: what a host answers from.
struct PlayingChunk {
  PlayingChunk()
      : robot(comply::model::loadRobotDescription("fr3"), {}),
        wrapper(comply::pipeline::parseWrapperConfig(
            "c: {ros__parameters: {plugin: cartesian_impedance, robot: fr3}}", "bench")),
        clock(robot),
        loop(robot, wrapper, clock, {.period_s = 0.001}) {
    comply::JointState state = comply::JointState::zero(robot.dof());
    robot.read(state);
    wrapper.activate(state);
    loop.runOnce();
    const CartesianCommand home = wrapper.lastAccepted();
    comply::Chunk<CartesianCommand> chunk;
    chunk.stamp_s = 1.0;
    chunk.fields = comply::CommandField::kPosition;
    for (int k = 0; k < comply::kMaxChunkWaypoints; ++k) {
      comply::ChunkWaypoint<CartesianCommand> waypoint{now() + 0.05 * k, home};
      waypoint.command.position.x() += 0.001 * k;
      chunk.waypoints.push_back(waypoint);
    }
    if (!wrapper.submitChunk(chunk, now()).accepted) {
      throw std::runtime_error("the chunk was refused");
    }
    for (int cycle = 0; cycle < 300; ++cycle) {
      loop.runOnce();
    }
  }
  /// The host's clock: the plant's time.
  [[nodiscard]] double now() const { return robot.simTime(); }

  comply::sim::SimulatedRobot robot;
  comply::pipeline::CartesianWrapper wrapper;
  comply::sim::SimulatedClock clock;
  comply::hardware::ControlLoop loop;
};

void answer(benchmark::State& state, bool encode) {
  PlayingChunk host;
  comply::host::CommittedAnswers<CartesianCommand> answers(host.wrapper, "fr3_link0");
  comply::transport::Sample<comply::transport::CommittedRequestMessage> request;
  const auto now_ns = static_cast<std::int64_t>(host.now() * 1e9);
  request.message.header.stamp = {1, 0};
  request.message.observation = comply::transport::Stamp::fromNanoseconds(now_ns);
  request.message.dt_s = 1.0 / 30.0;
  request.message.count = static_cast<std::uint32_t>(state.range(0));
  std::vector<std::uint8_t> bytes;
  for (auto _ : state) {
    const comply::transport::CommittedMessage& out = answers.answer(request, now_ns);
    if (encode) {
      comply::transport::encodeCdr(out, bytes);
    }
    benchmark::DoNotOptimize(out.cartesian.data());
  }
  if (encode) {
    state.counters["bytes"] = static_cast<double>(bytes.size());
  }
}

}  // namespace

BENCHMARK_CAPTURE(answer, predicted, false)
    ->Arg(16)
    ->Arg(50)
    ->Arg(64)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(answer, predicted_and_encoded, true)
    ->Arg(16)
    ->Arg(50)
    ->Arg(64)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
