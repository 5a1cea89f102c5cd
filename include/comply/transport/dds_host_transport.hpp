#pragma once
// The live host's transport over DDS: comply's topics as ROS 2 names and types them
// (endpoints.hpp), on a loopback-only participant unless the network is opened.

#include <memory>

#include "comply/transport/host_transport.hpp"

namespace comply::transport {

/// Registered as "dds". Throws TransportError when DDS refuses (domain out of range, ...).
std::unique_ptr<HostTransport> makeDdsHostTransport(const HostTransportOptions& options);

}  // namespace comply::transport
