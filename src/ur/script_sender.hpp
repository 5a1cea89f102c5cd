#pragma once
// Sending a URScript program to a UR controller's secondary interface.

#include <cstdint>
#include <string>

namespace comply::ur {

/// Sends a URScript program to the secondary interface at `host`:`port` and closes, after
/// reading the controller's greeting; throws hardware::BackendError naming the address when it
/// cannot.
void sendScript(const std::string& host, std::uint16_t port, const std::string& script,
                double timeout_s);

}  // namespace comply::ur
