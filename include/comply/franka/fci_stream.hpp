#pragma once
// The FCI command port's byte stream, for both ends (the client, comply's emulator).

#include <cstddef>
#include <cstdint>
#include <stop_token>

namespace comply::franka {

/// Reads exactly `bytes` from the connected TCP `socket` into `out`, looking at `stop` every
/// 50 ms; false when the peer closed the connection, it failed, or a stop was asked for.
bool readExactly(int socket, std::uint8_t* out, std::size_t bytes, const std::stop_token& stop);

}  // namespace comply::franka
