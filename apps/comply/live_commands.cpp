// The command-line options of `comply run`, `send` and `echo`.

#include "live_commands.hpp"

#include "cli_options.hpp"
#include "run_command.hpp"
#include "send_command.hpp"

namespace comply::app {
namespace {

void addClientOptions(CLI::App* command, ClientOptions& client) {
  command->add_option("--domain", client.domain_id, "DDS domain id (ROS_DOMAIN_ID)")
      ->capture_default_str()
      ->check(CLI::Range(0, 232));
  command
      ->add_option("--network", client.network,
                   "loopback (DDS traffic on 127.0.0.1 only; docs/live-control.md) or all")
      ->capture_default_str()
      ->check(CLI::IsMember({"loopback", "all"}));
  command->add_option("--name", client.name, "the host's name: topics /<name>/...")
      ->capture_default_str();
  command->add_option("--timeout", client.timeout_s, "seconds to find the host / an outcome")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--security", client.security,
                      "DDS Security: this client's enclave folder of a keystore "
                      "(scripts/create-keystore.sh; docs/live-control.md)");
}

CLI::App* addRunCommand(CLI::App& app, RunOptions* run) {
  CLI::App* run_command = app.add_subcommand(
      "run", "the controller host: live commands over DDS (ROS 2 topics), state and diagnostics");
  run_command->add_option("--config", run->config_file, "controller YAML")->required();
  run_command->add_option("--robot", run->robot, "robot name or folder (overrides the config's)");
  run_command->add_flag("--sim", run->sim, "a simulated arm (MuJoCo): --hardware sim");
  run_command
      ->add_option("--hardware", run->hardware,
                   "the robot: a built-in backend (sim; ur: docs/ur.md; franka: docs/franka.md), a "
                   "backend library (.so), "
                   "or NAME for "
                   "libcomply_hardware_NAME.so on the plugin path")
      ->capture_default_str();
  run_command->add_option("--hardware-option", run->hardware_options,
                          "key=value for the hardware backend (repeatable)");
  run_command
      ->add_option("--transport", run->transport,
                   "dds (ROS 2 wire, in a process of its own), dds_inline (in this process) or "
                   "in_process")
      ->capture_default_str();
  run_command->add_flag("--view", run->view, "interactive window (not yet)");
  run_command->add_option("--rate", run->rate_hz, "control rate [Hz]")
      ->capture_default_str()
      ->check(finiteIn(1.0, 10000.0));
  run_command->add_option("--state-rate", run->state_rate_hz, "state topic rate [Hz]")
      ->capture_default_str()
      ->check(finiteIn(0.1, 10000.0));
  run_command->add_option("--duration", run->duration_s, "stop after this many seconds (0: never)")
      ->check(finiteIn(0.0, 1e7));
  run_command->add_option("--domain", run->domain_id, "DDS domain id")
      ->capture_default_str()
      ->check(CLI::Range(0, 232));
  run_command
      ->add_option("--network", run->network,
                   "loopback (DDS traffic on 127.0.0.1 only; docs/live-control.md) or all")
      ->capture_default_str()
      ->check(CLI::IsMember({"loopback", "all"}));
  run_command->add_option("--name", run->name, "topics /<name>/...")->capture_default_str();
  run_command->add_option("--security", run->security,
                          "DDS Security: the host's enclave folder of a keystore "
                          "(scripts/create-keystore.sh; docs/live-control.md)");
  run_command->add_option("--priority", run->priority, "SCHED_FIFO priority (0: normal)")
      ->capture_default_str()
      ->check(CLI::Range(0, 99));
  run_command
      ->add_option("--warm-ahead-us", run->warm_ahead_us,
                   "wake this long before each cycle to warm its caches and spin to the start "
                   "(0: sleep to the start; docs/timing.md)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 500.0));
  run_command->add_option("--record", run->record_path,
                          "record every cycle, command and outcome to this MCAP file (its folder "
                          "must exist)");
  run_command->add_option("--foxglove", run->foxglove,
                          "serve a Foxglove live view on [ADDRESS:]PORT (ADDRESS default "
                          "127.0.0.1; Foxglove's port is 8765; docs/live-view.md)");
  return run_command;
}

CLI::App* addSendCommand(CLI::App& app, SendOptions* send) {
  CLI::App* send_command = app.add_subcommand("send", "send a command (or a stream) to a host");
  addClientOptions(send_command, send->client);
  send_command->add_option("--json", send->json, "one command as a JSON object");
  send_command->add_option("--file", send->file,
                           "a command (JSON/YAML object), or a stream (a list, or JSON lines)");
  send_command->add_option("--kind", send->kind, "cartesian or joint (default: the host's)")
      ->check(CLI::IsMember({"cartesian", "joint"}));
  send_command->add_option("--rate", send->rate_hz, "stream rate [Hz] (default 100)")
      ->check(CLI::PositiveNumber);
  send_command
      ->add_option("--request", send->request,
                   "activate, deactivate, reset (leave FAULT) or tare (the wrist sensor's zero)")
      ->check(CLI::IsMember(namesIn(transport::kRequestTypeNames)));
  send_command->add_flag("--no-wait", send->no_wait, "do not wait for the outcomes");
  return send_command;
}

CLI::App* addEchoCommand(CLI::App& app, EchoOptions* echo) {
  CLI::App* echo_command =
      app.add_subcommand("echo", "print a host's state, diagnostics or committed answers");
  addClientOptions(echo_command, echo->client);
  echo_command
      ->add_option("topic", echo->topic,
                   "state, diagnostics, both, or committed (the answers to committed requests)")
      ->capture_default_str()
      ->check(CLI::IsMember({"state", "diagnostics", "both", "committed"}));
  echo_command->add_flag("--json", echo->json, "one JSON object per line");
  echo_command->add_option("--count", echo->count, "stop after this many messages")
      ->check(CLI::NonNegativeNumber);
  return echo_command;
}

}  // namespace

LiveCommands addLiveCommands(CLI::App& app) {
  // The options outlive this call: the parsed values are read when the command runs.
  auto run = std::make_shared<RunOptions>();
  auto send = std::make_shared<SendOptions>();
  auto echo = std::make_shared<EchoOptions>();
  CLI::App* run_command = addRunCommand(app, run.get());
  CLI::App* send_command = addSendCommand(app, send.get());
  CLI::App* echo_command = addEchoCommand(app, echo.get());

  LiveCommands commands;
  commands.parsed = [=] {
    return run_command->parsed() || send_command->parsed() || echo_command->parsed();
  };
  commands.run = [=](std::ostream& out, std::ostream& err) {
    if (run_command->parsed()) {
      return runCommand(*run, out, err);
    }
    if (send_command->parsed()) {
      return sendCommand(*send, out, err);
    }
    return echoCommand(*echo, out, err);
  };
  return commands;
}

}  // namespace comply::app
