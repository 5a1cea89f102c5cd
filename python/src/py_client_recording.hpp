#pragma once
// What a comply.Client sent and saw, in an MCAP file (`record=`):
//
//   /<name>/cartesian_command  comply_msgs/CartesianCommand  every command written
//   /<name>/joint_command      comply_msgs/JointCommand      every command written
//   /<name>/cartesian_chunk    comply_msgs/CartesianChunk    every chunk written
//   /<name>/joint_chunk        comply_msgs/JointChunk        every chunk written
//   /<name>/request            comply_msgs/Request           every request written
//   /<name>/state              comply_msgs/ControllerState   every state taken from the host
//   /<name>/diagnostics        comply_msgs/Diagnostics       every diagnostics message taken
//
// Messages are the CDR bytes of the wire. What the client sent is logged at its stamp (the wall
// clock when it was sent), what it saw at the wall clock when the client took it. One lane: the
// client has no thread of its own, so every record comes from the thread that calls it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "comply/host/host_recording.hpp"
#include "comply/record/recorder.hpp"
#include "comply/transport/messages.hpp"

namespace comply::python {

class ClientRecording {
 public:
  /// Creates `path` (throws record::McapError naming it, or its missing folder: none is made)
  /// and starts the writer thread; `name`, `domain` and `network` are the host the client talks
  /// to (metadata "comply_client").
  ClientRecording(const std::filesystem::path& path, const std::string& name, int domain,
                  const std::string& network);

  /// A command or chunk of either kind, or a request, at its stamp.
  template <typename Message>
  void sent(const Message& message);
  void seen(const transport::ControllerStateMessage& message, transport::Stamp taken);
  void seen(const transport::DiagnosticsMessage& message, transport::Stamp taken);

  /// Later records are ignored (under the client's locks, which guard every record).
  void close() noexcept { open_ = false; }
  /// Drains, writes the counts and closes the file; idempotent. Needs no lock of the client's.
  void finish();
  /// close() and finish().
  void stop() {
    close();
    finish();
  }
  [[nodiscard]] record::RecorderStats stats() const { return recorder_.stats(); }

 private:
  template <typename Message>
  void push(std::uint16_t channel, const Message& message, transport::Stamp time);

  record::Recorder recorder_;
  record::RecordLane& lane_;
  host::SenderChannels senders_;
  std::uint16_t state_channel_ = 0;
  std::uint16_t diagnostics_channel_ = 0;
  bool open_ = true;
  std::vector<std::uint8_t> bytes_;  // the encoding's scratch
};

}  // namespace comply::python
