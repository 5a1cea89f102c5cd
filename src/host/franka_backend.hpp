#pragma once
// `comply run --hardware franka`: a Franka arm (FR3, Panda) through libfranka where comply was
// built with it, or comply's own FCI client (franka/fci_session.hpp), set up from
// --hardware-option key=value pairs.

#include <memory>

#include "comply/franka/franka_session.hpp"
#include "comply/host/hardware_backends.hpp"

namespace comply::host {

HardwareBackend frankaArm(const pipeline::WrapperConfig& config,
                          const hardware::BackendContext& context);

/// True when comply was built with libfranka.
bool libfrankaBuiltIn() noexcept;
/// A session through libfranka (franka_libfranka_session.cpp): nullptr when comply was built
/// without it. `realtime`: libfranka's check for a real-time kernel.
std::unique_ptr<franka::FrankaSession> makeLibfrankaSession(const std::string& robot_ip,
                                                            bool realtime);

}  // namespace comply::host
