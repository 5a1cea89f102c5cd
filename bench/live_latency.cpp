// Command latency and loop jitter of `comply run --sim` on loopback (a benchmark, not a test):
// starts a host, streams pose commands at a rate for a while, and prints, over the applied ones,
//   transport  send (the command's stamp) -> the host's reader took it
//   queue      the host's reader took it -> end of the control cycle that applied it
//   total      send -> end of the cycle that applied it
// all from CLOCK_REALTIME on one machine, and the cycle-start lateness of the host's control loop
// over the same span (its diagnostics histogram, 10 us bins).
//
//   build/bench/live_latency [--seconds 10] [--rate 1000] [--priority 80] [--transport dds]

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "comply/host/timing_statistics.hpp"
#include "comply/transport/endpoints.hpp"

namespace {

using namespace comply;
using Clock = std::chrono::steady_clock;

struct Options {
  double seconds = 10.0;
  double rate_hz = 1000.0;
  int priority = 80;
  std::string transport = "dds";  ///< the host's --transport: dds or dds_inline
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const double value = std::atof(argv[i + 1]);
    if (key == "--seconds") {
      options.seconds = value;
    } else if (key == "--rate") {
      options.rate_hz = value;
    } else if (key == "--priority") {
      options.priority = static_cast<int>(value);
    } else if (key == "--transport") {
      options.transport = argv[i + 1];
    }
  }
  return options;
}

pid_t startHost(int domain, const Options& options) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string config =
        std::string(COMPLY_SOURCE_DIR) + "/config/sim/cartesian_impedance.yaml";
    const std::string domain_text = std::to_string(domain);
    const std::string priority = std::to_string(options.priority);
    execl(COMPLY_CLI, COMPLY_CLI, "run", "--config", config.c_str(), "--robot", "fr3", "--sim",
          "--domain", domain_text.c_str(), "--name", "bench", "--priority", priority.c_str(),
          "--transport", options.transport.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

void printRow(const char* name, std::vector<double> samples_us) {
  if (samples_us.empty()) {
    std::printf("%-10s no samples\n", name);
    return;
  }
  const host::TimingSummary s = host::summarize(std::move(samples_us));
  std::printf("%-10s %9.1f %9.1f %9.1f %9.1f %9.1f\n", name, s.mean_us, s.sd_us, s.p50_us, s.p99_us,
              s.max_us);
}

double micros(const transport::Stamp& from, const transport::Stamp& to) {
  return 1e-3 * static_cast<double>(to.nanoseconds() - from.nanoseconds());
}

/// The lateness samples a histogram difference stands for (each bin at its centre).
std::vector<double> latenessSamples(const transport::DiagnosticsMessage& before,
                                    const transport::DiagnosticsMessage& after) {
  std::vector<double> samples;
  const auto& end = after.start_lateness_histogram;
  for (std::size_t i = 0; i < end.size(); ++i) {
    const std::uint64_t start =
        i < before.start_lateness_histogram.size() ? before.start_lateness_histogram[i] : 0;
    samples.insert(samples.end(), end[i] - start, (static_cast<double>(i) + 0.5) * 10.0);
  }
  return samples;
}

struct Collector {
  transport::Reader<transport::DiagnosticsMessage>& reader;
  std::map<std::int64_t, transport::CommandOutcomeMessage> outcomes;
  transport::DiagnosticsMessage last;
  void poll(double seconds) {
    std::vector<transport::Sample<transport::DiagnosticsMessage>> samples;
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < deadline) {
      reader.wait(0.02);
      samples.clear();
      reader.take(samples);
      for (const auto& sample : samples) {
        last = sample.message;
        for (const auto& outcome : sample.message.outcomes) {
          outcomes[outcome.stamp.nanoseconds()] = outcome;
        }
      }
    }
  }
};

transport::CartesianCommandMessage holdCommand(const transport::ControllerStateMessage& state,
                                               double offset_m) {
  transport::CartesianCommandMessage message;
  message.command = CartesianCommand::zero(static_cast<int>(state.position.size()));
  message.command.fields = CommandField::kPosition;
  message.command.position = {state.tcp_position[0], state.tcp_position[1] + offset_m,
                              state.tcp_position[2]};
  const auto& q = state.tcp_orientation;
  message.command.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
  return message;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::random_device random;
  const int domain = 1 + static_cast<int>(random() % 230);
  const pid_t host = startHost(domain, options);
  transport::Participant participant({.domain_id = domain});
  transport::Reader<transport::ControllerStateMessage> state_reader(participant, "bench");
  transport::Reader<transport::DiagnosticsMessage> diagnostics(participant, "bench", 100000);
  transport::Writer<transport::CartesianCommandMessage> writer(participant, "bench");
  std::vector<transport::Sample<transport::ControllerStateMessage>> states;
  for (int i = 0; i < 400 && states.empty(); ++i) {
    state_reader.wait(0.05);
    state_reader.take(states);
  }
  if (states.empty() || !writer.waitForMatch(1, 10.0)) {
    std::fprintf(stderr, "live_latency: no host\n");
    kill(host, SIGKILL);
    return 1;
  }
  const transport::ControllerStateMessage state = states.back().message;
  Collector collector{diagnostics, {}, {}};
  for (int i = 0; i < 50 && collector.outcomes.empty(); ++i) {  // discovery handshake
    transport::CartesianCommandMessage probe = holdCommand(state, 0.0);
    probe.header.stamp = transport::Stamp::now();
    writer.write(probe);
    collector.poll(0.1);
  }
  collector.poll(0.3);
  const transport::DiagnosticsMessage before = collector.last;
  collector.outcomes.clear();

  const auto count = static_cast<int>(options.seconds * options.rate_hz);
  const auto period = std::chrono::duration<double>(1.0 / options.rate_hz);
  const auto start = Clock::now();
  for (int i = 0; i < count; ++i) {
    std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(i * period));
    transport::CartesianCommandMessage message =
        holdCommand(state, 0.01 * std::sin(2.0 * M_PI * i / 2000.0));
    message.header.stamp = transport::Stamp::now();
    writer.write(message);
  }
  collector.poll(1.5);

  std::vector<double> transport_us, queue_us, total_us;
  int applied = 0;
  for (const auto& [stamp, outcome] : collector.outcomes) {
    if (outcome.outcome != transport::Outcome::kApplied) {
      continue;
    }
    ++applied;
    transport_us.push_back(micros(outcome.stamp, outcome.received));
    queue_us.push_back(micros(outcome.received, outcome.applied));
    total_us.push_back(micros(outcome.stamp, outcome.applied));
  }
  std::printf(
      "live_latency: %d commands at %.0f Hz to comply run --sim (1 kHz loop, priority %d), "
      "%d applied, %zu accounted\n",
      count, options.rate_hz, options.priority, applied, collector.outcomes.size());
  std::printf("%-10s %9s %9s %9s %9s %9s   [us]\n", "stage", "mean", "sd", "p50", "p99", "max");
  printRow("transport", transport_us);
  printRow("queue", queue_us);
  printRow("total", total_us);
  printRow("lateness", latenessSamples(before, collector.last));
  std::printf(
      "(lateness: cycle start against the wall clock, 10 us bins, bin centres; the last "
      "bin holds everything above 2 ms)\n");
  kill(host, SIGTERM);
  waitpid(host, nullptr, 0);
  return 0;
}
