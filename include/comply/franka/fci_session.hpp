#pragma once
// comply's own FCI client (fci_protocol.hpp): a FrankaSession without libfranka, for robots
// whose system speaks protocol version 7 and for comply's FCI robot emulator. A robot that
// speaks another version refuses it at Connect, and the error says to use libfranka.
//
// The commands go over TCP (a reader thread, not real-time, takes the responses); the states
// and the torques over UDP on the control thread: a blocking receive with a deadline, the
// answer encoded in place and sent. Neither allocates nor takes a lock.

#include <cstdint>
#include <memory>
#include <string>

#include "comply/franka/franka_session.hpp"

namespace comply::franka {

struct FciSessionOptions {
  std::string robot_ip;  ///< IPv4
  std::uint16_t command_port = fci::kCommandPort;
  double connect_timeout_s = 5.0;  ///< TCP connect and every command's response [s]
  /// The largest deviation from its path Move allows (libfranka's defaults for a torque control)
  std::array<double, 3> path_deviation{10.0, 3.12, 6.283185307179586};
};

/// Connects (TCP, then the version check), throws hardware::BackendError naming the address and
/// what failed.
std::unique_ptr<FrankaSession> makeFciSession(const FciSessionOptions& options);

}  // namespace comply::franka
