#pragma once
// Files that comply writes for other tools (comply codegen, comply plugin new): a relative path
// and its text, produced in memory so tests can look at them without touching the disk.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace comply::codegen {

struct GeneratedFile {
  std::filesystem::path path;  ///< relative to the output folder
  std::string text;
};

/// Writes every file under `out` (creating folders); throws std::runtime_error on I/O failure.
void writeFiles(const std::filesystem::path& out, std::span<const GeneratedFile> files);

/// A template file embedded at build time from src/codegen/templates (path relative to it).
/// Throws std::out_of_range for an unknown path.
std::string_view embeddedTemplate(std::string_view path);

/// `text` with every occurrence of `from` replaced by `to`.
std::string replaceAll(std::string text, std::string_view from, std::string_view to);

}  // namespace comply::codegen
