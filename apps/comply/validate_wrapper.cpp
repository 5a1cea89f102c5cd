#include "validate_wrapper.hpp"

#include <algorithm>

#include "comply/hardware/control_loop.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/wrapper.hpp"

namespace comply::app {
namespace {

using nlohmann::json;

/// The samples as the measurements of a robot, one per cycle.
class SampleHardware final : public hardware::HardwareInterface {
 public:
  explicit SampleHardware(const std::vector<ValidateSample>& samples) : samples_(samples) {}
  [[nodiscard]] int dof() const noexcept override {
    return static_cast<int>(samples_.front().state.position.size());
  }
  bool read(JointState& state) noexcept override {
    state = samples_[std::min(next_++, samples_.size() - 1)].state;
    return true;
  }
  bool write(std::span<const double> /*torque*/) noexcept override { return true; }

 private:
  const std::vector<ValidateSample>& samples_;
  std::size_t next_ = 0;
};

/// Submits each sample's command before its cycle and records what the cycle did.
template <typename Command>
class SampleRecorder final : public hardware::LoopObserver {
 public:
  SampleRecorder(pipeline::Wrapper<Command>& wrapper, const std::vector<ValidateSample>& samples,
                 const std::string& inputs_path, json& outputs)
      : wrapper_(wrapper), samples_(samples), inputs_path_(inputs_path), outputs_(outputs) {}

  void beforeCycle(std::uint64_t index, double time_s) override {
    const json& command = samples_[index].command;
    if (command.empty()) {
      return;
    }
    const std::string where = inputs_path_ + ": sample " + std::to_string(index);
    Command incoming = parseSampleCommand(command, wrapper_.dof(), wrapper_.lastAccepted(), where);
    if (!command.contains("stamp")) {
      incoming.stamp_s = time_s;
    }
    const pipeline::Verdict verdict = wrapper_.submit(incoming);
    if (!verdict.accepted) {
      outputs_[index]["wrapper_rejected"] = verdict.message;
    }
  }

  void afterCycle(const hardware::CycleRecord& record) override {
    json& out = outputs_[record.index];
    out["wrapper_torque"] = std::vector<double>(record.torque.begin(), record.torque.end());
    const bool fault = wrapper_.diagnostics().state == pipeline::WrapperState::kFault;
    out["wrapper_state"] = fault ? "fault" : "ok";
  }

 private:
  pipeline::Wrapper<Command>& wrapper_;
  const std::vector<ValidateSample>& samples_;
  const std::string& inputs_path_;
  json& outputs_;
};

template <typename Command>
void runWrapperAs(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                  const std::vector<ValidateSample>& samples, double period_s,
                  const std::string& inputs_path, json& outputs) {
  pipeline::Wrapper<Command> wrapper(resolved);
  const int dof = wrapper.dof();
  JointState first = samples.front().state;
  if (!samples.front().has_effort) {
    // Without a measured effort, start as a robot holding itself still would: at gravity.
    model::Data data(*resolved->model);
    model::update(*resolved->model, data, std::span<const double>(first.position.data(), dof),
                  std::span<const double>(first.velocity.data(), dof), model::Quantity::kGravity);
    first.effort = data.gravity;
  }
  wrapper.activate(first);
  SampleHardware hardware(samples);
  hardware::FreeRunningClock clock;
  hardware::ControlLoop loop(hardware, wrapper, clock,
                             {.period_s = period_s, .cycles = samples.size()});
  SampleRecorder<Command> recorder(wrapper, samples, inputs_path, outputs);
  loop.setObserver(&recorder);
  loop.run();
}

}  // namespace

void runWrapper(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                const std::vector<ValidateSample>& samples, double period_s,
                const std::string& inputs_path, json& outputs) {
  if (resolved->cartesian()) {
    runWrapperAs<CartesianCommand>(resolved, samples, period_s, inputs_path, outputs);
  } else {
    runWrapperAs<JointCommand>(resolved, samples, period_s, inputs_path, outputs);
  }
}

}  // namespace comply::app
