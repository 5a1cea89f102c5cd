// A URDF whose joints close a loop is freed in full once refused: urdfdom links a parent to its
// children by shared_ptr, so the loop would keep its links alive; ParsedUrdf cuts it. Checked with
// a weak_ptr rather than the leak sanitizer, which cannot tell these allocations from the ones
// urdfdom itself leaks when it refuses a URDF (tests/sanitizers/lsan.supp).

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <memory>
#include <string>

#include "comply/model/model_error.hpp"
#include "test_urdfs.hpp"
#include "urdf_checks.hpp"

namespace comply::model {
namespace {

TEST(ParsedUrdf, ALoopTheParserAcceptsIsFreedWhenTheModelGoes) {
  // The root is `base`, so urdfdom accepts the loop a -> b -> a.
  const std::string loop = test_urdfs::kinematicLoop();
  std::weak_ptr<urdf::Link> link_in_loop;
  {
    std::shared_ptr<urdf::ModelInterface> parsed = urdf::parseURDF(loop);
    ASSERT_TRUE(parsed);
    link_in_loop = parsed->links_.at("a");
    const ParsedUrdf urdf(std::move(parsed));
    EXPECT_THROW(requireTree(*urdf), ModelError);
    EXPECT_FALSE(link_in_loop.expired());
  }
  EXPECT_TRUE(link_in_loop.expired());
}

}  // namespace
}  // namespace comply::model
