#include "comply/codegen/plugin.hpp"

#include <cctype>
#include <stdexcept>

namespace comply::codegen {
namespace {

// The name the templates are written with (so they compile and format as they are); replaced by
// the plugin's name, and its CamelCase form for the C++ class.
constexpr std::string_view kTemplateName = "my_law";
constexpr std::string_view kTemplateClass = "MyLaw";
// The same for the hardware backend's templates.
constexpr std::string_view kHardwareTemplateName = "my_arm";
constexpr std::string_view kHardwareTemplateClass = "MyArm";

/// `name` in CamelCase; `prefix` goes in front when that would not start with a letter.
std::string camelCase(std::string_view name, std::string_view prefix) {
  std::string result;
  bool upper = true;
  for (const char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    result += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  // A name of underscores only, or one that starts with a digit after them, needs a prefix.
  if (result.empty() || std::isdigit(static_cast<unsigned char>(result.front())) != 0) {
    result = std::string(prefix) + result;
  }
  return result;
}

std::string instantiate(std::string_view path, const PluginSpec& spec) {
  const bool joint = spec.kind == "joint";
  const bool cpp = spec.language == "cpp";
  std::string text(embeddedTemplate(path));
  // Both C laws start alike; their templates name the common part rather than repeat it.
  text = replaceAll(std::move(text), "/* COMPLY_TEMPLATE_C_LIFECYCLE */\n",
                    embeddedTemplate("plugin/c_lifecycle.c"));
  text = replaceAll(std::move(text), "COMPLY_TEMPLATE_LANGUAGES", cpp ? "C CXX" : "C");
  text = replaceAll(std::move(text), "COMPLY_TEMPLATE_SOURCE",
                    std::string(kTemplateName) + (cpp ? ".cpp" : ".c"));
  text = replaceAll(std::move(text), "COMPLY_TEMPLATE_KIND_NAME", joint ? "joint" : "Cartesian");
  text = replaceAll(std::move(text), "COMPLY_TEMPLATE_KIND",
                    joint ? "COMPLY_COMMAND_JOINT" : "COMPLY_COMMAND_CARTESIAN");
  text = replaceAll(std::move(text), "COMPLY_TEMPLATE_LANGUAGE_NAME",
                    cpp ? "C++ (through the SDK)" : "C (against abi.h alone)");
  text = replaceAll(std::move(text), kTemplateClass, camelCase(spec.name, "Law"));
  return replaceAll(std::move(text), kTemplateName, spec.name);
}

/// A hardware backend's project: one C++ class, so neither kind nor language varies its files.
std::vector<GeneratedFile> hardwareFiles(const PluginSpec& spec) {
  const auto instantiateHardware = [&](std::string_view from) {
    std::string text(embeddedTemplate("hardware/" + std::string(from)));
    text = replaceAll(std::move(text), kHardwareTemplateClass, camelCase(spec.name, "Arm"));
    return replaceAll(std::move(text), kHardwareTemplateName, spec.name);
  };
  return {{"CMakeLists.txt", instantiateHardware("CMakeLists.txt")},
          {spec.name + ".cpp", instantiateHardware("my_arm.cpp")},
          {"README.md", instantiateHardware("README.md")}};
}

}  // namespace

std::string pluginNameProblem(std::string_view name) {
  if (name.empty()) {
    return "the plugin name is empty";
  }
  const auto identifier = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  };
  for (const char c : name) {
    if (!identifier(c) || static_cast<unsigned char>(c) >= 0x80) {
      return "plugin name '" + std::string(name) +
             "' is not a C identifier (letters, digits and _, not starting with a digit)";
    }
  }
  if (std::isdigit(static_cast<unsigned char>(name.front())) != 0) {
    return "plugin name '" + std::string(name) + "' starts with a digit; it must be a C identifier";
  }
  return {};
}

std::vector<GeneratedFile> pluginFiles(const PluginSpec& spec) {
  if (const auto problem = pluginNameProblem(spec.name); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  if (spec.kind == "hardware") {
    if (spec.language != "cpp") {
      // HardwareInterface is a C++ class; there is no C form of a backend.
      throw std::invalid_argument("a hardware backend is written in cpp, not " + spec.language);
    }
    return hardwareFiles(spec);
  }
  if (spec.kind != "joint" && spec.kind != "cartesian") {
    throw std::invalid_argument("plugin kind must be joint, cartesian or hardware, not '" +
                                spec.kind + "'");
  }
  if (spec.language != "cpp" && spec.language != "c") {
    throw std::invalid_argument("plugin language must be cpp or c, not '" + spec.language + "'");
  }
  const std::string source = spec.kind + (spec.language == "cpp" ? ".cpp" : ".c");
  const std::string law_file = spec.name + (spec.language == "cpp" ? ".cpp" : ".c");
  std::vector<GeneratedFile> files;
  const auto add = [&](std::string path, std::string_view from) {
    files.push_back({std::move(path), instantiate("plugin/" + std::string(from), spec)});
  };
  add("CMakeLists.txt", "CMakeLists.txt");
  add(law_file, source);
  add("test/plugin_test.c", "plugin_test.c");
  add("README.md", "README.md");
  add("fr3_samples.json", "samples_" + spec.kind + ".json");
  add(spec.name + ".yaml", "controller_" + spec.kind + ".yaml");
  add("task.yaml", "task_" + spec.kind + ".yaml");
  return files;
}

}  // namespace comply::codegen
