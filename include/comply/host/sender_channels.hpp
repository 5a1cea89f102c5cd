#pragma once
// The channels of what a sender writes, under a prefix (`/<name>/`): the commands and chunks of
// both kinds and the requests, one channel each, whatever a channel's id is: a recording's
// (host_recording.hpp) or a live view's (live_view.hpp).

#include <string>
#include <type_traits>

#include "comply/transport/messages.hpp"

namespace comply::host {

template <typename Id>
class SenderChannelIds {
 public:
  SenderChannelIds() = default;
  /// `add(topic, std::type_identity<Message>{})` makes the channel of `Message` on `topic`.
  template <typename Add>
  SenderChannelIds(const std::string& prefix, Add&& add)
      : cartesian_(add(prefix + "cartesian_command",
                       std::type_identity<transport::CartesianCommandMessage>{})),
        joint_(add(prefix + "joint_command", std::type_identity<transport::JointCommandMessage>{})),
        cartesian_chunk_(add(prefix + "cartesian_chunk",
                             std::type_identity<transport::CartesianChunkMessage>{})),
        joint_chunk_(
            add(prefix + "joint_chunk", std::type_identity<transport::JointChunkMessage>{})),
        request_(add(prefix + "request", std::type_identity<transport::RequestMessage>{})) {}

  /// The channel of a message of type `Message`.
  template <typename Message>
  [[nodiscard]] Id of() const noexcept {
    if constexpr (std::is_same_v<Message, transport::CartesianCommandMessage>) {
      return cartesian_;
    } else if constexpr (std::is_same_v<Message, transport::JointCommandMessage>) {
      return joint_;
    } else if constexpr (std::is_same_v<Message, transport::CartesianChunkMessage>) {
      return cartesian_chunk_;
    } else if constexpr (std::is_same_v<Message, transport::JointChunkMessage>) {
      return joint_chunk_;
    } else {
      static_assert(std::is_same_v<Message, transport::RequestMessage>, "not a sender's message");
      return request_;
    }
  }

 private:
  Id cartesian_{};
  Id joint_{};
  Id cartesian_chunk_{};
  Id joint_chunk_{};
  Id request_{};
};

}  // namespace comply::host
