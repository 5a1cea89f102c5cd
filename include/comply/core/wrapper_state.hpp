#pragma once
// The controller wrapper's state (pipeline::Controller). Every host reports it as it is:
// ControllerState.state on the wire carries these values (transport::HostState).

#include <cstdint>
#include <string_view>

#include "comply/core/enum_names.hpp"

namespace comply {

enum class WrapperState : std::uint8_t { kInactive = 0, kActive = 1, kFault = 2 };
inline constexpr EnumNames<WrapperState, 3> kWrapperStateNames{
    {{WrapperState::kInactive, "inactive"},
     {WrapperState::kActive, "active"},
     {WrapperState::kFault, "fault"}}};

constexpr std::string_view toString(WrapperState state) noexcept {
  return nameIn(kWrapperStateNames, state);
}

}  // namespace comply
