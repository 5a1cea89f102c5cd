// `comply run --sim` keeps the simulation to the wall clock, and its timing summary measures the
// cycles against it: a control thread that stalls for 15 ms is lateness and overruns in the
// summary, exactly as the run's recording shows them. Measured on the simulation's own clock, a
// recording with 66 stalls of 2 to 15 ms once came with "lateness p99 10 us, 0 overruns".

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <regex>
#include <sstream>
#include <thread>

#include "cdr_fields.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/hardware_backends.hpp"
#include "comply/host/live_host.hpp"
#include "comply/record/mcap_reader.hpp"
#include "live_support.hpp"

namespace comply::live_test {
namespace {

constexpr double kPeriodS = 1.0 / 1000.0;  // the host's default --rate
constexpr int kStallAtRead = 300;

/// The simulated arm, whose read() sleeps 15 ms once, at its kStallAtRead-th read: the control
/// thread stalled in a cycle.
class StallingArm final : public hardware::HardwareInterface {
 public:
  explicit StallingArm(std::shared_ptr<hardware::HardwareInterface> arm) : arm_(std::move(arm)) {}
  [[nodiscard]] int dof() const noexcept override { return arm_->dof(); }
  bool read(JointState& state) noexcept override {
    if (++reads_ == kStallAtRead) {
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
    }
    return arm_->read(state);
  }
  bool write(std::span<const double> torque) noexcept override { return arm_->write(torque); }
  [[nodiscard]] bool accepts(OutputMode mode) const noexcept override {
    return arm_->accepts(mode);
  }
  bool writeCommand(const ActuatorCommand& command) noexcept override {
    return arm_->writeCommand(command);
  }
  bool hold() noexcept override { return arm_->hold(); }
  [[nodiscard]] bool compensatesGravity() const noexcept override {
    return arm_->compensatesGravity();
  }
  bool readWrench(Vector6d& wrench) noexcept override { return arm_->readWrench(wrench); }
  bool readSequence(std::uint64_t& sequence) noexcept override {
    return arm_->readSequence(sequence);
  }

 private:
  std::shared_ptr<hardware::HardwareInterface> arm_;
  int reads_ = 0;
};

/// The built-in "sim" backend (and its paced clock) with the stalling arm in front of the plant.
host::HardwareBackend stallingSimulation(const pipeline::WrapperConfig& config,
                                         const hardware::BackendContext& context) {
  host::HardwareBackend backend = host::makeHardware("sim", config, context);
  backend.hardware = std::make_shared<StallingArm>(backend.hardware);
  return backend;
}

/// What the summary line of `comply run` says about the cycles.
struct Summary {
  std::uint64_t cycles = 0;
  std::uint64_t overruns = 0;
  long max_lateness_us = -1;
};

Summary summaryOf(const std::string& text) {
  static const std::regex line(
      R"(comply run: (\d+) cycles, (\d+) overruns, .*cycle start lateness p50 \d+ us, p99 \d+ us, max (\d+) us)");
  std::smatch match;
  Summary summary;
  if (std::regex_search(text, match, line)) {
    summary = {std::stoull(match[1]), std::stoull(match[2]), std::stol(match[3])};
  }
  return summary;
}

/// Every cycle record's compute time and start lateness [s], in order.
std::vector<std::pair<double, double>> recordedTimings(const std::string& path) {
  std::map<std::uint16_t, std::string> topics;
  for (const auto& channel : record::readMcap(path).channels) {
    topics[channel.id] = channel.topic;
  }
  std::vector<std::pair<double, double>> timings;
  record::readMcap(path, [&](const record::McapMessageView& message) {
    if (!topics.at(message.channel_id).ends_with("/cycle")) {
      return;
    }
    transport::cdr::Reader reader(message.data);
    transport::ControllerStateMessage state;
    transport::cdr::getFields(reader, state);  // CycleRecord: the state, then the two times
    const auto compute_s = reader.get<double>();
    const auto lateness_s = reader.get<double>();
    EXPECT_TRUE(reader.ok());
    timings.emplace_back(compute_s, lateness_s);
  });
  return timings;
}

TEST(LiveTiming, AStallOfTheSimulatedArmIsInTheSummaryAsInTheRecording) {
  host::registerHardware("stalling_sim", stallingSimulation);
  host::LiveHostOptions options;
  options.config_file = kHostConfig;
  options.robot = "fr3";
  options.hardware = "stalling_sim";
  options.transport = "in_process";
  options.name = "stall";
  options.priority = 0;
  options.duration_s = 0.6;
  options.record_path = scratchFile("stall.mcap");
  const pipeline::WrapperConfig config =
      host::simControllerConfig(options.robot, "", options.config_file);
  const std::atomic<bool> stop{false};
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(host::runLiveHost(options, config, stop, out, err), 0) << err.str();

  const auto timings = recordedTimings(options.record_path);
  ASSERT_EQ(timings.size(), 600U) << "a cycle record for every cycle";
  double max_lateness_s = 0.0;
  std::uint64_t overruns = 0;
  for (const auto& [compute_s, lateness_s] : timings) {
    max_lateness_s = std::max(max_lateness_s, lateness_s);
    overruns += std::max(lateness_s, 0.0) + compute_s > kPeriodS ? 1 : 0;
  }
  // The stalled cycle computed 15 ms or more; the next began 14 ms or more after it was due (a
  // sleep never returns early), and the plant's paced clock did not hide it.
  EXPECT_GE(max_lateness_s, 0.014);
  EXPECT_GE(overruns, 2U);
  const Summary summary = summaryOf(out.str());
  EXPECT_EQ(summary.cycles, timings.size()) << out.str();
  EXPECT_EQ(summary.overruns, overruns) << out.str();
  EXPECT_EQ(summary.max_lateness_us, std::lround(max_lateness_s * 1e6)) << out.str();
}

}  // namespace
}  // namespace comply::live_test
