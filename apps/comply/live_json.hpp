#pragma once
// The live messages as JSON objects (`comply echo --json`), field names as in msg/*.msg.

#include <nlohmann/json.hpp>

#include "comply/transport/messages.hpp"

namespace comply::app {

nlohmann::json toJson(const transport::Stamp& stamp);
nlohmann::json toJson(const transport::ControllerStateMessage& state);
nlohmann::json toJson(const transport::CommandOutcomeMessage& outcome);
nlohmann::json toJson(const transport::DiagnosticsMessage& diagnostics);

/// One line for a human: "applied 1700000000.000123456 by cycle 42" or "rejected ...: reason".
std::string outcomeLine(const transport::CommandOutcomeMessage& outcome);

}  // namespace comply::app
