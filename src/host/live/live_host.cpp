// The control, reader and publisher threads of `comply run`.

#include "comply/host/live_host.hpp"

#include <cmath>
#include <iomanip>
#include <mutex>
#include <ostream>
#include <sstream>
#include <thread>

#include "comply/core/clock.hpp"
#include "comply/core/realtime_scheduling.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/host/committed_answers.hpp"
#include "comply/host/diagnostics_message.hpp"
#include "comply/host/hardware_backends.hpp"
#include "comply/host/live_view.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/transport/host_transport.hpp"
#include "live_intake.hpp"
#include "live_observer.hpp"
#include "realtime_grant.hpp"

namespace comply::host {
namespace {

using Clock = std::chrono::steady_clock;

/// Takes what arrives: commands and requests into the intake, then answers the committed
/// requests (after the commands of the same receive: an answer includes a chunk taken with it).
template <typename Command>
void readerThread(transport::HostTransport& transport, Intake<Command>& intake,
                  CommittedAnswers<Command>& committed, const std::atomic<bool>& running) {
  transport::Inbox inbox;
  while (running.load()) {
    inbox.clear();
    transport.receive(inbox, 0.1);
    intake.take(inbox);
    for (const auto& request : inbox.committed_requests) {
      transport.publish(committed.answer(request, wallClockNanoseconds()));
    }
  }
}

/// What the publisher thread needs.
template <typename Command>
struct PublisherContext {
  const LiveHostOptions& options;
  const pipeline::ResolvedController& resolved;
  pipeline::Wrapper<Command>& wrapper;
  LiveObserver<Command>& observer;
  pipeline::CommandGate& gate;
  transport::HostTransport& transport;
  double period_s;
  HostRecording* recording;
  LiveView* view;
};

template <typename Command>
void publishDiagnostics(PublisherContext<Command>& c,
                        std::vector<transport::CommandOutcomeMessage> outcomes) {
  transport::DiagnosticsMessage message =
      diagnosticsMessage(c.wrapper.diagnostics(), c.observer.counters(), c.period_s,
                         c.gate.counts(), c.gate.publisher(), c.options.name, std::move(outcomes));
  if (c.recording != nullptr) {
    const record::RecorderStats stats = c.recording->stats();
    message.records_dropped = stats.dropped;
    message.recording = stats.error.empty() ? c.recording->path() : "stopped early: " + stats.error;
    for (const transport::CommandOutcomeMessage& outcome : message.outcomes) {
      c.recording->outcome(outcome);
    }
    c.recording->diagnostics(message);
  }
  if (c.view != nullptr) {
    for (const transport::CommandOutcomeMessage& outcome : message.outcomes) {
      c.view->outcome(outcome);
    }
    c.view->diagnostics(message);
  }
  c.transport.publish(message);
}

template <typename Command>
void publisherThread(PublisherContext<Command> c, const std::atomic<bool>& running) {
  const auto state_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / c.options.state_rate_hz));
  auto next_state = Clock::now();
  auto last_diagnostics = Clock::now() - std::chrono::seconds(1);
  std::uint64_t events_seen = 0;
  while (running.load()) {
    c.observer.settleRequests(c.gate);  // activations, deactivations, resets the cycle decided
    c.gate.settle();
    const auto now = Clock::now();
    if (now >= next_state) {
      StateSample sample;
      if (c.observer.takeState(sample)) {
        c.transport.publish(stateMessage(sample, c.resolved));
      }
      next_state = std::max(next_state + state_period, now);
    }
    if (now - last_diagnostics >= std::chrono::milliseconds(10)) {
      // A watchdog timeout, a fault or a state change goes out at once, not with the heartbeat.
      const pipeline::Diagnostics& d = c.wrapper.controller().diagnostics();
      const std::uint64_t events = d.watchdog_timeouts.load() + d.faults.load() +
                                   (static_cast<std::uint64_t>(d.state.load()) << 32);
      auto outcomes = outcomeMessages(c.gate.takeOutcomes());
      if (!outcomes.empty() || events != events_seen ||
          now - last_diagnostics >= std::chrono::seconds(1)) {
        events_seen = events;
        publishDiagnostics(c, std::move(outcomes));
        last_diagnostics = now;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void printSummary(const LoopCounters& counters, const pipeline::GateCounts& counts,
                  const hardware::LoopStats& stats, const transport::HostTransport& transport,
                  const HardwareBackend& backend, std::ostream& out) {
  const auto us = [](double seconds) { return std::lround(seconds * 1e6); };
  out << "comply run: " << counters.cycles.load() << " cycles, " << counters.overruns.load()
      << " overruns, " << stats.read_failures << " read failures, " << stats.write_failures
      << " write failures; cycle start lateness p50 "
      << us(histogramQuantile(counters.lateness, 0.5)) << " us, p99 "
      << us(histogramQuantile(counters.lateness, 0.99)) << " us, max "
      << us(stats.max_start_lateness_s) << " us; compute p50 "
      << us(histogramQuantile(counters.compute, 0.5)) << " us, p99 "
      << us(histogramQuantile(counters.compute, 0.99)) << " us, max " << us(stats.max_compute_s)
      << " us (10 us bins, max exact)\n"
      << "comply run: commands received " << counts.received << ", applied " << counts.applied
      << ", rejected " << counts.rejected << "; malformed samples dropped by the transport "
      << transport.malformedSamples() << "; transport restarts " << transport.restarts() << "\n";
  if (const std::uint64_t lost = counters.chunk_timings_lost.load(); lost > 0) {
    // Their chunks' outcomes went out without them, and the recording has no row for them.
    out << "comply run: chunk timing records lost (more than the gate's queue held) " << lost
        << "\n";
  }
  if (const std::string driver = backend.hardware->summary(); !driver.empty()) {
    out << "comply run: " << driver << "\n";
  }
}

/// A run that faulted says so, and why it last did (the diagnostics' last_fault).
void printFaults(const pipeline::DiagnosticsSnapshot& diagnostics, std::ostream& out) {
  if (diagnostics.faults > 0) {
    out << "comply run: the controller faulted " << diagnostics.faults << " time"
        << (diagnostics.faults == 1 ? "" : "s") << ", last: " << diagnostics.last_fault << "\n";
  }
}

void printRecording(const HostRecording& recording, std::ostream& out) {
  const record::RecorderStats stats = recording.stats();
  out << "comply run: recorded " << stats.written << " messages to " << recording.path() << " ("
      << std::fixed << std::setprecision(1) << static_cast<double>(stats.bytes) / 1e6
      << " MB), dropped " << stats.dropped << "; writer thread CPU " << std::setprecision(2)
      << stats.writer_cpu_s << " s\n";
  if (!stats.error.empty()) {
    out << "comply run: the recording stopped early: " << stats.error << " (" << stats.lost
        << " records not written)\n";
  }
  out.unsetf(std::ios::floatfield);
}

/// Stops `recording` (nullptr: none) and says what it wrote.
void stopRecording(HostRecording* recording, std::ostream& out) {
  if (recording == nullptr) {
    return;
  }
  recording->stop();
  printRecording(*recording, out);
}

/// Just below `priority`, the control thread's: a command waits for the threads that receive it,
/// not for the scheduler.
int receivePriority(int priority) {
  return priority > 1 ? priority - 1 : 0;
}

std::unique_ptr<transport::HostTransport> openHostTransport(const LiveHostOptions& options,
                                                            int priority) {
  return transport::makeHostTransport(options.transport,
                                      {.name = options.name,
                                       .domain_id = options.domain_id,
                                       .network = options.network,
                                       .receive_priority = receivePriority(priority),
                                       .security = options.security});
}

/// The recording of --record; none without it.
std::unique_ptr<HostRecording> openRecording(
    const LiveHostOptions& options,
    const std::shared_ptr<const pipeline::ResolvedController>& resolved,
    const HardwareBackend& backend) {
  if (options.record_path.empty()) {
    return nullptr;
  }
  return std::make_unique<HostRecording>(
      options.record_path, resolved, options.name,
      record::StringMap{{"host", "comply run"},
                        {"rate_hz", (std::ostringstream() << options.rate_hz).str()},
                        {"hardware", backend.description}},
      // The control thread never waits for the disk: a full lane drops, and counts.
      HostRecordingOptions{.when_full = record::WhenFull::kDrop});
}

/// The live view of --foxglove; none without it.
std::unique_ptr<LiveView> openView(
    const LiveHostOptions& options,
    const std::shared_ptr<const pipeline::ResolvedController>& resolved) {
  if (options.foxglove.empty()) {
    return nullptr;
  }
  return std::make_unique<LiveView>(parseViewAddress(options.foxglove), resolved, options.name);
}

void printView(const LiveView* view, std::ostream& out) {
  if (view != nullptr) {
    out << "comply run: " << describeViewStats(view->stats()) << "\n";
  }
}

template <typename Command>
int runWith(const LiveHostOptions& options,
            const std::shared_ptr<const pipeline::ResolvedController>& resolved,
            HardwareBackend& backend, int priority, const std::atomic<bool>& stop,
            std::ostream& out, std::ostream& err) {
  hardware::HardwareInterface& robot = *backend.hardware;
  pipeline::Wrapper<Command> wrapper(resolved);
  JointState state = JointState::zero(wrapper.dof());
  if (!robot.read(state)) {
    err << "comply run: the hardware gave no valid joint state to start from\n";
    return 1;
  }
  wrapper.activate(state);
  const std::unique_ptr<transport::HostTransport> transport = openHostTransport(options, priority);

  const double period_s = 1.0 / options.rate_hz;
  pipeline::CommandGate gate(pipeline::gateOptions(resolved->config, resolved->cartesian()));
  LiveObserver<Command> observer(wrapper, gate);
  const auto cycles = static_cast<std::uint64_t>(std::llround(options.duration_s / period_s));
  hardware::ControlLoop loop(
      robot, wrapper, *backend.clock,
      {.period_s = period_s, .cycles = cycles, .warm_ahead_s = 1e-6 * options.warm_ahead_us});
  loop.setObserver(&observer);
  Intake<Command> intake(wrapper, observer, gate, &robot);
  CommittedAnswers<Command> committed(wrapper, resolved->robot.base_frame);
  const std::unique_ptr<HostRecording> recording = openRecording(options, resolved, backend);
  if (recording != nullptr) {
    observer.setRecording(recording.get());
    intake.setRecording(recording.get());
  }
  const std::unique_ptr<LiveView> view = openView(options, resolved);
  observer.setView(view.get());
  intake.setView(view.get());

  std::atomic<bool> loop_running{true};
  std::atomic<bool> io_running{true};
  std::thread control([&] {
    if (const std::string why = makeRealtime(priority); !why.empty()) {
      err << "comply run: warning: " << why << "\n";
    }
    loop.run();
    loop_running = false;
  });
  std::thread reader([&] {
    makeThreadRealtime(receivePriority(priority));  // granted: the control thread's is
    readerThread(*transport, intake, committed, io_running);
  });
  PublisherContext<Command> context{options,    *resolved, wrapper,         observer,  gate,
                                    *transport, period_s,  recording.get(), view.get()};
  std::thread publisher([&] { publisherThread(context, io_running); });
  out << "comply run: " << resolved->robot.name << " with " << resolved->config.plugin << " at "
      << options.rate_hz << " Hz on " << backend.description << "; " << transport->describe()
      << "; Ctrl-C to stop" << std::endl;
  if (view != nullptr) {
    out << "comply run: Foxglove live view on " << view->url() << std::endl;
  }

  while (!stop.load() && loop_running.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Shutdown: no new commands, then the loop stops and the controller lets go; every command
  // taken is accounted before the last diagnostics go out.
  io_running = false;
  transport->wake();
  reader.join();
  loop.stop();
  control.join();
  (void)robot.hold();  // now, not after the shutdown: a Franka faults on 20 missed cycles
  wrapper.deactivate();
  publisher.join();
  gate.abandonPending("the host shut down before a cycle took it");
  publishDiagnostics(context, outcomeMessages(gate.takeOutcomes()));
  transport->flush(1.0);
  printSummary(observer.counters(), gate.counts(), loop.stats(), *transport, backend, out);
  printFaults(wrapper.diagnostics(), out);
  stopRecording(recording.get(), out);
  printView(view.get(), out);
  return 0;
}

}  // namespace

std::string makeRealtime(int priority) {
  const std::string refusal = makeThreadRealtime(priority);
  if (refusal.empty()) {
    return {};
  }
  return "no real-time scheduling for the control thread (" + refusal +
         "): it runs at normal priority and its timing will show it; to grant it, " +
         kRealtimeGrantAdvice;
}

int runLiveHost(const LiveHostOptions& options, pipeline::WrapperConfig config,
                const std::atomic<bool>& stop, std::ostream& out, std::ostream& err) {
  static std::once_flag registered;
  std::call_once(registered, registerBuiltinTransports);
  if (!options.record_path.empty()) {
    record::checkRecordingFolder(options.record_path);  // before the hardware is touched
  }
  if (!config.robot_description) {
    pipeline::completeForRobot(config, std::make_shared<const model::RobotDescription>(
                                           model::loadRobotDescription(config.robot)));
  }
  const int priority = grantRealtime(options, err);
  HardwareBackend backend =
      makeHardware(options.hardware, config,
                   backendContext(config, 1.0 / options.rate_hz, options.hardware_options));
  if (backend.hardware->dof() != config.dof) {
    err << "comply run: the hardware has " << backend.hardware->dof() << " joints, the controller "
        << config.dof << "\n";
    return 2;
  }
  // What the robot does is a fact of the hardware, decided before the controller is resolved.
  config.hardware_compensates_gravity = backend.hardware->compensatesGravity();
  if (config.hardware_compensates_gravity) {
    out << "comply run: the hardware compensates gravity itself; comply adds none (nor in the "
           "FAULT hold)"
        << std::endl;
  }
  const std::shared_ptr<const pipeline::ResolvedController> resolved =
      pipeline::resolveController(config);
  for (const std::string& warning : resolved->warnings) {
    out << "comply run: " << warning << std::endl;
  }
  return resolved->cartesian()
             ? runWith<CartesianCommand>(options, resolved, backend, priority, stop, out, err)
             : runWith<JointCommand>(options, resolved, backend, priority, stop, out, err);
}

}  // namespace comply::host
