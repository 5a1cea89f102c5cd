// A simulated run: the MuJoCo plant as the hardware, its time as the clock, the library's control
// loop, and an observer that streams the task's commands and records every cycle.

#include "comply/host/sim_session.hpp"

#include <chrono>
#include <iomanip>
#include <memory>
#include <sstream>

#include "comply/core/output_folder.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/live_view.hpp"
#include "comply/host/task_source.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "progress_bar.hpp"
#include "sim_crash_guard.hpp"
#include "sim_pictures.hpp"
#include "sim_view.hpp"

namespace comply::host {
namespace {

using WallClock = std::chrono::steady_clock;

sim::PlantOptions plantOptions(const SimRunOptions& options,
                               const pipeline::ResolvedController& resolved) {
  sim::PlantOptions plant;
  plant.actuation = resolved.parameters.output.mode;  // the drives the controller drives
  plant.substeps = options.task.substeps;
  plant.seed = options.task.seed;
  plant.scene = options.task.scene;
  plant.scene.offscreen_width = std::max(options.image_width, 1280);
  plant.scene.offscreen_height = std::max(options.image_height, 960);
  plant.tip_frame = resolved.config.tip_frame;
  plant.joint_dynamics = options.plant_joint_dynamics;
  plant.friction_scale = options.plant_friction_scale;
  plant.link_side_torque = options.plant_link_side_torque;
  return plant;
}

/// The host's side of each cycle: before it, the source's command is submitted (and snapshots,
/// the view and the progress bar follow the plant); after it, the cycle is logged.
template <typename Command>
class SimRecorder final : public hardware::LoopObserver {
 public:
  SimRecorder(const SimRunOptions& options, pipeline::Wrapper<Command>& wrapper,
              task::CommandSource<Command>& source, sim::SimulatedRobot& plant,
              SimPictures& pictures, ProgressBar& progress, SimResult& result)
      : options_(options),
        wrapper_(wrapper),
        source_(source),
        plant_(plant),
        pictures_(pictures),
        progress_(progress),
        result_(result) {}

  void setLoop(hardware::ControlLoop* loop, std::uint64_t cycles, std::uint64_t snapshot_every) {
    loop_ = loop;
    cycles_ = cycles;
    snapshot_every_ = snapshot_every;
  }
  void setGuard(CrashGuard* guard) { guard_ = guard; }
  /// Every cycle, command and outcome is recorded there, stamped with the simulated time.
  /// And shown there (`--foxglove`); either may be null.
  void setRecording(HostRecording* recording, LiveView* view, const std::string& base_frame) {
    recording_ = recording;
    view_ = view;
    base_frame_ = base_frame;
    if (recording != nullptr || view != nullptr) {
      sampler_.emplace(wrapper_);
    }
  }

  void beforeCycle(std::uint64_t index, double t) override {
    if (guard_ != nullptr) {
      guard_->cycle(index);
    }
    if (snapshot_every_ != 0 && index > 0 && index % snapshot_every_ == 0 && index < cycles_) {
      std::ostringstream name;
      name << "snapshot_" << std::setw(6) << std::setfill('0') << std::llround(t * 1000.0) << "ms";
      pictures_.snapshot(plant_, name.str());
    }
    if (!pictures_.show(plant_, t)) {
      loop_->stop();  // the user closed the window
    }
    progress_.update(t, std::chrono::duration<double>(WallClock::now() - wall_start_).count());
    if (std::optional<Command> command = source_.next(t, wrapper_.measuredPose())) {
      submit(*command, t);
    }
  }

  void afterCycle(const hardware::CycleRecord& record) override {
    if (sampler_ && record.state != nullptr) {
      sampler_->fill(record, *record.state, transport::Stamp::fromSeconds(record.time_s), sample_);
      forwardCycle(recording_, view_, sample_, wrapper_, record);
    }
    SimLog& log = result_.log;
    SimSummary& summary = result_.summary;
    const Eigen::Map<const Eigen::VectorXd> torque(record.torque.data(),
                                                   static_cast<Eigen::Index>(record.torque.size()));
    log.time_s.push_back(record.time_s);
    log.position.push_back(record.state->position);
    log.velocity.push_back(record.state->velocity);
    log.torque.push_back(torque);
    const Eigen::Isometry3d tcp = plant_.tcpPose();
    log.tcp_position.push_back(tcp.translation());
    log.tcp_orientation.push_back(Eigen::Quaterniond(tcp.linear()));
    log.contact_wrench.push_back(plant_.toolContactWrench());
    const pipeline::Controller& controller = wrapper_.controller();
    if (controller.observer().enabled()) {
      log.estimated_wrench.push_back(controller.observer().wrench());
    }
    if (record.command != nullptr && record.command->mode != OutputMode::kTorque) {
      log.position_command.push_back(record.command->position);
      if (isAdmittance(record.command->mode)) {
        log.sensor_wrench.push_back(controller.sensorWrenchValid() ? controller.sensorWrench()
                                                                   : Vector6d::Zero());
      }
    }
    log.passivity.push_back(wrapper_.controller().diagnostics().passivity());
    log.cycle_cost_us.push_back(record.controller_s * 1e6);
    const Command in_force = wrapper_.lastAccepted();
    if constexpr (std::is_same_v<Command, CartesianCommand>) {
      log.reference_position.push_back(in_force.position);
      log.reference_orientation.push_back(in_force.orientation);
    } else {
      log.joint_reference.push_back(in_force.position);
    }
    trackSaturation(torque, record.period_s, summary);
    summary.overruns += record.controller_s > record.period_s ? 1 : 0;
    if (guard_ != nullptr) {
      std::ostringstream row;
      if (log.size() == 1) {
        writeLogHeader(log, row);  // the first row says whether the tank's columns are there
      }
      writeLogRow(log, log.size() - 1, row);
      guard_->append(row.str());
      if (record.index % 1000 == 999) {  // every simulated second at 1 kHz
        guard_->flush();
      }
    }
    for (Eigen::Index j = 0; j < torque.size(); ++j) {
      if (std::abs(torque[j]) > summary.max_torque_nm) {
        summary.max_torque_nm = std::abs(torque[j]);
        summary.max_torque_joint = static_cast<int>(j);
      }
      if (record.index > 0) {
        const double rate = std::abs(torque[j] - log.torque[log.size() - 2][j]) / record.period_s;
        summary.max_torque_rate_nm_per_s = std::max(summary.max_torque_rate_nm_per_s, rate);
      }
    }
  }

  [[nodiscard]] double wallSeconds() const {
    return std::chrono::duration<double>(WallClock::now() - wall_start_).count();
  }

 private:
  // A joint whose torque sits at its effort limit (within rounding) this cycle.
  void trackSaturation(const Eigen::Map<const Eigen::VectorXd>& torque, double period_s,
                       SimSummary& summary) {
    const JointVector& limit = wrapper_.controller().effortLimit();
    int saturated = -1;
    for (Eigen::Index j = 0; j < torque.size() && j < limit.size(); ++j) {
      if (std::abs(torque[j]) >= limit[j] * (1.0 - 1e-9)) {
        saturated = static_cast<int>(j);
      }
    }
    saturation_s_ = saturated >= 0 ? saturation_s_ + period_s : 0.0;
    if (saturation_s_ > summary.longest_saturation_s) {
      summary.longest_saturation_s = saturation_s_;
      summary.saturated_joint = saturated;
    }
  }

  /// The command as it would have come over the wire, and its outcome.
  void record(const Command& command, const pipeline::Verdict& verdict, double t) {
    const transport::Stamp now = transport::Stamp::fromSeconds(t);
    const transport::Header header{transport::Stamp::fromSeconds(command.stamp_s), base_frame_};
    transport::CommandOutcomeMessage outcome;
    outcome.stamp = header.stamp;
    outcome.received = now;
    const transport::CommandMessageOf<Command> message{header, command};
    if (recording_ != nullptr) {
      recording_->received(message, now);
    }
    if (view_ != nullptr) {
      view_->received(message, now);
    }
    outcome.command_kind = std::is_same_v<Command, CartesianCommand>
                               ? transport::WireCommandKind::kCartesian
                               : transport::WireCommandKind::kJoint;
    if (verdict.accepted) {
      // Submitted before the cycle that takes it: that cycle is the next one.
      outcome.outcome = transport::Outcome::kApplied;
      outcome.cycle = static_cast<std::uint64_t>(result_.log.size());
      outcome.applied = now;
    } else {
      outcome.outcome = transport::Outcome::kRejected;
      outcome.reason = static_cast<transport::Reason>(verdict.reason);
      outcome.message = verdict.message;
    }
    if (recording_ != nullptr) {
      recording_->outcome(outcome);
    }
    if (view_ != nullptr) {
      view_->outcome(outcome);
    }
  }

  void submit(Command command, double t) {
    const pipeline::Verdict verdict = wrapper_.submit(command);
    if (recording_ != nullptr || view_ != nullptr) {
      record(command, verdict, t);
    }
    ++result_.summary.commands_sent;
    result_.summary.last_command_rejected = !verdict.accepted;
    result_.summary.last_rejection = verdict.message;
    if (!verdict.accepted) {
      std::ostringstream message;
      message << "t = " << std::fixed << std::setprecision(3) << t
              << " s: command rejected: " << verdict.message;
      addMessage(result_.summary, message.str(), options_.progress);
    }
  }

  const SimRunOptions& options_;
  pipeline::Wrapper<Command>& wrapper_;
  task::CommandSource<Command>& source_;
  sim::SimulatedRobot& plant_;
  SimPictures& pictures_;
  ProgressBar& progress_;
  SimResult& result_;
  hardware::ControlLoop* loop_ = nullptr;
  std::uint64_t cycles_ = 0;
  std::uint64_t snapshot_every_ = 0;
  double saturation_s_ = 0.0;
  CrashGuard* guard_ = nullptr;
  WallClock::time_point wall_start_ = WallClock::now();
  HostRecording* recording_ = nullptr;
  LiveView* view_ = nullptr;
  std::string base_frame_;
  std::optional<StateSampler<Command>> sampler_;
  StateSample sample_;  // the loop thread's scratch
};

// Wall time a single cycle may take before the run is declared hung (a plugin in an endless
// loop): far above any real cycle, rendering included.
constexpr double kStepTimeoutS = 10.0;

std::uint64_t cyclesIn(double seconds, double period_s) {
  return static_cast<std::uint64_t>(std::llround(seconds / period_s));
}

/// Runs the loop under a crash guard: log.csv is streamed while the loop runs, and a crashing or
/// hanging plugin is named.
template <typename Command>
void runGuarded(const SimRunOptions& options, const pipeline::ResolvedController& resolved,
                SimRecorder<Command>& recorder, hardware::ControlLoop& loop, SimResult& result) {
  CrashGuard guard(resolved.plugin->path().string(),
                   options.out_dir.empty() ? std::filesystem::path() : options.out_dir / "log.csv",
                   kStepTimeoutS);
  recorder.setGuard(&guard);  // it writes the header with the first row
  loop.run();
  recorder.setGuard(nullptr);
  if (result.log.size() == 0) {  // no cycle ran: the header alone
    std::ostringstream header;
    writeLogHeader(result.log, header);
    guard.append(header.str());
  }
  guard.flush();
  if (const std::string error = guard.writeError(); !error.empty()) {
    addMessage(result.summary, "log.csv is incomplete: writing it failed (" + error + ")",
               options.progress);
  }
}

void summarizeDiagnostics(const pipeline::DiagnosticsSnapshot& diagnostics, SimSummary& summary) {
  summary.rejections = diagnostics.rejectionsTotal();
  summary.rate_limit_hits = diagnostics.rate_limit_hits;
  summary.effort_limit_hits = diagnostics.effort_limit_hits;
  summary.governor_hits = diagnostics.governor_hits;
  summary.wall_reference_hits = diagnostics.wall_reference_hits;
  summary.wall_brake_hits = diagnostics.wall_brake_hits;
  summary.contact_speed_hits = diagnostics.contact_speed_hits;
  summary.faults = diagnostics.faults;
  if (diagnostics.faults > 0) {
    summary.fault_reason = diagnostics.last_fault;
  }
}

template <typename Command>
SimResult runWith(const SimRunOptions& options,
                  const std::shared_ptr<const pipeline::ResolvedController>& resolved) {
  SimResult result;
  SimSummary& summary = result.summary;
  summary.robot = resolved->robot.name;
  summary.plugin = resolved->config.plugin;
  summary.output_mode = resolved->parameters.output.mode;
  for (const std::string& warning : resolved->warnings) {
    addMessage(summary, warning, options.progress);
  }
  sim::SimulatedRobot plant(resolved->robot, plantOptions(options, *resolved));
  pipeline::Wrapper<Command> wrapper(resolved);
  const int dof = wrapper.dof();
  summary.dof = result.log.dof = dof;
  summary.cartesian = result.log.cartesian = resolved->cartesian();

  const double period_s = plant.controlPeriod();
  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  TaskSource<Command> task_source(options.task, wrapper.lastAccepted(), dof, period_s);
  // An experiment's own stream replaces the task's, at the task's command rate.
  std::optional<task::PacedSource<Command>> paced;
  task::CommandSource<Command>* source = &task_source;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    if (options.cartesian_source) {
      source = &paced.emplace(*options.cartesian_source, commandPeriodOf(options.task, period_s),
                              period_s);
    }
  }

  const double duration_s = options.duration_s > 0.0 ? options.duration_s : options.task.duration_s;
  const std::uint64_t cycles = cyclesIn(duration_s, period_s);
  SimPictures pictures(options, plant, summary);
  pictures.snapshot(plant, "start");
  ProgressBar progress(options.progress, "sim " + resolved->robot.name, duration_s);
  sim::SimulatedClock clock(plant, options.realtime || options.view);
  hardware::ControlLoop loop(plant, wrapper, clock, {.period_s = period_s, .cycles = cycles});
  SimRecorder<Command> recorder(options, wrapper, *source, plant, pictures, progress, result);
  recorder.setLoop(
      &loop, cycles,
      options.task.snapshot_every_ms > 0.0
          ? std::max<std::uint64_t>(1, cyclesIn(options.task.snapshot_every_ms * 1e-3, period_s))
          : 0);
  loop.setObserver(&recorder);
  std::unique_ptr<HostRecording> recording;
  if (!options.record_path.empty()) {
    // Simulated time has no deadline: a busy disk slows the run instead of thinning the file.
    recording = std::make_unique<HostRecording>(
        options.record_path.string(), resolved, "comply",
        record::StringMap{{"host", "comply sim"}, {"clock", "simulated"}},
        HostRecordingOptions{.when_full = record::WhenFull::kWait});
  }
  const SimView view = openView(options, resolved, clock);
  recorder.setRecording(recording.get(), view.get(), resolved->robot.base_frame);
  runGuarded(options, *resolved, recorder, loop, result);
  clock.waitUntil(loop.nextCycleTime());  // the plant carries out the last torque written
  progress.finish();
  summary.wall_s = recorder.wallSeconds();
  summary.simulated_s = plant.simTime();
  pictures.snapshot(plant, "end");
  if (recording != nullptr) {
    recording->stop();
    const record::RecorderStats stats = recording->stats();
    summary.recording = RecordingSummary{options.record_path, stats.written,      stats.dropped,
                                         stats.bytes,         stats.writer_cpu_s, stats.error};
  }

  summarizeDiagnostics(wrapper.diagnostics(), summary);
  summarizeLog(result.log, task_source.motionEndTime(), summary);
  if (!result.log.cycle_cost_us.empty()) {
    summary.cycle_cost = summarize(result.log.cycle_cost_us);
  }
  return result;
}

}  // namespace

SimResult runSimulation(const SimRunOptions& options) {
  // Both refused before anything runs, rather than at the end of a long run.
  if (!options.record_path.empty()) {
    record::checkRecordingFolder(options.record_path.string());
  }
  const auto resolved =
      options.resolved ? options.resolved : pipeline::resolveController(options.config);
  if (!options.out_dir.empty()) {
    makeOutputFolder(options.out_dir);  // its parent must exist
  }
  SimResult result = resolved->cartesian() ? runWith<CartesianCommand>(options, resolved)
                                           : runWith<JointCommand>(options, resolved);
  if (!options.out_dir.empty()) {
    result.summary.files.push_back(options.out_dir / "log.csv");  // streamed by the run
  }
  return result;
}

}  // namespace comply::host
