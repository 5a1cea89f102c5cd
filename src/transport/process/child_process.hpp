#pragma once
// Starting and reaping one child process that talks over a socket: the operating system's part
// of the transport process's supervision (supervisor.hpp). Private to the transport.

#include <sys/types.h>

#include <string>
#include <vector>

namespace comply::transport::process {

/// A started child and the host's end of its socket.
struct ChildWithSocket {
  pid_t pid = -1;
  int socket = -1;
};

/// Starts `args[0]` with `args` on a new socket pair: the child's end as descriptor `child_fd`
/// (every other descriptor of the host stays closed there), the host's end returned with a send
/// timeout of `send_timeout_s`. Throws TransportError when it cannot be started.
ChildWithSocket spawnWithSocket(const std::vector<std::string>& args, int child_fd,
                                double send_timeout_s);

/// Waits for `pid` to end (killing it when `kill`, or when it will not end in 1 s); its wait
/// status, -1 when it could not be read, 0 without a child (`pid` <= 0).
int reapChild(pid_t pid, bool kill);

/// How a child with wait status `status` (reapChild) ended, in words: "ended on signal 6
/// (Aborted)", "exited with code 1".
std::string describeEnd(int status);

}  // namespace comply::transport::process
