#pragma once
// The threads of `comply run` around one wrapper and one plant (run_command.cpp sets them up).

#include <atomic>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "comply/pipeline/config.hpp"

namespace comply::host {

/// How `comply run` (or any live host) is set up.
struct LiveHostOptions {
  std::string config_file;
  std::string robot;             ///< overrides the controller file's robot
  bool sim = false;              ///< --sim: the same as --hardware sim
  std::string hardware = "sim";  ///< a backend name or library (host/hardware_backends.hpp)
  std::vector<std::string> hardware_options;  ///< key=value, handed to the backend
  bool view = false;                          ///< interactive window
  double rate_hz = 1000.0;                    ///< control rate
  double state_rate_hz = 100;                 ///< state topic rate
  double duration_s = 0.0;        ///< > 0: stop after this long (benchmarks); 0: until a signal
  std::string transport = "dds";  ///< a registered transport (transport/host_transport.hpp)
  int domain_id = 0;
  std::string network = "loopback";
  /// DDS Security: an enclave folder (transport/participant.hpp); empty: off.
  std::string security;
  std::string name = "comply";
  /// SCHED_FIFO priority of the control thread (the command reader and the transport's receive
  /// threads run one below); 0: normal scheduling. A process that may not have it runs at normal
  /// priority and says so once.
  int priority = 80;
  /// mlockall before the threads start (comply run); a refusal is a warning, not an error.
  bool lock_memory = false;
  /// Wake this long [us] before each cycle, warm the caches and spin to its start
  /// (hardware::LoopOptions::warm_ahead_s); 0: sleep to the start. Only for a sleeping clock.
  double warm_ahead_us = 0.0;
  std::string
      record_path;  ///< non-empty: record every cycle, command and outcome to this MCAP file
  /// Non-empty: a Foxglove live view on "[ADDRESS:]PORT" (host/live_view.hpp).
  std::string foxglove;
};

/// Runs the controller `config` (from controllerConfig() or simControllerConfig()) on the
/// hardware and transport `options` name until `stop` is set or options.duration_s has passed;
/// prints a summary on `out`. Resolves the controller once, after the hardware says whether it
/// compensates gravity itself. Returns the process exit code; throws on bad set-up.
int runLiveHost(const LiveHostOptions& options, pipeline::WrapperConfig config,
                const std::atomic<bool>& stop, std::ostream& out, std::ostream& err);

/// Registers the transports built into comply ("dds", "in_process"); runLiveHost() does it once.
void registerBuiltinTransports();

/// Makes the calling thread SCHED_FIFO at `priority` (0: leaves it); "" on success, else why not
/// and what it costs.
std::string makeRealtime(int priority);

}  // namespace comply::host
