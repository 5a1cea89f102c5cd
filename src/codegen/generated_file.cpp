#include "comply/codegen/generated_file.hpp"

#include <fstream>
#include <stdexcept>

#include "embedded_templates.hpp"

namespace comply::codegen {

void writeFiles(const std::filesystem::path& out, std::span<const GeneratedFile> files) {
  for (const auto& file : files) {
    const auto path = out / file.path;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream stream(path, std::ios::binary);
    stream << file.text;
    if (!stream.flush()) {
      throw std::runtime_error("cannot write " + path.string());
    }
  }
}

std::string_view embeddedTemplate(std::string_view path) {
  const auto& templates = embeddedTemplates();
  const auto found = templates.find(path);
  if (found == templates.end()) {
    throw std::out_of_range("no embedded template " + std::string(path));
  }
  return found->second;
}

std::string replaceAll(std::string text, std::string_view from, std::string_view to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace comply::codegen
