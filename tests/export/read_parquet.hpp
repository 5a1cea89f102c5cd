#pragma once
// tests/export/read_parquet.mjs from a test: a Parquet file as hyparquet, a reader independent of
// comply's writer, reads it (its footer and every row, INT64 values as decimal strings).

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "scratch.hpp"

namespace comply::exporter::test {

/// What read_parquet.mjs prints for `path`; null JSON and a test failure when Node or its
/// packages are missing or the file does not read.
inline nlohmann::json readWithHyparquet(const std::filesystem::path& path) {
  const std::string source = COMPLY_SOURCE_DIR;
  const auto [status, text] = testing::runCommand(
      "node " + source + "/tests/export/read_parquet.mjs '" + path.string() + "'");
  if (status != 0 || text.empty()) {
    ADD_FAILURE() << "read_parquet.mjs failed (exit " << status << ") on " << path
                  << ": run scripts/install-deps.sh to install Node's packages";
    return nullptr;
  }
  return nlohmann::json::parse(text);
}

}  // namespace comply::exporter::test
