#pragma once
// The writers matched with one DDS reader: which process sent a sample, and which writers left.
//
// Every reader of commands needs both, whoever created it: comply's own readers (Reader<Message>)
// and the ROS 2 controllers, whose subscriptions rmw_cyclonedds creates on the same CycloneDDS
// (comply_ros2_control/writer_identity.hpp). A sample names its writer by the DDS instance handle
// of the writer's publication here (dds_sample_info_t::publication_handle, also what
// rmw_cyclonedds puts into a ROS message's publisher_gid); DDS knows that writer's participant.
//
// Not thread-safe: one thread (the one taking the reader's samples) asks.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

/// The process a writer belongs to.
struct WriterSender {
  std::uint64_t participant = 0;  ///< its participant's instance handle here (0: not known)
  Gid gid{};                      ///< its participant's GUID, as every peer knows it
};

class MatchedWriters {
 public:
  /// `reader`: a DDS reader entity (dds_entity_t) of this process.
  explicit MatchedWriters(std::int32_t reader) noexcept : reader_(reader) {}

  /// True when `entity` is a DDS reader of this process (a handle from elsewhere is checked).
  [[nodiscard]] static bool isReader(std::int32_t entity) noexcept;

  /// The participant of the matched writer `publication` (a publication handle), asked of DDS
  /// once per writer; all zero while DDS does not know it (asked again next time).
  WriterSender senderOf(std::uint64_t publication);

  /// Appends to `departed` each writer matched at the previous call and no longer matched now
  /// (deleted, or its process ended). Lists the matched set only when the reader's matched
  /// status says matching happened since; the first call only learns the set.
  void noteDepartures(std::vector<std::uint64_t>& departed);

  /// Whether `publication` was matched at the last noteDepartures(): a sample can outlive its
  /// writer's match (a publisher that sent once and exited), and its sender has then left.
  [[nodiscard]] bool isMatched(std::uint64_t publication) const noexcept;

 private:
  std::int32_t reader_ = 0;
  std::vector<std::uint64_t> matched_;  ///< the writers matched when last asked
  std::uint32_t matches_seen_ = 0;      ///< the status's total match count then
  std::unordered_map<std::uint64_t, WriterSender> senders_;  ///< writer -> its participant
};

}  // namespace comply::transport
