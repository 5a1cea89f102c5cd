#pragma once
// The option readers' tests: a controller file's text that must be refused, with an error that
// names every one of `fragments` (the option's path, the reason).

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace comply::pipeline::test {

/// `read(lines)` throws, and its message holds each of `fragments`.
template <typename Read>
void expectReadError(const Read& read, const std::string& lines,
                     const std::vector<std::string>& fragments) {
  try {
    (void)read(lines);
    ADD_FAILURE() << "expected an error for:\n" << lines;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
    }
  }
}

}  // namespace comply::pipeline::test
