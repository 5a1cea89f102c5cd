// `comply send`'s line for an outcome: the reason named once, whether the message came from the
// wrapper (which begins it with its reason) or from the command gate (which does not).

#include <gtest/gtest.h>

#include <string>

#include "live_json.hpp"

namespace comply::app {
namespace {

transport::CommandOutcomeMessage rejected(transport::Reason reason, const std::string& message) {
  transport::CommandOutcomeMessage outcome;
  outcome.stamp = {.sec = 12, .nanosec = 5};
  outcome.outcome = transport::Outcome::kRejected;
  outcome.reason = reason;
  outcome.message = message;
  return outcome;
}

TEST(OutcomeLine, NamesTheReasonOnce) {
  EXPECT_EQ(outcomeLine(rejected(transport::Reason::kInvalidWorkspace,
                                 "invalid_workspace: workspace_min along x (0.6 m) is not below "
                                 "workspace_max (0.5 m)")),
            "rejected 12.000000005: invalid_workspace: workspace_min along x (0.6 m) is not below "
            "workspace_max (0.5 m)");
  EXPECT_EQ(outcomeLine(rejected(transport::Reason::kOtherPublisher, "another sender holds them")),
            "rejected 12.000000005: other_publisher: another sender holds them");
}

}  // namespace
}  // namespace comply::app
