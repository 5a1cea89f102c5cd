#pragma once
// The Foxglove WebSocket protocol's text messages, both ways: what the server says (serverInfo,
// advertise, status) and what it understands of a client (subscribe, unsubscribe), and the
// subprotocol negotiation.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "client_queue.hpp"
#include "comply/viewer/foxglove_server.hpp"

namespace comply::viewer {

/// The subprotocol names served, the current one first.
inline constexpr std::string_view kSubprotocolSdk = "foxglove.sdk.v1";
inline constexpr std::string_view kSubprotocolWebsocket = "foxglove.websocket.v1";

/// The first name of a Sec-WebSocket-Protocol header (comma-separated, in the client's order of
/// preference) that this server speaks; none when it speaks none of them.
std::optional<std::string> chooseSubprotocol(std::string_view offered);

/// Status levels of the protocol's status message.
enum class StatusLevel : int { kInfo = 0, kWarning = 1, kError = 2 };

std::string serverInfoJson(const std::string& name, const std::string& session_id);
std::string advertiseJson(const std::vector<std::pair<ChannelId, ChannelSpec>>& channels);
std::string statusJson(StatusLevel level, const std::string& message);

/// A client's message this server cannot take (not JSON, a field missing or of the wrong type).
class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SubscribeOp {
  std::vector<std::pair<SubscriptionId, ChannelId>> subscriptions;
};
struct UnsubscribeOp {
  std::vector<SubscriptionId> subscriptions;
};
/// Any other op: the server says it does not take it.
struct OtherOp {
  std::string op;
};
using ClientOp = std::variant<SubscribeOp, UnsubscribeOp, OtherOp>;

/// Throws ProtocolError saying what is wrong.
ClientOp parseClientOp(std::string_view text);

}  // namespace comply::viewer
