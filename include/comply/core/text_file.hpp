#pragma once
// The one way comply reads an input file (controller and task files, URDFs, robot.yaml, scene
// fragments, sample files): a regular file of bounded size, read whole. A device (`/dev/zero`),
// a FIFO or a file far larger than any real input is refused with a message naming it, instead
// of reading until memory runs out.

#include <cstddef>
#include <filesystem>
#include <string>
#include <system_error>

namespace comply {

/// Largest input file [bytes]: real ones are kilobytes; a URDF with meshes inlined, megabytes.
inline constexpr std::size_t kMaxInputFileBytes = 16U << 20U;

struct TextFile {
  std::string text;
  std::string error;  ///< why it could not be read, naming the file; empty on success
  [[nodiscard]] bool ok() const noexcept { return error.empty(); }
};

/// The whole file, or the reason it was refused ("cannot read '<path>': no such file", "... too
/// many levels of symbolic links (a symlink loop)", "'<path>' is not a regular file", "... is 20.0
/// MB, more than an input file may be (16 MB)"). Callers throw their own error type with `error`,
/// so that their messages keep their form.
TextFile readTextFile(const std::filesystem::path& path,
                      std::size_t max_bytes = kMaxInputFileBytes);

/// Why a path could not be looked up or opened, from the system's error: "no such file", "too many
/// levels of symbolic links (a symlink loop)", "permission denied", "not a directory". Every cause
/// once read "no such file", a symlink loop included.
std::string fileErrorText(const std::error_code& error);

}  // namespace comply
