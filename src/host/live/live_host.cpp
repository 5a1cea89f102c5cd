// The control, reader and publisher threads of `comply run`.

#include "comply/host/live_host.hpp"

#include <pthread.h>
#include <sched.h>

#include <cmath>
#include <cstring>
#include <iomanip>
#include <ostream>
#include <thread>

#include "comply/hardware/control_loop.hpp"
#include "comply/sim/simulated_clock.hpp"
#include "comply/transport/endpoints.hpp"
#include "live_intake.hpp"
#include "live_messages.hpp"
#include "live_observer.hpp"

namespace comply::host {
namespace {

using Clock = std::chrono::steady_clock;

/// The DDS side of the host: the endpoints on one participant.
struct HostEndpoints {
  // Every command kept until the reader thread takes it: a burst that arrives while the thread is
  // descheduled, or faster than it validates, waits here (and holds a reliable writer back)
  // instead of being dropped unaccounted.
  static constexpr int kCommandDepth = transport::kKeepAll;
  explicit HostEndpoints(const LiveHostOptions& options)
      : participant(
            {options.domain_id,
             options.network == "all" ? transport::Network::kAll : transport::Network::kLoopback,
             options.priority > 1 ? options.priority - 1 : 0}),
        cartesian(participant, options.name, kCommandDepth),
        joint(participant, options.name, kCommandDepth),
        request(participant, options.name),
        state(participant, options.name),
        diagnostics(participant, options.name),
        waitset(participant) {
    waitset.attach(cartesian);
    waitset.attach(joint);
    waitset.attach(request);
  }
  transport::Participant participant;
  transport::Reader<transport::CartesianCommandMessage> cartesian;
  transport::Reader<transport::JointCommandMessage> joint;
  transport::Reader<transport::RequestMessage> request;
  transport::Writer<transport::ControllerStateMessage> state;
  transport::Writer<transport::DiagnosticsMessage> diagnostics;
  transport::WaitSet waitset;
};

template <typename Command>
void readerThread(HostEndpoints& dds, Intake<Command>& intake, const std::atomic<bool>& running) {
  std::vector<transport::Sample<transport::CartesianCommandMessage>> cartesian;
  std::vector<transport::Sample<transport::JointCommandMessage>> joint;
  std::vector<transport::Sample<transport::RequestMessage>> requests;
  while (running.load()) {
    dds.waitset.wait(0.1);
    cartesian.clear();
    joint.clear();
    requests.clear();
    dds.cartesian.take(cartesian);
    dds.joint.take(joint);
    dds.request.take(requests);
    for (const auto& sample : cartesian) {
      intake.handle(sample);
    }
    for (const auto& sample : joint) {
      intake.handle(sample);
    }
    for (const auto& sample : requests) {
      intake.handle(sample);
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
  Accounting& accounting;
  PublisherLock& lock;
  HostEndpoints& dds;
  double period_s;
};

template <typename Command>
void publishDiagnostics(PublisherContext<Command>& c,
                        std::vector<transport::CommandOutcomeMessage> outcomes) {
  transport::DiagnosticsMessage message = diagnosticsMessage(
      c.wrapper.diagnostics(), c.observer.counters(), c.period_s, c.accounting.counts(),
      c.lock.holder(), c.options.name, std::move(outcomes));
  for (auto it = message.outcomes.rbegin(); it != message.outcomes.rend(); ++it) {
    if (it->outcome == transport::Outcome::kRejected) {
      message.last_rejection = it->message;  // the host's reasons too, not only the wrapper's
      break;
    }
  }
  c.dds.diagnostics.write(message);
}

template <typename Command>
void publisherThread(PublisherContext<Command> c, const std::atomic<bool>& running) {
  const auto state_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / c.options.state_rate_hz));
  auto next_state = Clock::now();
  auto last_diagnostics = Clock::now() - std::chrono::seconds(1);
  std::uint64_t events_seen = 0;
  while (running.load()) {
    AppliedEvent event;
    while (c.observer.takeApplied(event)) {
      c.accounting.settle(event);
    }
    const auto now = Clock::now();
    if (now >= next_state) {
      StateSample sample;
      if (c.observer.takeState(sample)) {
        c.dds.state.write(stateMessage(sample, c.resolved));
      }
      next_state = std::max(next_state + state_period, now);
    }
    if (now - last_diagnostics >= std::chrono::milliseconds(10)) {
      // A watchdog timeout, a fault or a state change goes out at once, not with the heartbeat.
      const pipeline::Diagnostics& d = c.wrapper.controller().diagnostics();
      const std::uint64_t events = d.watchdog_timeouts.load() + d.faults.load() +
                                   (static_cast<std::uint64_t>(d.state.load()) << 32);
      auto outcomes = c.accounting.takeOutcomes();
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

void printSummary(const LoopCounters& counters, const AccountingCounts& counts, std::ostream& out) {
  const auto us = [](double seconds) { return std::lround(seconds * 1e6); };
  out << "comply run: " << counters.cycles.load() << " cycles, " << counters.overruns.load()
      << " overruns; cycle start lateness p50 " << us(histogramQuantile(counters.lateness, 0.5))
      << " us, p99 " << us(histogramQuantile(counters.lateness, 0.99)) << " us; compute p50 "
      << us(histogramQuantile(counters.compute, 0.5)) << " us, p99 "
      << us(histogramQuantile(counters.compute, 0.99)) << " us (10 us bins)\n"
      << "comply run: commands received " << counts.received << ", applied " << counts.applied
      << ", rejected " << counts.rejected << "\n";
}

template <typename Command>
int runWith(const LiveHostOptions& options,
            const std::shared_ptr<const pipeline::ResolvedController>& resolved,
            const std::atomic<bool>& stop, std::ostream& out, std::ostream& err) {
  sim::PlantOptions plant_options;
  plant_options.control_period_s = 1.0 / options.rate_hz;
  plant_options.tip_frame = resolved->config.tip_frame;
  sim::SimulatedRobot plant(resolved->robot, plant_options);
  pipeline::Wrapper<Command> wrapper(resolved);
  JointState state = JointState::zero(wrapper.dof());
  plant.read(state);
  wrapper.activate(state);
  HostEndpoints dds(options);

  const double period_s = plant.controlPeriod();
  sim::SimulatedClock clock(plant, true);
  LiveObserver<Command> observer(wrapper, &plant, hardware::monotonicSeconds());
  const auto cycles = static_cast<std::uint64_t>(std::llround(options.duration_s / period_s));
  hardware::ControlLoop loop(plant, wrapper, clock, {.period_s = period_s, .cycles = cycles});
  loop.setObserver(&observer);
  Accounting accounting;
  PublisherLock lock(resolved->config.command_timeout_s);
  Intake<Command> intake(wrapper, observer, accounting, lock);

  std::atomic<bool> loop_running{true};
  std::atomic<bool> io_running{true};
  std::thread control([&] {
    if (const std::string why = makeRealtime(options.priority); !why.empty()) {
      err << "comply run: warning: " << why << "\n";
    }
    loop.run();
    loop_running = false;
  });
  std::thread reader([&] {
    // Just below the control thread: a command waits for the reader, not for the scheduler.
    makeRealtime(options.priority > 1 ? options.priority - 1 : 0);
    readerThread(dds, intake, io_running);
  });
  PublisherContext<Command> context{options,    *resolved, wrapper, observer,
                                    accounting, lock,      dds,     period_s};
  std::thread publisher([&] { publisherThread(context, io_running); });
  out << "comply run: " << resolved->robot.name << " with " << resolved->config.plugin << " at "
      << options.rate_hz << " Hz; topics rt/" << options.name << "/* on domain "
      << options.domain_id << " (" << options.network << "); Ctrl-C to stop" << std::endl;

  while (!stop.load() && loop_running.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Shutdown: no new commands, then the loop stops and the controller lets go; every command
  // taken is accounted before the last diagnostics go out.
  io_running = false;
  dds.waitset.trigger();
  reader.join();
  loop.stop();
  control.join();
  wrapper.deactivate();
  publisher.join();
  AppliedEvent event;
  while (observer.takeApplied(event)) {
    accounting.settle(event);
  }
  accounting.abandonPending("the host shut down before a cycle took it");
  publishDiagnostics(context, accounting.takeOutcomes());
  dds.diagnostics.flush(1.0);
  printSummary(observer.counters(), accounting.counts(), out);
  return 0;
}

}  // namespace

std::string makeRealtime(int priority) {
  if (priority <= 0) {
    return {};
  }
  sched_param parameters{};
  parameters.sched_priority = priority;
  const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &parameters);
  if (error != 0) {
    return std::string("no SCHED_FIFO for the control thread (") + std::strerror(error) +
           "): it runs at normal priority and its timing will show it; run as root, or grant "
           "rtprio in /etc/security/limits.conf (or CAP_SYS_NICE)";
  }
  return {};
}

int runLiveHost(const LiveHostOptions& options,
                const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                const std::atomic<bool>& stop, std::ostream& out, std::ostream& err) {
  return resolved->cartesian() ? runWith<CartesianCommand>(options, resolved, stop, out, err)
                               : runWith<JointCommand>(options, resolved, stop, out, err);
}

}  // namespace comply::host
