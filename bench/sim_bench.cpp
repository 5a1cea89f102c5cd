// What one simulated control cycle costs: the plant alone (read, write, one physics step at 1 ms)
// and the closed loop with the Cartesian wrapper, per robot, without and with contact (FR3 probe
// pressing on a table). Also one 640 x 480 snapshot (EGL, llvmpipe on a machine without a GPU).
// Run through `make bench`, pinned to one core.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "comply/hardware/control_loop.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace {

using comply::JointState;

const std::filesystem::path kExamples =
    std::filesystem::path(COMPLY_SOURCE_DIR) / "examples" / "sim";

comply::sim::PlantOptions plantOptions(bool contact) {
  comply::sim::PlantOptions options;
  if (contact) {
    options.scene.tool = kExamples / "probe_tool.xml";
    options.scene.objects.push_back(kExamples / "table.xml");
  }
  return options;
}

void plantCycle(benchmark::State& state, const std::string& robot_name) {
  comply::sim::SimulatedRobot robot(comply::model::loadRobotDescription(robot_name),
                                    plantOptions(false));
  JointState joint_state = JointState::zero(robot.dof());
  robot.read(joint_state);
  std::vector<double> torque(robot.appliedEffort().begin(), robot.appliedEffort().end());
  for (auto _ : state) {
    robot.read(joint_state);
    robot.write(torque);
    robot.step();
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

/// Submits a reference 5 mm lower every 50 cycles until z = 0.38 m: the FR3's probe (0.11 m below
/// the TCP) then presses on the table top at 0.30 m.
class Approach final : public comply::hardware::LoopObserver {
 public:
  explicit Approach(comply::pipeline::CartesianWrapper& wrapper)
      : wrapper_(wrapper), command_(wrapper.lastAccepted()) {
    command_.fields = comply::CommandField::kPosition;
  }
  void beforeCycle(std::uint64_t index, double time_s) override {
    if (index % 50 == 0 && command_.position.z() > 0.38) {
      command_.position.z() -= 0.005;
      command_.stamp_s = time_s;
      wrapper_.submit(command_);
    }
  }

 private:
  comply::pipeline::CartesianWrapper& wrapper_;
  comply::CartesianCommand command_;
};

/// The Cartesian wrapper holding the arm at home, run by the control loop every host uses with the
/// plant's time as its clock; with contact, the FR3's probe is first brought down onto the table
/// so that every cycle has an active contact.
void closedLoop(benchmark::State& state, const std::string& robot_name, bool contact) {
  const comply::model::RobotDescription description =
      comply::model::loadRobotDescription(robot_name);
  comply::sim::SimulatedRobot robot(description, plantOptions(contact));
  const comply::pipeline::WrapperConfig config = comply::pipeline::parseWrapperConfig(
      "c: {ros__parameters: {plugin: cartesian_impedance, robot: " + robot_name + "}}", "bench");
  comply::pipeline::CartesianWrapper wrapper(config);
  JointState joint_state = JointState::zero(robot.dof());
  robot.read(joint_state);
  wrapper.activate(joint_state);
  comply::sim::SimulatedClock clock(robot);
  comply::hardware::ControlLoop loop(robot, wrapper, clock, {.period_s = 0.001});
  if (contact) {
    Approach approach(wrapper);
    loop.setObserver(&approach);
    for (int cycle = 0; cycle < 3000; ++cycle) {
      loop.runOnce();
    }
    loop.setObserver(nullptr);
    if (robot.toolContactWrench().head<3>().norm() < 1.0) {
      state.SkipWithError("the probe is not in contact");
      return;
    }
  }
  for (auto _ : state) {
    loop.runOnce();
  }
  state.counters["cycles_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void snapshot(benchmark::State& state) {
  comply::sim::SimulatedRobot robot(comply::model::loadRobotDescription("fr3"), plantOptions(true));
  comply::sim::Renderer renderer(robot.mujocoModel(), 640, 480);
  const comply::sim::CameraView view;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.render(robot.mujocoData(), view));
  }
}

// The plant of every robot on the search path: a robot added as a folder is measured too.
const int kRegistered = [] {
  for (const std::string& robot : comply::model::availableRobots()) {
    benchmark::RegisterBenchmark(("plantCycle/" + robot).c_str(),
                                 [robot](benchmark::State& state) { plantCycle(state, robot); });
  }
  return 0;
}();

}  // namespace

BENCHMARK_CAPTURE(closedLoop, fr3_free, std::string("fr3"), false);
BENCHMARK_CAPTURE(closedLoop, ur5e_free, std::string("ur5e"), false);
BENCHMARK_CAPTURE(closedLoop, fr3_contact, std::string("fr3"), true);
BENCHMARK(snapshot)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
