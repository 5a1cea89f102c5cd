// The registry of host transports (see host_transport.hpp).

#include "comply/transport/host_transport.hpp"

#include "comply/core/named_registry.hpp"

namespace comply::transport {
namespace {

NamedRegistry<HostTransportFactory>& registry() {
  static NamedRegistry<HostTransportFactory> instance;
  return instance;
}

}  // namespace

void registerHostTransport(const std::string& name, HostTransportFactory factory) {
  registry().add(name, std::move(factory));
}

std::unique_ptr<HostTransport> makeHostTransport(const std::string& name,
                                                 const HostTransportOptions& options) {
  const HostTransportFactory factory = registry().find(name);
  if (!factory) {
    throw TransportError("no transport named '" + name + "' (registered: " + registry().list() +
                         ")");
  }
  return factory(options);
}

std::vector<std::string> hostTransportNames() {
  return registry().names();
}

}  // namespace comply::transport
