// JSON of the live messages (see live_json.hpp).

#include "live_json.hpp"

#include <cstdio>

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
  return std::string("rejected ") + stamp + ": " + std::string(toString(outcome.reason)) + ": " +
         outcome.message;
}

}  // namespace comply::app
