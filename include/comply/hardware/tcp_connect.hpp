#pragma once
// A TCP connection to a robot controller's port, made within a time limit: the vendor backends'
// clients (UR's RTDE and program sender, comply's FCI client).

#include <cstdint>
#include <string>

namespace comply::hardware {

/// A connected socket to `host` (an IPv4 address):`port`, or -1 with `why` said ("... is not an
/// IPv4 address", or the system's reason, ETIMEDOUT after `timeout_s`). A blocking connect would
/// wait for TCP's own retries instead: minutes on a routed network.
int connectTcp(const std::string& host, std::uint16_t port, double timeout_s, std::string& why);

}  // namespace comply::hardware
