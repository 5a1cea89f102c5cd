// Matched writers of a DDS reader over the CycloneDDS C API.

#include "comply/transport/matched_writers.hpp"

#include <dds/dds.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <span>

namespace comply::transport {

bool MatchedWriters::isReader(std::int32_t entity) noexcept {
  // Only a reader has a subscription-matched status; a writer is an illegal operation, anything
  // else a bad parameter.
  dds_subscription_matched_status_t status{};
  return entity > 0 && dds_get_subscription_matched_status(entity, &status) == DDS_RETCODE_OK;
}

WriterSender MatchedWriters::senderOf(std::uint64_t publication) {
  const auto known = senders_.find(publication);
  if (known != senders_.end()) {
    return known->second;
  }
  dds_builtintopic_endpoint_t* endpoint = dds_get_matched_publication_data(reader_, publication);
  if (endpoint == nullptr) {
    // Not known (yet): asked again next time rather than remembered as nobody, whose outcomes
    // every client would take for its own.
    return {};
  }
  WriterSender sender;
  sender.participant = endpoint->participant_instance_handle;
  std::memcpy(sender.gid.data(), endpoint->participant_key.v, sender.gid.size());
  dds_builtintopic_free_endpoint(endpoint);
  if (senders_.size() > 4096) {
    senders_.clear();  // writers come and go; a long-lived host must not grow without bound
  }
  senders_.emplace(publication, sender);
  return sender;
}

bool MatchedWriters::isMatched(std::uint64_t publication) const noexcept {
  return std::find(matched_.begin(), matched_.end(), publication) != matched_.end();
}

void MatchedWriters::noteDepartures(std::vector<std::uint64_t>& departed) {
  // A writer deleted (or whose process ended) is no longer matched. The matched set is compared,
  // not the matched status's count: a writer leaving while another arrives nets no change.
  dds_subscription_matched_status_t status{};
  if (dds_get_subscription_matched_status(reader_, &status) < 0 ||
      (status.total_count == matches_seen_ && status.current_count == matched_.size())) {
    return;
  }
  matches_seen_ = status.total_count;
  std::array<dds_instance_handle_t, 64> handles{};
  const dds_return_t count = dds_get_matched_publications(reader_, handles.data(), handles.size());
  if (count < 0) {
    return;
  }
  const auto now = std::span(handles.data(), std::min<std::size_t>(count, handles.size()));
  for (const std::uint64_t before : matched_) {
    if (std::find(now.begin(), now.end(), before) == now.end()) {
      departed.push_back(before);
    }
  }
  matched_.assign(now.begin(), now.end());
}

}  // namespace comply::transport
