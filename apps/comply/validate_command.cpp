#include "validate_command.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <vector>

#include "comply/core/text_file.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/command_bus.hpp"
#include "comply/pipeline/plugin_input.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/schema/json.hpp"
#include "comply/schema/schema.hpp"
#include "validate_wrapper.hpp"

namespace comply::app {
namespace {

using nlohmann::json;

constexpr model::Quantity kAllModelQuantities =
    model::Quantity::kPose | model::Quantity::kJacobian | model::Quantity::kGravity |
    model::Quantity::kCoriolis | model::Quantity::kMassMatrix;

const std::set<std::string> kOutputKeys{"tcp_position", "tcp_orientation", "jacobian",
                                        "gravity",      "coriolis",        "mass_matrix",
                                        "torque",       "wrapper_torque"};

json readJsonFile(const std::string& path) {
  const TextFile file = readTextFile(path);
  if (!file.ok()) {
    throw InputError(InputErrc::kCannotRead, "", "", file.error);
  }
  try {
    return schema::parseJson(file.text, path);
  } catch (const json::parse_error& error) {
    throw InputError(InputErrc::kSyntax, "", "",
                     "'" + path + "' is not valid JSON: " + error.what());
  }
}

/// The sample list of an inputs/outputs document: a top-level list or {"samples": [...]}.
const json& samplesOf(const json& document, const std::string& path) {
  const json& samples =
      document.is_object() && document.contains("samples") ? document.at("samples") : document;
  if (!samples.is_array()) {
    throw InputError(InputErrc::kWrongType, "", "",
                     "'" + path + "' must hold a list of samples or {\"samples\": [...]}");
  }
  if (samples.size() > kMaxValidateSamples) {
    throw InputError(InputErrc::kWrongSize, "", "",
                     "'" + path + "' holds " + std::to_string(samples.size()) +
                         " samples, more than " + std::to_string(kMaxValidateSamples) +
                         " (split it)");
  }
  return samples;
}

JointVector jointVector(const json& sample, const std::string& key, int dof,
                        const std::string& where) {
  std::vector<double> values;
  try {
    values = sample.at(key).get<std::vector<double>>();
  } catch (const json::exception&) {
    throw InputError(InputErrc::kWrongType, "", "",
                     where + ": '" + key + "' must be a list of numbers");
  }
  if (static_cast<int>(values.size()) != dof) {
    throw InputError(InputErrc::kWrongSize, "", "",
                     where + ": '" + key + "' has " + std::to_string(values.size()) +
                         " entries, the robot has " + std::to_string(dof) + " joints");
  }
  JointVector result(dof);
  for (int i = 0; i < dof; ++i) {
    result[i] = values[static_cast<std::size_t>(i)];
  }
  return result;
}

std::vector<ValidateSample> readSamples(const std::string& path, int dof) {
  const json document = readJsonFile(path);
  std::vector<ValidateSample> samples;
  int index = 0;
  for (const json& entry : samplesOf(document, path)) {
    const std::string where = path + ": sample " + std::to_string(index++);
    if (!entry.is_object()) {
      throw InputError(InputErrc::kWrongType, "", "", where + " must be an object");
    }
    for (const auto& [key, value] : entry.items()) {
      if (key != "q" && key != "dq" && key != "effort" && key != "command") {
        throw InputError(InputErrc::kUnknownKey, "", "",
                         where + ": unknown field '" + key + "' (known: q, dq, effort, command)");
      }
    }
    for (const char* required : {"q", "dq"}) {
      if (!entry.contains(required)) {
        throw InputError(InputErrc::kMissingKey, "", "",
                         where + ": missing field '" + std::string(required) + "'");
      }
    }
    ValidateSample sample;
    sample.state.position = jointVector(entry, "q", dof, where);
    sample.state.velocity = jointVector(entry, "dq", dof, where);
    sample.has_effort = entry.contains("effort");
    sample.state.effort =
        sample.has_effort ? jointVector(entry, "effort", dof, where) : JointVector::Zero(dof);
    if (entry.contains("command")) {
      sample.command = entry.at("command");
    }
    samples.push_back(std::move(sample));
  }
  if (samples.empty()) {
    throw InputError(InputErrc::kWrongSize, "", "", "'" + path + "' holds no samples");
  }
  return samples;
}

json toJson(const JointVector& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

json rowsOf(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  json rows = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    std::vector<double> row(static_cast<std::size_t>(m.cols()));
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      row[static_cast<std::size_t>(c)] = m(r, c);
    }
    rows.push_back(row);
  }
  return rows;
}

template <typename Command>
const Command& initialCommand(const pipeline::WrapperConfig& config);
template <>
const JointCommand& initialCommand<JointCommand>(const pipeline::WrapperConfig& config) {
  return config.initial_joint;
}
template <>
const CartesianCommand& initialCommand<CartesianCommand>(const pipeline::WrapperConfig& config) {
  return config.initial_cartesian;
}

/// Model quantities and the law's torque, each sample on its own: the reference not given by the
/// command is the measured pose (as on activation), gains not given are the configured initial
/// ones.
template <typename Command>
void runLaw(const pipeline::ResolvedController& resolved,
            const std::vector<ValidateSample>& samples, const std::string& inputs_path,
            json& outputs) {
  const pipeline::WrapperConfig& config = resolved.config;
  const model::Model& model = *resolved.model;
  model::Data data(model);
  const int dof = resolved.dof;
  plugin::PluginInstance law(resolved.plugin, dof, config.plugin_parameters);

  for (std::size_t i = 0; i < samples.size(); ++i) {
    const ValidateSample& sample = samples[i];
    const std::string where = inputs_path + ": sample " + std::to_string(i);
    json& out = outputs[i];
    const auto q = std::span<const double>(sample.state.position.data(), dof);
    const auto dq = std::span<const double>(sample.state.velocity.data(), dof);
    if (model::update(model, data, q, dq, kAllModelQuantities) != model::UpdateStatus::kOk) {
      throw InputError(InputErrc::kOutOfRange, "", "", where + ": q or dq holds NaN or infinity");
    }
    out["tcp_position"] = {data.tip_position.x(), data.tip_position.y(), data.tip_position.z()};
    out["tcp_orientation"] = {data.tip_orientation.x(), data.tip_orientation.y(),
                              data.tip_orientation.z(), data.tip_orientation.w()};
    out["jacobian"] = rowsOf(data.jacobian);
    out["gravity"] = toJson(data.gravity);
    out["coriolis"] = toJson(data.coriolis);
    out["mass_matrix"] = rowsOf(data.mass_matrix);

    Command merged = initialCommand<Command>(config);
    const MeasuredPose pose = pipeline::measuredPoseFrom(sample.state.position, data);
    schema::seedReference(merged, pose);
    const Command incoming = parseSampleCommand(sample.command, dof, merged, where);
    const pipeline::Verdict verdict =
        pipeline::validateAndMerge(incoming, config.validation, dof, pose, merged);
    if (!verdict.accepted) {
      out["law_error"] = "command rejected: " + verdict.message;
      continue;
    }
    comply_input input{};
    pipeline::fillPluginInput(sample.state, data, kAllModelQuantities, 0.0, 0.001, input);
    const auto bus = pipeline::toBus(merged, dof);
    comply_output output{};
    if (law.step(input, &bus, output) != COMPLY_OK) {
      out["law_error"] = std::string("step failed: ") + output.message;
      continue;
    }
    out["torque"] = std::vector<double>(output.torque, output.torque + dof);
  }
}

std::vector<double> flatten(const json& value, const std::string& where) {
  std::vector<double> flat;
  if (value.is_number()) {
    return {value.get<double>()};
  }
  if (!value.is_array()) {
    throw InputError(InputErrc::kWrongType, "", "", where + " must be a number or a list");
  }
  for (const json& entry : value) {
    const std::vector<double> inner = flatten(entry, where);
    flat.insert(flat.end(), inner.begin(), inner.end());
  }
  return flat;
}

}  // namespace

json runValidation(const ValidateOptions& options) {
  const pipeline::WrapperConfig config =
      host::controllerConfig(options.robot, options.plugin, options.config_file);
  const auto resolved = pipeline::resolveController(config);  // the plugin decides the kind
  const bool cartesian = resolved->cartesian();
  const std::vector<ValidateSample> samples = readSamples(options.inputs, config.dof);

  json document;
  document["robot"] = config.robot;
  document["plugin"] = config.plugin;
  document["joints"] = config.joints;
  document["base_frame"] = config.base_frame;
  document["tip_frame"] = config.tip_frame;
  json outputs = json::array();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    outputs.push_back(json::object());
  }
  if (cartesian) {
    runLaw<CartesianCommand>(*resolved, samples, options.inputs, outputs);
  } else {
    runLaw<JointCommand>(*resolved, samples, options.inputs, outputs);
  }
  if (options.wrapper) {
    runWrapper(resolved, samples, options.period_s, options.inputs, outputs);
  }
  document["samples"] = outputs;
  return document;
}

std::map<std::string, double> compareOutputs(const json& actual, const json& expected) {
  const json& actual_samples = samplesOf(actual, "output");
  const json& expected_samples = samplesOf(expected, "expected");
  if (actual_samples.size() != expected_samples.size()) {
    throw InputError(InputErrc::kInconsistent, "", "",
                     "expected file has " + std::to_string(expected_samples.size()) +
                         " samples, the inputs " + std::to_string(actual_samples.size()));
  }
  std::map<std::string, double> max_error;
  for (std::size_t i = 0; i < expected_samples.size(); ++i) {
    const std::string where = "expected sample " + std::to_string(i);
    for (const auto& [key, value] : expected_samples[i].items()) {
      if (kOutputKeys.count(key) == 0) {
        if (value.is_string()) {
          continue;  // status texts (law_error, wrapper_state, ...) are not compared
        }
        std::string known;
        for (const std::string& name : kOutputKeys) {
          known += (known.empty() ? "" : ", ") + name;
        }
        throw InputError(InputErrc::kUnknownKey, "", "",
                         where + ": unknown output '" + key + "' (known: " + known + ")");
      }
      if (!actual_samples[i].contains(key)) {
        throw InputError(InputErrc::kInconsistent, "", "",
                         where + ": '" + key + "' was not produced for this sample" +
                             (key == "wrapper_torque" ? " (run with --wrapper)" : ""));
      }
      const std::vector<double> want = flatten(value, where + "." + key);
      const std::vector<double> got = flatten(actual_samples[i].at(key), key);
      if (want.size() != got.size()) {
        throw InputError(InputErrc::kInconsistent, "", "",
                         where + ": '" + key + "' has " + std::to_string(want.size()) +
                             " numbers, the output " + std::to_string(got.size()));
      }
      double error = 0.0;
      double error_flipped = 0.0;  // q and -q are the same orientation
      for (std::size_t k = 0; k < want.size(); ++k) {
        // A non-finite number on either side is a mismatch: std::max would drop a NaN error.
        const bool finite = std::isfinite(got[k]) && std::isfinite(want[k]);
        constexpr double kMismatch = std::numeric_limits<double>::infinity();
        error = std::max(error, finite ? std::abs(got[k] - want[k]) : kMismatch);
        error_flipped = std::max(error_flipped, finite ? std::abs(got[k] + want[k]) : kMismatch);
      }
      if (key == "tcp_orientation") {
        error = std::min(error, error_flipped);
      }
      max_error[key] = std::max(max_error[key], error);
    }
  }
  return max_error;
}

int validateCommand(const ValidateOptions& options, std::ostream& out, std::ostream& err) {
  const json document = runValidation(options);
  if (!options.out.empty()) {
    std::ofstream file(options.out);
    if (!(file << document.dump(2) << "\n")) {
      throw std::runtime_error("cannot write '" + options.out + "'");
    }
    err << "validate: " << document.at("samples").size() << " samples written to " << options.out
        << "\n";
  } else if (options.expected.empty()) {
    out << document.dump(2) << "\n";
  }
  if (options.expected.empty()) {
    return 0;
  }
  const std::map<std::string, double> errors =
      compareOutputs(document, readJsonFile(options.expected));
  bool within = true;
  out << std::left << std::setw(18) << "output" << std::right << std::setw(14) << "max |error|"
      << "  (tolerance " << options.tolerance << ")\n";
  for (const auto& [key, error] : errors) {
    const bool ok = error <= options.tolerance;
    within = within && ok;
    out << std::left << std::setw(18) << key << std::right << std::setw(14);
    if (std::isfinite(error)) {
      out << std::scientific << std::setprecision(3) << error;
    } else {
      out << "non-finite";
    }
    out << (ok ? "  ok" : "  ABOVE TOLERANCE") << "\n";
  }
  out << (within ? "validate: all outputs within tolerance\n"
                 : "validate: outputs above tolerance\n");
  return within ? 0 : 1;
}

}  // namespace comply::app
