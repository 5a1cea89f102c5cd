#pragma once
// Who sent a message on a controller's command topics, and which writers left, as `comply run`
// tells them apart (comply/transport/matched_writers.hpp).
//
// Under rmw_cyclonedds the subscription is a CycloneDDS reader of this process, and a message's
// publisher_gid holds the writer's DDS publication handle: DDS then names the writer's participant
// (its process, whose GUID every peer knows: the sender an outcome names, so that a client
// recognises its own commands), and says when the writer is no longer matched (deleted, or its
// process ended), which releases the command topics at once. Under another middleware only the
// publisher GID is known (namesSenders() false): outcomes name no sender, and the controller
// releases the topics when its subscriptions have no publisher left.
//
// Not thread-safe: the controller asks under its endpoints mutex.

#include <rmw/types.h>

#include <cstdint>
#include <optional>
#include <rclcpp/subscription_base.hpp>
#include <vector>

#include "comply/transport/matched_writers.hpp"

namespace comply_ros2_control {

/// A message's sender as the command gate takes it (comply::pipeline::Offer).
struct WriterOf {
  std::uint64_t publisher = 0;      ///< the writer (never 0)
  std::uint64_t participant = 0;    ///< its process (0: not known)
  comply::transport::Gid sender{};  ///< its process's GUID (all zero: not known)
};

class WriterIdentity {
 public:
  /// For the messages of `subscription`, which must outlive this.
  explicit WriterIdentity(rclcpp::SubscriptionBase& subscription);

  /// True when the middleware names senders and departures (rmw_cyclonedds).
  [[nodiscard]] bool namesSenders() const noexcept { return writers_.has_value(); }

  /// The sender of a message taken with `info`.
  WriterOf of(const rmw_message_info_t& info);

  /// With namesSenders(): appends each writer (WriterOf::publisher) that left since the last call.
  void noteDepartures(std::vector<std::uint64_t>& departed);
  /// With namesSenders(): whether `publisher` was matched at the last noteDepartures() (else its
  /// message outlived it: it sent and left).
  [[nodiscard]] bool isMatched(std::uint64_t publisher) const noexcept {
    return !writers_ || writers_->isMatched(publisher);
  }

 private:
  std::optional<comply::transport::MatchedWriters> writers_;
};

}  // namespace comply_ros2_control
