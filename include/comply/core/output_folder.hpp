#pragma once
// Where comply writes: a file's folder must exist (`--record FILE`), and an output folder
// (`--out DIR`) is made only as its last component. A mistyped path ends in an error naming the
// missing folder, never in a chain of folders made somewhere unexpected (even under `/`).

#include <filesystem>
#include <string>

namespace comply {

/// "" when the folder `file` would be written in exists (the working folder for a bare name);
/// else why not, naming the folder: "the folder 'runs/today' does not exist (create it first:
/// mkdir -p 'runs/today')", "'runs' is not a folder". Creates nothing.
std::string missingFolderOf(const std::filesystem::path& file);

/// Makes the output folder `folder` when it does not exist yet; its parent must (the working
/// folder for a bare name). True when it was made. Throws std::runtime_error naming the missing
/// parent ("cannot make the output folder 'a/b/c': the folder 'a/b' does not exist (create it
/// first: mkdir -p 'a/b')"), or `folder` when it is a file, or the system's reason.
bool makeOutputFolder(const std::filesystem::path& folder);

}  // namespace comply
