#pragma once
// `comply run`: the controller host. The control loop runs the wrapper on the hardware at the
// control rate on a real-time thread; DDS threads feed it commands and publish its state and
// diagnostics (ROS 2 topics under /<name>/, see transport/endpoints.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct RunOptions {
  std::string config_file;
  std::string robot;           ///< overrides the controller file's robot
  bool sim = false;            ///< MuJoCo plant as the hardware
  bool view = false;           ///< interactive window
  double rate_hz = 1000.0;     ///< control rate
  double state_rate_hz = 100;  ///< state topic rate
  double duration_s = 0.0;     ///< > 0: stop after this long (benchmarks); 0: until a signal
  int domain_id = 0;
  std::string network = "loopback";
  std::string name = "comply";
  int priority = 80;  ///< SCHED_FIFO priority of the control thread; 0: normal scheduling
};

/// Runs until SIGINT or SIGTERM (or duration_s), then deactivates, flushes and returns 0; 2 on
/// bad options or setup.
int runCommand(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
