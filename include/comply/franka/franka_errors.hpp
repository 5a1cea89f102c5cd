#pragma once
// What stops a Franka arm, in words: the robot's 41 error flags (the order of the state's
// `errors` and `reflex_reason`) and its modes, as the FAULT texts the backend hands the cycle
// (HardwareInterface::robotStop).

#include <array>
#include <cstdint>
#include <string>

#include "comply/franka/fci_protocol.hpp"

namespace comply::franka {

/// The flag's name as libfranka and the robot's Desk print it ("joint_reflex"); "" past the last.
const char* errorName(int index) noexcept;
/// All flags set, by name, comma-separated ("joint_reflex, cartesian_reflex"); "" for none.
std::string errorNames(const std::array<bool, fci::kErrorCount>& flags);

/// The FAULT text for a robot that stopped with `flags` (its active errors, or what ended the
/// motion) in `mode`, or nullptr when it runs. Static texts: the first flag set decides
/// ("reflex joint_reflex (...): reset to recover; ..."); a mode without a flag has its own (user
/// stop, guiding, not ready). Real-time: no allocation.
const char* stopText(const std::array<bool, fci::kErrorCount>& flags, fci::RobotMode mode) noexcept;

}  // namespace comply::franka
