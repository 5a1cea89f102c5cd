// The emulated UR controller: construction, ports, and the calls from outside its cycle
// (ur_emulator.hpp).

#include "comply/ur_emulator/ur_emulator.hpp"

#include <algorithm>
#include <cmath>

#include "comply/core/realtime_scheduling.hpp"
#include "emulator_impl.hpp"

namespace comply::ur {
namespace {

RtdeServerOptions rtdeOptions(const UrEmulatorOptions& options) {
  RtdeServerOptions rtde;
  rtde.address = options.address;
  rtde.port = options.rtde_port;
  rtde.version = options.version;
  rtde.max_frequency_hz = 1.0 / options.period_s;
  rtde.thread_priority = options.priority;
  return rtde;
}

}  // namespace

UrEmulator::Impl::Impl(const UrEmulatorOptions& options)
    : options_(options),
      robot_(model::loadRobotDescription(options.robot)),
      rtde_(rtdeOptions(options)) {
  buildPlant(OutputMode::kPosition);
  Vector6d at_rest;
  if (plant_->readWrench(at_rest)) {
    wrench_tare_ = at_rest;
  }
  script_port_ = std::make_unique<TextPort>(
      options.address, options.script_port, "the emulated secondary interface",
      [this](TextConnection& connection) { runScript(connection.readAll(1.0)); });
  dashboard_port_ = std::make_unique<TextPort>(
      options.address, options.dashboard_port, "the emulated dashboard server",
      [this](TextConnection& connection) {
        connection.write("Connected: Universal Robots Dashboard Server\n");
        std::string line;
        while (connection.readLine(line)) {
          connection.write(dashboard(line) + "\n");
          if (line == "quit") {
            return;
          }
        }
      });
  cycle_thread_ = std::jthread([this](const std::stop_token& stop) {
    (void)makeThreadRealtime(options_.priority);
    runCycles(stop);
  });
}

UrEmulator::Impl::~Impl() {
  cycle_thread_ = {};
}

void UrEmulator::Impl::buildPlant(OutputMode actuation) {
  sim::PlantOptions plant;
  plant.control_period_s = options_.period_s;
  plant.substeps = std::max(1, static_cast<int>(std::lround(options_.period_s / 0.001)));
  plant.actuation = actuation;
  plant.servo_bandwidth_hz = options_.servo_bandwidth_hz;
  plant.scene = options_.scene;
  JointVector position;
  const bool keep = plant_ != nullptr;
  if (keep) {
    position = measured_.position;
  }
  plant_ = std::make_unique<sim::SimulatedRobot>(robot_, plant);
  if (keep) {
    plant_->setJointPositions({position.data(), static_cast<std::size_t>(position.size())});
  } else {
    std::vector<double> home(robot_.home.begin(), robot_.home.end());
    plant_->setJointPositions(home);
  }
  plant_mode_ = actuation;
  dof_address_.clear();
  const mjModel& model = plant_->mujocoModel();
  for (const std::string& joint : robot_.joints) {
    const int id = mj_name2id(&model, mjOBJ_JOINT, joint.c_str());
    dof_address_.push_back(id >= 0 ? model.jnt_dofadr[id] : 0);
  }
  measured_ = JointState::zero(plant_->dof());
  plant_->read(measured_);
}

void UrEmulator::Impl::protectiveStop() {
  const std::lock_guard lock(mutex_);
  protectiveStopLocked();
}

void UrEmulator::Impl::protectiveStopLocked() {
  if (safety_mode_ == 3) {
    return;
  }
  safety_mode_ = 3;
  stopped_at_s_ = static_cast<double>(cycle_) * options_.period_s;
  ++stats_.protective_stops;
  if (running_) {
    stopProgram(program_flag_);  // the program ends; its registers keep what they said
  }
}

void UrEmulator::Impl::dropPackages(int cycles) {
  const std::lock_guard lock(mutex_);
  drop_ += std::max(0, cycles);
}

void UrEmulator::Impl::runScript(const std::string& script) {
  const std::lock_guard lock(mutex_);
  try {
    pending_ = readControlProgram(script);
    stats_.last_program_error.clear();
  } catch (const ControlProgramError& error) {
    stats_.last_program_error = error.what();
  }
}

UrEmulatorStats UrEmulator::Impl::stats() const {
  const std::lock_guard lock(mutex_);
  return stats_;
}

UrEmulatorState UrEmulator::Impl::state() const {
  const std::lock_guard lock(mutex_);
  UrEmulatorState state;
  state.safety_mode = safety_mode_;
  state.program_running = running_;
  state.program_mode = program_.mode;
  state.position = measured_.position;
  state.tcp = plant_->tcpPose();
  state.contact_wrench = plant_->toolContactWrench();
  state.time_s = static_cast<double>(cycle_) * options_.period_s;
  return state;
}

void UrEmulator::Impl::withPlant(const std::function<void(sim::SimulatedRobot&)>& edit) {
  const std::lock_guard lock(mutex_);
  edit(*plant_);
}

UrEmulator::UrEmulator(const UrEmulatorOptions& options) : impl_(std::make_unique<Impl>(options)) {}
UrEmulator::~UrEmulator() = default;
std::uint16_t UrEmulator::rtdePort() const noexcept {
  return impl_->rtdePort();
}
std::uint16_t UrEmulator::scriptPort() const noexcept {
  return impl_->scriptPort();
}
std::uint16_t UrEmulator::dashboardPort() const noexcept {
  return impl_->dashboardPort();
}
void UrEmulator::protectiveStop() {
  impl_->protectiveStop();
}
void UrEmulator::dropPackages(int cycles) {
  impl_->dropPackages(cycles);
}
void UrEmulator::closeConnections() {
  impl_->closeConnections();
}
void UrEmulator::runScript(const std::string& script) {
  impl_->runScript(script);
}
std::string UrEmulator::dashboard(const std::string& command) {
  return impl_->dashboard(command);
}
UrEmulatorStats UrEmulator::stats() const {
  return impl_->stats();
}
UrEmulatorState UrEmulator::state() const {
  return impl_->state();
}
void UrEmulator::withPlant(const std::function<void(sim::SimulatedRobot&)>& edit) {
  impl_->withPlant(edit);
}

}  // namespace comply::ur
