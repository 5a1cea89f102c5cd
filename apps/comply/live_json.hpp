#pragma once
// The live messages as JSON objects (`comply echo --json`), field names as in msg/*.msg.

#include <nlohmann/json.hpp>

#include "comply/transport/messages.hpp"

namespace comply::app {

nlohmann::json toJson(const transport::Stamp& stamp);
nlohmann::json toJson(const transport::ControllerStateMessage& state);
nlohmann::json toJson(const transport::CommandOutcomeMessage& outcome);
nlohmann::json toJson(const transport::DiagnosticsMessage& diagnostics);
/// The answer's fields, each entry of `cartesian` or `joint` its header and the command's keys.
nlohmann::json toJson(const transport::CommittedMessage& answer);

/// One line for a human: "applied 1700000000.000123456 by cycle 42" or "rejected ...: reason".
std::string outcomeLine(const transport::CommandOutcomeMessage& outcome);
/// "committed 1700000000.000123456 (<sender>): 16 times from 1700000000.1 to ..., position ..."
/// or "... refused: <why>".
std::string committedLine(const transport::CommittedMessage& answer);

}  // namespace comply::app
