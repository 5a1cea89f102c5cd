// The transports a live host can be reached over, by name (`comply run --transport NAME`). A new
// middleware is one folder implementing transport::HostTransport and one line here.

#include "comply/host/live_host.hpp"
#include "comply/transport/dds_host_transport.hpp"
#include "comply/transport/in_process.hpp"

namespace comply::host {

void registerBuiltinTransports() {
  transport::registerHostTransport("dds", transport::makeDdsHostTransport);
  transport::registerHostTransport("in_process", transport::makeInProcessHostTransport);
}

}  // namespace comply::host
