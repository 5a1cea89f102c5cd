// JSON of the live messages (see live_json.hpp).

#include "live_json.hpp"

#include <cstdio>
#include <iomanip>
#include <sstream>

#include "comply/schema/json.hpp"
#include "comply/transport/message_json.hpp"

namespace comply::app {

nlohmann::json toJson(const transport::Stamp& stamp) {
  return transport::fieldJson(stamp);
}

nlohmann::json toJson(const transport::ControllerStateMessage& s) {
  return transport::messageJson(s);
}

nlohmann::json toJson(const transport::CommandOutcomeMessage& o) {
  return transport::messageJson(o);
}

nlohmann::json toJson(const transport::DiagnosticsMessage& d) {
  nlohmann::json json = transport::messageJson(d);
  // Refused commands per reason by the reason's name, not its number.
  nlohmann::json rejections = nlohmann::json::object();
  for (std::size_t i = 0; i < d.rejections.size(); ++i) {
    rejections[std::string(toString(static_cast<transport::Reason>(i)))] = d.rejections[i];
  }
  json["rejections"] = rejections;
  return json;
}

namespace {

template <typename CommandMessage>
nlohmann::json entriesJson(const std::vector<CommandMessage>& entries) {
  nlohmann::json list = nlohmann::json::array();
  for (const CommandMessage& entry : entries) {
    nlohmann::json object = schema::toJson(entry.command);
    object["header"] = transport::fieldJson(entry.header);
    list.push_back(std::move(object));
  }
  return list;
}

std::string stampText(const transport::Stamp& stamp) {
  char text[32];
  std::snprintf(text, sizeof(text), "%d.%09u", stamp.sec, stamp.nanosec);
  return text;
}

}  // namespace

nlohmann::json toJson(const transport::CommittedMessage& a) {
  return {{"header", transport::fieldJson(a.header)},
          {"request_stamp", transport::fieldJson(a.request_stamp)},
          {"sender", transport::toHex(a.sender)},
          {"command_kind", std::string(toString(a.command_kind))},
          {"answered", a.answered},
          {"known", a.known},
          {"message", a.message},
          {"cartesian", entriesJson(a.cartesian)},
          {"joint", entriesJson(a.joint)}};
}

std::string committedLine(const transport::CommittedMessage& a) {
  std::ostringstream line;
  line << "committed " << stampText(a.request_stamp) << " (" << transport::toHex(a.sender) << ")";
  if (!a.answered) {
    line << " refused: " << a.message;
    return line.str();
  }
  const auto describe = [&](const auto& entries, const auto& position) {
    line << ": " << entries.size() << " times";
    if (!entries.empty()) {
      line << " from " << stampText(entries.front().header.stamp) << " to "
           << stampText(entries.back().header.stamp) << std::fixed << std::setprecision(4)
           << ", position " << position(entries.front()).transpose() << " to "
           << position(entries.back()).transpose();
    }
  };
  const auto position = [](const auto& entry) { return entry.command.position; };
  if (a.command_kind == transport::WireCommandKind::kJoint) {
    describe(a.joint, position);
  } else {
    describe(a.cartesian, position);
  }
  line << (a.known ? "" : " (not all known)");
  return line.str();
}

std::string outcomeLine(const transport::CommandOutcomeMessage& outcome) {
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "%d.%09u", outcome.stamp.sec, outcome.stamp.nanosec);
  const bool applied = outcome.outcome == transport::Outcome::kApplied;
  if (outcome.command_kind == transport::WireCommandKind::kRequest) {
    // A request is carried out by the host, not by a cycle; one it could not carry out has no
    // reason of the command rules, only why.
    if (applied) {
      return std::string("request carried out ") + stamp;
    }
    const std::string reason = outcome.reason == transport::Reason::kNone
                                   ? std::string()
                                   : std::string(toString(outcome.reason)) + ": ";
    return std::string("request refused ") + stamp + ": " + reason + outcome.message;
  }
  if (applied) {
    return std::string("applied ") + stamp + " by cycle " + std::to_string(outcome.cycle);
  }
  // The wrapper's own messages begin with their reason already; the gate's do not.
  const std::string reason = std::string(toString(outcome.reason)) + ": ";
  const bool named = outcome.message.starts_with(reason);
  return std::string("rejected ") + stamp + ": " + (named ? "" : reason) + outcome.message;
}

}  // namespace comply::app
