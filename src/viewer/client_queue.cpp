// One client's queues (see client_queue.hpp).

#include "client_queue.hpp"

namespace comply::viewer {

std::array<std::uint8_t, 13> messageDataHeader(SubscriptionId subscription,
                                               std::int64_t log_time_ns) {
  std::array<std::uint8_t, 13> header{};
  header[0] = 0x01;  // messageData
  for (int i = 0; i < 4; ++i) {
    header[1 + i] = static_cast<std::uint8_t>(subscription >> (8 * i));
  }
  const auto time = static_cast<std::uint64_t>(log_time_ns);
  for (int i = 0; i < 8; ++i) {
    header[5 + i] = static_cast<std::uint8_t>(time >> (8 * i));
  }
  return header;
}

bool ClientQueue::subscribe(ChannelId channel, SubscriptionId subscription) {
  if (channels_.contains(channel)) {
    return false;
  }
  for (const auto& [id, queue] : channels_) {
    if (queue.subscription == subscription) {
      return false;
    }
  }
  channels_[channel].subscription = subscription;
  return true;
}

std::optional<ChannelId> ClientQueue::unsubscribe(SubscriptionId subscription) {
  for (auto it = channels_.begin(); it != channels_.end(); ++it) {
    if (it->second.subscription == subscription) {
      const ChannelId channel = it->first;
      channels_.erase(it);
      return channel;
    }
  }
  return std::nullopt;
}

std::vector<ChannelId> ClientQueue::channels() const {
  std::vector<ChannelId> ids;
  ids.reserve(channels_.size());
  for (const auto& entry : channels_) {
    ids.push_back(entry.first);
  }
  return ids;
}

bool ClientQueue::pushText(std::string text) {
  if (texts_.size() >= kMaxTexts) {
    return false;
  }
  texts_.push_back(std::move(text));
  return true;
}

std::uint64_t ClientQueue::push(ChannelId channel, std::int64_t log_time_ns,
                                SharedPayload payload) {
  const auto found = channels_.find(channel);
  if (found == channels_.end()) {
    return 0;
  }
  ChannelQueue& queue = found->second;
  queue.bytes += payload->size();
  queue.messages.push_back({log_time_ns, std::move(payload)});
  std::uint64_t dropped = 0;
  while (queue.bytes > limit_bytes_ && queue.messages.size() > 1) {
    queue.bytes -= queue.messages.front().payload->size();
    queue.messages.pop_front();
    ++dropped;
  }
  queue.dropped_unreported += dropped;
  return dropped;
}

bool ClientQueue::pop(Outgoing& out) {
  if (!texts_.empty()) {
    out = OutgoingText{std::move(texts_.front())};
    texts_.pop_front();
    return true;
  }
  if (channels_.empty()) {
    return false;
  }
  // The first channel after the last one served that has a message, wrapping around.
  auto start = last_served_ ? channels_.upper_bound(*last_served_) : channels_.begin();
  for (std::size_t seen = 0; seen < channels_.size(); ++seen) {
    if (start == channels_.end()) {
      start = channels_.begin();
    }
    ChannelQueue& queue = start->second;
    if (!queue.messages.empty()) {
      Queued& next = queue.messages.front();
      queue.bytes -= next.payload->size();
      out = OutgoingData{start->first, messageDataHeader(queue.subscription, next.log_time_ns),
                         std::move(next.payload)};
      queue.messages.pop_front();
      last_served_ = start->first;
      return true;
    }
    ++start;
  }
  return false;
}

std::vector<DropReport> ClientQueue::takeDrops() {
  std::vector<DropReport> reports;
  for (auto& [channel, queue] : channels_) {
    if (queue.dropped_unreported > 0) {
      reports.push_back({channel, queue.dropped_unreported});
      queue.dropped_unreported = 0;
    }
  }
  return reports;
}

std::size_t ClientQueue::queuedBytes(ChannelId channel) const {
  const auto found = channels_.find(channel);
  return found == channels_.end() ? 0 : found->second.bytes;
}

}  // namespace comply::viewer
