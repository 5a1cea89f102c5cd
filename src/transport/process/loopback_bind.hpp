#pragma once
// CycloneDDS 0.10 binds its UDP sockets to the "any" address whatever interface it is told to use
// (it has no option to bind to one), so a host on loopback would still take packets sent to the
// machine's other addresses. comply-transport defines bind() itself (loopback_bind.cpp): the
// program's own definition comes first in the dynamic linker's search, so CycloneDDS's calls reach
// it. While loopback only is on, an IPv4 "any" address becomes 127.0.0.1; everything else passes
// unchanged to the kernel. Only comply-transport links this.

namespace comply::transport::process {

/// From now on, sockets bound to the IPv4 "any" address are bound to 127.0.0.1 instead.
void bindLoopbackOnly();

}  // namespace comply::transport::process
