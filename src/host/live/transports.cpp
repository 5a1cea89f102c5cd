// The transports a live host can be reached over, by name (`comply run --transport NAME`). A new
// middleware is one folder implementing transport::HostTransport and one line here.

#include "comply/host/live_host.hpp"
#include "comply/transport/dds_host_transport.hpp"
#include "comply/transport/in_process.hpp"
#include "comply/transport/process_transport.hpp"

namespace comply::host {

void registerBuiltinTransports() {
  // DDS deserialises what any peer sends: in a process of its own, so that a crash or hang there
  // leaves the control loop running. dds_inline keeps it in the host (one hop less).
  transport::registerHostTransport("dds", [](const transport::HostTransportOptions& options) {
    return transport::makeProcessHostTransport(options);
  });
  transport::registerHostTransport("dds_inline", transport::makeDdsHostTransport);
  transport::registerHostTransport("in_process", transport::makeInProcessHostTransport);
}

}  // namespace comply::host
