// `comply echo`: a host's state and diagnostics, or its answers to committed requests, as text or
// JSON lines.

#include <iomanip>
#include <ostream>

#include "comply/transport/endpoints.hpp"
#include "live_json.hpp"
#include "send_command.hpp"

namespace comply::app {
namespace {

std::string vectorText(const auto& values) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(4) << "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    text << (i == 0 ? "" : " ") << values[i];
  }
  return text.str() + "]";
}

void printState(const transport::ControllerStateMessage& s, bool json, std::ostream& out) {
  if (json) {
    out << toJson(s).dump() << "\n";
    return;
  }
  out << "state " << toString(s.state) << " cycle " << s.cycle << " tcp "
      << vectorText(s.tcp_position) << " reference " << vectorText(s.reference_position)
      << " wrench " << vectorText(s.contact_wrench) << " q " << vectorText(s.position) << "\n";
}

void printDiagnostics(const transport::DiagnosticsMessage& d, bool json, std::ostream& out) {
  if (json) {
    out << toJson(d).dump() << "\n";
    return;
  }
  out << "diagnostics " << toString(d.state) << " cycles " << d.cycles << " overruns " << d.overruns
      << " received " << d.commands_received << " applied " << d.commands_applied << " rejected "
      << d.commands_rejected << " watchdog " << d.watchdog_timeouts << " faults " << d.faults
      << " publisher " << (d.publisher.empty() ? "-" : d.publisher) << "\n";
  for (const auto& outcome : d.outcomes) {
    out << "  " << outcomeLine(outcome) << "\n";
  }
}

/// Every answer to a committed request, any client's, until `count` (0: until interrupted).
int echoCommitted(const EchoOptions& options, std::ostream& out) {
  transport::Participant participant(participantOptions(options.client));
  transport::Reader<transport::CommittedMessage> committed(participant, options.client.name);
  std::vector<transport::Sample<transport::CommittedMessage>> answers;
  int printed = 0;
  while (options.count == 0 || printed < options.count) {
    committed.wait(0.5);
    answers.clear();
    committed.take(answers);
    for (const auto& sample : answers) {
      if (options.count == 0 || printed < options.count) {
        out << (options.json ? toJson(sample.message).dump() : committedLine(sample.message))
            << "\n";
        ++printed;
      }
    }
    out.flush();
  }
  return 0;
}

}  // namespace

int echoCommand(const EchoOptions& options, std::ostream& out, std::ostream& /*err*/) {
  if (options.topic == "committed") {
    return echoCommitted(options, out);
  }
  transport::Participant participant(participantOptions(options.client));
  transport::Reader<transport::ControllerStateMessage> state(participant, options.client.name);
  transport::Reader<transport::DiagnosticsMessage> diagnostics(participant, options.client.name);
  transport::WaitSet waitset(participant);
  const bool want_state = options.topic != "diagnostics";
  const bool want_diagnostics = options.topic != "state";
  waitset.attach(state);
  waitset.attach(diagnostics);
  std::vector<transport::Sample<transport::ControllerStateMessage>> states;
  std::vector<transport::Sample<transport::DiagnosticsMessage>> diagnosed;
  int printed = 0;
  while (options.count == 0 || printed < options.count) {
    waitset.wait(0.5);
    states.clear();
    diagnosed.clear();
    state.take(states);
    diagnostics.take(diagnosed);
    for (const auto& sample : states) {
      if (want_state && (options.count == 0 || printed < options.count)) {
        printState(sample.message, options.json, out);
        ++printed;
      }
    }
    for (const auto& sample : diagnosed) {
      if (want_diagnostics && (options.count == 0 || printed < options.count)) {
        printDiagnostics(sample.message, options.json, out);
        ++printed;
      }
    }
    out.flush();
  }
  return 0;
}

}  // namespace comply::app
