// A URDF whose joints close a loop is freed in full once refused: urdfdom links a parent to its
// children by shared_ptr, so the loop would keep its links alive; ParsedUrdf cuts it. Checked with
// a weak_ptr rather than the leak sanitizer, which cannot tell these allocations from the ones
// urdfdom itself leaks when it refuses a URDF (tests/sanitizers/lsan.supp).

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <memory>
#include <string>

#include "comply/model/model_error.hpp"
#include "urdf_checks.hpp"

namespace comply::model {
namespace {

TEST(ParsedUrdf, ALoopTheParserAcceptsIsFreedWhenTheModelGoes) {
  // The root is `base`, so urdfdom accepts the loop a -> b -> a.
  const std::string loop = R"(<robot name="loop"><link name="base"/><link name="a"/>
    <link name="b"/>
    <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" velocity="1" effort="10"/></joint>
    <joint name="j2" type="revolute"><parent link="b"/><child link="a"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" velocity="1" effort="10"/></joint></robot>)";
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
