// This comply was built without libfranka (franka_backend.hpp): no such session.

#include "franka_backend.hpp"

namespace comply::host {

bool libfrankaBuiltIn() noexcept {
  return false;
}

std::unique_ptr<franka::FrankaSession> makeLibfrankaSession(const std::string& robot_ip,
                                                            bool realtime) {
  (void)robot_ip;
  (void)realtime;
  return nullptr;
}

}  // namespace comply::host
