// A UR controller's side of one RTDE connection (see rtde_server_session.hpp).

#include "comply/ur/rtde_server_session.hpp"

#include <algorithm>

namespace comply::ur {
namespace {

/// A setup's refusal: no recipe (id 0), no variable found, so that a client waiting for the
/// answer gets one and cannot use it.
std::vector<std::uint8_t> refusedSetup(PackageType type, std::size_t names) {
  return setupReply(type, {0, std::vector<std::string>(names, std::string(kNotFound))});
}

std::size_t namesIn(const Package& package) {
  try {
    return package.type == PackageType::kSetupOutputs
               ? readSetupOutputsRequest(package.payload).names.size()
               : readSetupInputsRequest(package.payload).size();
  } catch (const RtdeError&) {
    return 0;
  }
}

}  // namespace

RtdeServerSession::RtdeServerSession(ControllerVersion version, double max_frequency_hz)
    : version_(version), max_frequency_hz_(max_frequency_hz) {}

std::vector<std::uint8_t> RtdeServerSession::error(const std::string& message) {
  return textMessagePackage({message.substr(0, 255), "RTDE", TextLevel::kError});
}

std::vector<std::vector<std::uint8_t>> RtdeServerSession::handle(const Package& package) {
  const bool setup =
      package.type == PackageType::kSetupOutputs || package.type == PackageType::kSetupInputs;
  const bool control = package.type == PackageType::kStart || package.type == PackageType::kPause;
  try {
    switch (package.type) {
      case PackageType::kRequestProtocolVersion: {
        const bool accepted = readProtocolVersionRequest(package.payload) == kRtdeProtocolVersion;
        if (accepted) {
          protocol_version_ = kRtdeProtocolVersion;
        }
        return {acceptedReply(package.type, accepted)};
      }
      case PackageType::kGetUrControlVersion:
        return {controllerVersionReply(version_)};
      case PackageType::kTextMessage:
        readTextMessage(package.payload);  // a client's message: read, nothing to answer
        return {};
      default:
        break;
    }
    if (protocol_version_ == 0 && (setup || control || package.type == PackageType::kDataPackage)) {
      throw RtdeError("request protocol version 2 first: this controller speaks no other");
    }
    if (setup && started_) {
      throw RtdeError("recipes are set up while paused: pause first");
    }
    switch (package.type) {
      case PackageType::kSetupOutputs:
        return {setupOutputs(package)};
      case PackageType::kSetupInputs:
        return {setupInputs(package)};
      case PackageType::kStart:
        started_ = true;
        return {acceptedReply(package.type, true)};
      case PackageType::kPause:
        started_ = false;
        return {acceptedReply(package.type, true)};
      case PackageType::kDataPackage:
        takeInputs(package);
        return {};
      default:
        throw RtdeError("unknown package type " + std::to_string(static_cast<int>(package.type)));
    }
  } catch (const RtdeError& refusal) {
    // The reason, then the refusal a client waiting for an answer expects.
    std::vector<std::vector<std::uint8_t>> answers{error(refusal.what())};
    if (setup) {
      answers.push_back(refusedSetup(package.type, namesIn(package)));
    } else if (control) {
      answers.push_back(acceptedReply(package.type, false));
    }
    return answers;
  }
}

std::vector<std::uint8_t> RtdeServerSession::setupOutputs(const Package& package) {
  const SetupOutputsRequest request = readSetupOutputsRequest(package.payload);
  if (!(request.frequency_hz > 0.0 && request.frequency_hz <= max_frequency_hz_)) {
    throw RtdeError("an output frequency of " + std::to_string(request.frequency_hz) +
                    " Hz: this controller serves up to " + std::to_string(max_frequency_hz_));
  }
  const std::uint8_t id = next_recipe_id_++;
  const SetupReply reply = answerSetup(id, request.names, Direction::kOutput);
  output_.reset();
  if (std::find(reply.types.begin(), reply.types.end(), kNotFound) == reply.types.end()) {
    output_ =
        OutputRecipe{id, request.frequency_hz, request.names, recipeTypes(request.names, reply)};
  }
  return setupReply(package.type, reply);
}

std::vector<std::uint8_t> RtdeServerSession::setupInputs(const Package& package) {
  const std::vector<std::string> names = readSetupInputsRequest(package.payload);
  const std::uint8_t id = next_recipe_id_++;
  SetupReply reply = answerSetup(id, names, Direction::kInput);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (taken_elsewhere_.count(names[i]) != 0) {
      reply.types[i] = std::string(kInUse);
    }
    for (const auto& [other, recipe] : input_recipes_) {
      if (std::find(recipe.names.begin(), recipe.names.end(), names[i]) != recipe.names.end()) {
        reply.types[i] = std::string(kInUse);
      }
    }
  }
  const bool usable = std::none_of(reply.types.begin(), reply.types.end(), [](const auto& type) {
    return type == kNotFound || type == kInUse;
  });
  if (usable) {
    input_recipes_[id] = {names, recipeTypes(names, reply)};
  }
  return setupReply(package.type, reply);
}

std::set<std::string> RtdeServerSession::inputNames() const {
  std::set<std::string> names;
  for (const auto& [id, recipe] : input_recipes_) {
    names.insert(recipe.names.begin(), recipe.names.end());
  }
  return names;
}

void RtdeServerSession::takeInputs(const Package& package) {
  if (!started_) {
    throw RtdeError("a data package while paused: start first");
  }
  const std::uint8_t id = readRecipeId(package.payload);
  const auto recipe = input_recipes_.find(id);
  if (recipe == input_recipes_.end()) {
    throw RtdeError("a data package of recipe " + std::to_string(id) +
                    ", which is no input recipe of this connection");
  }
  const std::vector<RtdeValue> values = readData(package.payload, recipe->second.types);
  for (std::size_t i = 0; i < values.size(); ++i) {
    inputs_[recipe->second.names[i]] = values[i];
  }
}

std::vector<std::uint8_t> RtdeServerSession::outputPackage(
    std::span<const RtdeValue> values) const {
  if (!output_) {
    throw RtdeError("no output recipe to send");
  }
  if (values.size() != output_->types.size()) {
    throw RtdeError("an output package of " + std::to_string(values.size()) +
                    " values for a recipe of " + std::to_string(output_->types.size()));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (typeOf(values[i]) != output_->types[i]) {
      throw RtdeError("output " + output_->names[i] + " is a " +
                      std::string(nameIn(kRtdeTypeNames, output_->types[i])) + ", not a " +
                      std::string(nameIn(kRtdeTypeNames, typeOf(values[i]))));
    }
  }
  return dataPackage(output_->id, values);
}

}  // namespace comply::ur
