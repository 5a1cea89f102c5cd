#pragma once
// The controller wrapper's state (pipeline::Controller). Every host reports it as it is:
// ControllerState.state on the wire carries these values (transport::HostState).

#include <cstdint>
#include <string_view>

namespace comply {

enum class WrapperState : std::uint8_t { kInactive = 0, kActive = 1, kFault = 2 };

/// "inactive", "active" or "fault".
std::string_view toString(WrapperState state);

}  // namespace comply
