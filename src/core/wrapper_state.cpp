#include "comply/core/wrapper_state.hpp"

namespace comply {

std::string_view toString(WrapperState state) {
  switch (state) {
    case WrapperState::kInactive:
      return "inactive";
    case WrapperState::kActive:
      return "active";
    case WrapperState::kFault:
      return "fault";
  }
  return "unknown";
}

}  // namespace comply
