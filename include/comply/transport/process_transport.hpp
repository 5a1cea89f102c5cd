#pragma once
// A live host's middleware in a process of its own: the `comply-transport` program runs a
// transport (DDS) and hands the host what it receives, as comply's own CDR frames over a socket.
// Whatever the network sends is deserialised in that process, so a middleware that crashes on a
// malformed sample (CycloneDDS 0.10 on one XCDR2 sample does) or hangs takes that process down,
// not the control loop: the host sees no commands while the transport is gone, the watchdog
// holds the arm, and the transport is started again. Each end is printed with its cause and
// counted (HostTransport::restarts(), in the run's summary).

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>

#include "comply/transport/host_transport.hpp"

namespace comply::transport {

struct ProcessTransportOptions {
  std::string inner = "dds";      ///< the transport the process runs (comply-transport --transport)
  std::filesystem::path program;  ///< empty: transportProgram()
  /// A ready process that sends nothing for this long is hung: it is killed and started again.
  /// It sends a heartbeat every 50 ms.
  double heartbeat_timeout_s = 1.0;
  /// The wait before a restart; it doubles, up to 8 s, while restarted processes keep ending
  /// within 2 s (a process that cannot start is not restarted in a tight loop).
  double restart_delay_s = 0.5;
  /// How long a start may take until the process is ready (its DDS participant made; DDS
  /// Security's checks can take a while): the first start's error, a restart's kill.
  double start_timeout_s = 10.0;
  std::ostream* log = nullptr;  ///< where the ends and restarts are reported; nullptr: std::cerr
};

/// A process transport (above); the first start is waited for, so that an error of the inner
/// transport (domain out of range, ...) is thrown here as TransportError with its own message.
std::unique_ptr<HostTransport> makeProcessHostTransport(const HostTransportOptions& options,
                                                        ProcessTransportOptions process = {});

/// The transport program: $COMPLY_TRANSPORT_PROGRAM when set, else comply-transport of an
/// installed comply (lib/comply/ of the prefix), else the one of the build tree.
std::filesystem::path transportProgram();

}  // namespace comply::transport
