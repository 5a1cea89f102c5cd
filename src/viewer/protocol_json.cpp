// The protocol's text messages (see protocol_json.hpp).

#include "protocol_json.hpp"

#include <nlohmann/json.hpp>

namespace comply::viewer {
namespace {

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) {
    return {};
  }
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

template <typename Number>
Number number(const nlohmann::json& object, const char* key, std::string_view op) {
  const auto found = object.find(key);
  if (found == object.end() || !found->is_number_unsigned()) {
    throw ProtocolError(std::string(op) + ": \"" + key + "\" must be a non-negative integer");
  }
  const auto value = found->get<std::uint64_t>();
  if (value > std::numeric_limits<Number>::max()) {
    throw ProtocolError(std::string(op) + ": \"" + key + "\" is out of range");
  }
  return static_cast<Number>(value);
}

const nlohmann::json& array(const nlohmann::json& message, const char* key, std::string_view op) {
  const auto found = message.find(key);
  if (found == message.end() || !found->is_array()) {
    throw ProtocolError(std::string(op) + ": \"" + key + "\" must be an array");
  }
  return *found;
}

}  // namespace

std::optional<std::string> chooseSubprotocol(std::string_view offered) {
  while (!offered.empty()) {
    const auto comma = offered.find(',');
    const std::string_view name = trimmed(offered.substr(0, comma));
    if (name == kSubprotocolSdk || name == kSubprotocolWebsocket) {
      return std::string(name);
    }
    if (comma == std::string_view::npos) {
      break;
    }
    offered.remove_prefix(comma + 1);
  }
  return std::nullopt;
}

std::string serverInfoJson(const std::string& name, const std::string& session_id) {
  return nlohmann::json{{"op", "serverInfo"},
                        {"name", name},
                        {"capabilities", nlohmann::json::array()},
                        {"supportedEncodings", nlohmann::json::array()},
                        {"metadata", nlohmann::json::object()},
                        {"sessionId", session_id}}
      .dump();
}

std::string advertiseJson(const std::vector<std::pair<ChannelId, ChannelSpec>>& channels) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [id, spec] : channels) {
    list.push_back({{"id", id},
                    {"topic", spec.topic},
                    {"encoding", spec.encoding},
                    {"schemaName", spec.schema_name},
                    {"schema", spec.schema},
                    {"schemaEncoding", spec.schema_encoding}});
  }
  return nlohmann::json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string statusJson(StatusLevel level, const std::string& message) {
  return nlohmann::json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}
      .dump();
}

ClientOp parseClientOp(std::string_view text) {
  const nlohmann::json message = nlohmann::json::parse(text, nullptr, false);
  if (message.is_discarded() || !message.is_object()) {
    throw ProtocolError("not a JSON object");
  }
  const auto op = message.find("op");
  if (op == message.end() || !op->is_string()) {
    throw ProtocolError("no \"op\" string");
  }
  const std::string name = op->get<std::string>();
  if (name == "subscribe") {
    SubscribeOp subscribe;
    for (const nlohmann::json& entry : array(message, "subscriptions", name)) {
      if (!entry.is_object()) {
        throw ProtocolError("subscribe: each subscription must be an object");
      }
      subscribe.subscriptions.emplace_back(number<SubscriptionId>(entry, "id", name),
                                           number<ChannelId>(entry, "channelId", name));
    }
    return subscribe;
  }
  if (name == "unsubscribe") {
    UnsubscribeOp unsubscribe;
    for (const nlohmann::json& entry : array(message, "subscriptionIds", name)) {
      if (!entry.is_number_unsigned() ||
          entry.get<std::uint64_t>() > std::numeric_limits<SubscriptionId>::max()) {
        throw ProtocolError("unsubscribe: subscription ids must be non-negative integers");
      }
      unsubscribe.subscriptions.push_back(static_cast<SubscriptionId>(entry.get<std::uint64_t>()));
    }
    return unsubscribe;
  }
  return OtherOp{name};
}

}  // namespace comply::viewer
