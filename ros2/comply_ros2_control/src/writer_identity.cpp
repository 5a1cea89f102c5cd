#include "comply_ros2_control/writer_identity.hpp"

#include <rcl/subscription.h>

#include <cstring>
#include <string_view>

namespace comply_ros2_control {
namespace {

/// A publisher GID folded into the gate's 64-bit writer identity (FNV-1a), never 0.
std::uint64_t gidHash(const rmw_gid_t& gid) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const auto byte : gid.data) {
    hash = (hash ^ static_cast<std::uint8_t>(byte)) * 1099511628211ULL;
  }
  return hash == 0 ? 1 : hash;
}

/// The CycloneDDS reader behind `subscription`, when rmw_cyclonedds made it. rmw_cyclonedds keeps
/// the reader's entity handle as the first member of the subscription's implementation data (its
/// CddsSubscription derives from CddsEntity { dds_entity_t enth; }, as from Foxy on); DDS is
/// asked whether the handle is a reader before it is used.
std::optional<std::int32_t> cycloneReader(rclcpp::SubscriptionBase& subscription) {
  const rmw_subscription_t* rmw =
      rcl_subscription_get_rmw_handle(subscription.get_subscription_handle().get());
  if (rmw == nullptr || rmw->data == nullptr || rmw->implementation_identifier == nullptr ||
      std::string_view(rmw->implementation_identifier) != "rmw_cyclonedds_cpp") {
    return std::nullopt;
  }
  std::int32_t reader = 0;
  std::memcpy(&reader, rmw->data, sizeof reader);
  if (!comply::transport::MatchedWriters::isReader(reader)) {
    return std::nullopt;
  }
  return reader;
}

}  // namespace

WriterIdentity::WriterIdentity(rclcpp::SubscriptionBase& subscription) {
  if (const auto reader = cycloneReader(subscription)) {
    writers_.emplace(*reader);
  }
}

WriterOf WriterIdentity::of(const rmw_message_info_t& info) {
  WriterOf writer;
  if (!writers_) {
    writer.publisher = gidHash(info.publisher_gid);
    return writer;
  }
  // rmw_cyclonedds: the first 8 bytes of publisher_gid are the writer's publication handle, what
  // comply's own readers name a sample's writer by.
  std::memcpy(&writer.publisher, info.publisher_gid.data, sizeof writer.publisher);
  const comply::transport::WriterSender sender = writers_->senderOf(writer.publisher);
  writer.participant = sender.participant;
  writer.sender = sender.gid;
  if (writer.publisher == 0) {
    writer.publisher = gidHash(info.publisher_gid);
  }
  return writer;
}

void WriterIdentity::noteDepartures(std::vector<std::uint64_t>& departed) {
  if (writers_) {
    writers_->noteDepartures(departed);
  }
}

}  // namespace comply_ros2_control
