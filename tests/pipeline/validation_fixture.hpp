#pragma once
// The fixture both kinds of command validation share: validateAndMerge() against the limits, the
// merged command in force and the measured pose, and the check of a rejection (its reason, its
// message, and the command in force unchanged to the bit).

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "command_bits.hpp"
#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline::test {

/// Both kinds are validated for a 3-joint arm.
inline constexpr int kDof = 3;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename Command>
class ValidationFixture : public ::testing::Test {
 protected:
  /// `next`: a valid command that would be accepted on top of `merged`.
  ValidationFixture(int dof, Command merged, MeasuredPose measured, Command (*next)())
      : merged_(std::move(merged)), measured_(measured), dof_(dof), next_(next) {}

  /// Validates `incoming` and expects a rejection for `reason` whose message holds `fragments`,
  /// with the merged command unchanged.
  void expectRejected(const Command& incoming, RejectionReason reason,
                      const std::vector<std::string>& fragments) {
    const Command before = merged_;
    const Verdict verdict = validate(incoming);
    EXPECT_FALSE(verdict.accepted);
    EXPECT_EQ(verdict.reason, reason) << verdict.message;
    EXPECT_EQ(verdict.message.rfind(std::string(toString(reason)) + ": ", 0), 0U)
        << verdict.message;
    for (const auto& fragment : fragments) {
      EXPECT_NE(verdict.message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << verdict.message;
    }
    expectSameBits(merged_, before);
  }

  /// Same for a change applied to a valid next command.
  void expectRejected(const std::function<void(Command&)>& corrupt, RejectionReason reason,
                      const std::vector<std::string>& fragments) {
    Command incoming = next_();
    corrupt(incoming);
    expectRejected(incoming, reason, fragments);
  }

  /// Whatever mask the sender used, the merged command holds every group (the plugin reads all).
  void expectMergedCarriesEveryGroup() {
    merged_.fields = CommandField::kNone;
    Command incoming = next_();
    incoming.fields = CommandField::kVelocity;
    ASSERT_TRUE(validate(incoming).accepted);
    EXPECT_EQ(merged_.fields, CommandField::kAll);
  }

  Verdict validate(const Command& incoming) {
    return validateAndMerge(incoming, limits_, dof_, measured_, merged_);
  }

  ValidationConfig limits_;
  Command merged_;
  MeasuredPose measured_;

 private:
  int dof_;
  Command (*next_)();
};

}  // namespace comply::pipeline::test
