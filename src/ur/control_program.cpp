// comply's URScript control program, written and read back (see control_program.hpp).

#include "comply/ur/control_program.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace comply::ur {
namespace {

// A program sent to the controller starts with `def` and ends with `end`, both in column 0; the
// marker is the first line inside it.
constexpr std::string_view kHead = "def comply_control():\n  # comply control program, version 1\n";

std::string number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

constexpr double kMaxInstance = 2147483646.0;

void check(bool holds, const std::string& what) {
  if (!holds) {
    throw ControlProgramError("UR control program: " + what);
  }
}

void checkRanges(const ControlProgram& program) {
  check(program.instance >= 1 && program.instance <= kMaxInstance,
        "instance " + std::to_string(program.instance) + " is not in [1, 2^31 - 1)");
  check(program.mode != OutputMode::kJointPd,
        "a UR controller has no per-joint PD command; output.mode must be position (servoj), "
        "velocity (speedj) or torque (direct_torque)");
  check(std::isfinite(program.period_s) && program.period_s > 0.0 && program.period_s <= 0.1,
        "period_s " + number(program.period_s) + " is not in (0, 0.1] s");
  check(program.register_offset >= 0 && program.register_offset + 5 <= 47,
        "registers " + std::to_string(program.register_offset) + " to " +
            std::to_string(program.register_offset + 5) + " are not within 0 to 47");
  check(std::isfinite(program.watchdog_s) && program.watchdog_s >= 2.0 * program.period_s,
        "watchdog_s " + number(program.watchdog_s) + " is shorter than two controller cycles");
  check(program.servoj_lookahead_s >= 0.03 && program.servoj_lookahead_s <= 0.2,
        "servoj lookahead " + number(program.servoj_lookahead_s) + " s is not in [0.03, 0.2]");
  check(program.servoj_gain >= 100.0 && program.servoj_gain <= 2000.0,
        "servoj gain " + number(program.servoj_gain) + " is not in [100, 2000]");
  check(std::isfinite(program.speedj_acceleration_rad_per_s2) &&
            program.speedj_acceleration_rad_per_s2 > 0.0,
        "speedj acceleration must be positive");
  check(std::isfinite(program.stop_deceleration_rad_per_s2) &&
            program.stop_deceleration_rad_per_s2 > 0.0,
        "stop deceleration must be positive");
}

/// The six doubles' registers read into a list, URScript.
std::string targetList(int offset) {
  std::string list = "[";
  for (int joint = 0; joint < 6; ++joint) {
    list += (joint > 0 ? ", " : "") + std::string("read_input_float_register(") +
            std::to_string(offset + joint) + ")";
  }
  return list + "]";
}

std::string driveLine(const ControlProgram& program) {
  switch (program.mode) {
    case OutputMode::kPosition:
      // servoj(q, a, v, t, lookahead_time, gain): a and v are not used by servoj.
      return "servoj(target, 0, 0, COMPLY_PERIOD, COMPLY_LOOKAHEAD, COMPLY_GAIN)";
    case OutputMode::kVelocity:
      return "speedj(target, COMPLY_ACCELERATION, COMPLY_PERIOD)";
    default:
      // Returns at once: the cycle ends at sync().
      return "direct_torque(target, friction_comp=True)\n      sync()";
  }
}

/// The value of the line `  NAME = value` in `script`.
double constant(std::string_view script, std::string_view name) {
  const std::string key = std::string(name) + " = ";
  const std::size_t at = script.find(key);
  check(at != std::string_view::npos, "no " + std::string(name) + " in the program");
  const char* begin = script.data() + at + key.size();
  const char* end = script.data() + script.size();
  std::size_t line_end = script.find('\n', at);
  if (line_end != std::string_view::npos) {
    end = script.data() + line_end;
  }
  double value = 0.0;
  const auto [ptr, error] = std::from_chars(begin, end, value);
  check(error == std::errc() && ptr == end,
        std::string(name) + " = '" + std::string(begin, end) + "' is not a number");
  return value;
}

/// A constant that must be a whole number in [least, most] (read from the network: checked
/// before it is converted).
double wholeNumber(std::string_view script, std::string_view name, double least, double most) {
  const double value = constant(script, name);
  check(value >= least && value <= most && value == std::floor(value),
        std::string(name) + " = " + number(value) + " is not a whole number in [" + number(least) +
            ", " + number(most) + "]");
  return value;
}

}  // namespace

std::string_view driveCommand(OutputMode mode) {
  switch (mode) {
    case OutputMode::kPosition:
      return "servoj";
    case OutputMode::kVelocity:
      return "speedj";
    case OutputMode::kTorque:
      return "direct_torque";
    default:
      return "";
  }
}

std::string controlProgramScript(const ControlProgram& program) {
  checkRanges(program);
  const int o = program.register_offset;
  const std::string cycle_in = "read_input_integer_register(" + std::to_string(o) + ")";
  const std::string drive_in = "read_input_integer_register(" + std::to_string(o + 1) + ")";
  std::ostringstream s;
  s << kHead << "  COMPLY_DRIVE = \"" << driveCommand(program.mode) << "\"\n"
    << "  COMPLY_INSTANCE = " << program.instance << "\n"
    << "  COMPLY_MODE = " << static_cast<int>(program.mode) << "\n"
    << "  COMPLY_PERIOD = " << number(program.period_s) << "\n"
    << "  COMPLY_REGISTER = " << o << "\n"
    << "  COMPLY_WATCHDOG = " << number(program.watchdog_s) << "\n"
    << "  COMPLY_LOOKAHEAD = " << number(program.servoj_lookahead_s) << "\n"
    << "  COMPLY_GAIN = " << number(program.servoj_gain) << "\n"
    << "  COMPLY_ACCELERATION = " << number(program.speedj_acceleration_rad_per_s2) << "\n"
    << "  COMPLY_DECELERATION = " << number(program.stop_deceleration_rad_per_s2) << "\n"
    << "  write_output_integer_register(" << o + 1 << ", COMPLY_INSTANCE)\n"
    << "  textmsg(\"comply: control program started with \", COMPLY_DRIVE)\n"
    << "  last_cycle = " << cycle_in << "\n"
    << "  armed = False\n"
    << "  quiet = 0.0\n"
    << "  while True:\n"
    << "    cycle = " << cycle_in << "\n"
    << "    if cycle != last_cycle:\n"
    << "      last_cycle = cycle\n"
    << "      armed = True\n"
    << "      quiet = 0.0\n"
    << "    else:\n"
    << "      quiet = quiet + COMPLY_PERIOD\n"
    << "    end\n"
    << "    if armed and quiet > COMPLY_WATCHDOG:\n"
    << "      write_output_integer_register(" << o + 1 << ", -COMPLY_INSTANCE)\n"
    << "      textmsg(\"comply: no command within the watchdog: \", \"the arm stops\")\n"
    << "      stopj(COMPLY_DECELERATION)\n"
    << "      halt\n"
    << "    end\n"
    << "    write_output_integer_register(" << o << ", cycle)\n"
    << "    if " << drive_in << " == 1:\n"
    << "      target = " << targetList(o) << "\n"
    << "      " << driveLine(program) << "\n"
    << "    else:\n"
    << "      stopj(COMPLY_DECELERATION)\n"
    << "      sync()\n"
    << "    end\n"
    << "  end\n"
    << "end\n";
  return s.str();
}

ControlProgram readControlProgram(std::string_view script) {
  check(script.starts_with(kHead), "the text does not start with comply's '" +
                                       std::string(kHead.substr(0, kHead.find('\n'))) +
                                       "' and its marker: not comply's control program");
  std::string_view trimmed = script;
  while (!trimmed.empty() && (trimmed.back() == '\n' || trimmed.back() == ' ')) {
    trimmed.remove_suffix(1);
  }
  check(trimmed.ends_with("\nend"), "the program does not end with 'end' in column 0");
  ControlProgram program;
  const double mode = constant(script, "COMPLY_MODE");
  check(mode == 0.0 || mode == 2.0 || mode == 3.0,
        "COMPLY_MODE " + number(mode) + " is not torque (0), position (2) or velocity (3)");
  program.mode = static_cast<OutputMode>(static_cast<int>(mode));
  program.period_s = constant(script, "COMPLY_PERIOD");
  program.instance =
      static_cast<std::int32_t>(wholeNumber(script, "COMPLY_INSTANCE", 1, kMaxInstance));
  program.register_offset = static_cast<int>(wholeNumber(script, "COMPLY_REGISTER", 0, 47));
  program.watchdog_s = constant(script, "COMPLY_WATCHDOG");
  program.servoj_lookahead_s = constant(script, "COMPLY_LOOKAHEAD");
  program.servoj_gain = constant(script, "COMPLY_GAIN");
  program.speedj_acceleration_rad_per_s2 = constant(script, "COMPLY_ACCELERATION");
  program.stop_deceleration_rad_per_s2 = constant(script, "COMPLY_DECELERATION");
  checkRanges(program);
  check(script.find(std::string(driveCommand(program.mode)) + "(") != std::string_view::npos,
        "the program does not call " + std::string(driveCommand(program.mode)));
  return program;
}

}  // namespace comply::ur
