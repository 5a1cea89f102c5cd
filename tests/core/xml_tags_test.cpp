#include "comply/core/xml_tags.hpp"

#include <gtest/gtest.h>

#include <string_view>

namespace comply {
namespace {

std::string_view tagText(std::string_view xml, const XmlTag& tag) {
  return xml.substr(tag.begin, tag.end - tag.begin);
}

TEST(XmlTags, FindsTheOpeningTagAndItsEnd) {
  constexpr std::string_view kXml = R"(<robot name="arm"><link name="base"/></robot>)";
  const auto robot = findOpeningTag(kXml, "robot");
  ASSERT_TRUE(robot);
  EXPECT_EQ(tagText(kXml, *robot), R"(<robot name="arm">)");
  EXPECT_FALSE(robot->selfClosing(kXml));
  const auto link = findOpeningTag(kXml, "link");
  ASSERT_TRUE(link);
  EXPECT_EQ(tagText(kXml, *link), R"(<link name="base"/>)");
  EXPECT_TRUE(link->selfClosing(kXml));
}

TEST(XmlTags, SkipsCommentsCdataInstructionsAndDeclarations) {
  constexpr std::string_view kXml =
      "<?xml version=\"1.0\"?><!DOCTYPE robot><!-- <robot name=\"decoy\"> -->"
      "<x><![CDATA[<robot name=\"cdata\">]]></x><robot name=\"real\">";
  const auto robot = findOpeningTag(kXml, "robot");
  ASSERT_TRUE(robot);
  EXPECT_EQ(tagText(kXml, *robot), "<robot name=\"real\">");
}

TEST(XmlTags, MatchesTheWholeNameOnly) {
  constexpr std::string_view kXml = "<bodyx/><body\tname=\"b\">";
  const auto body = findOpeningTag(kXml, "body");
  ASSERT_TRUE(body);
  EXPECT_EQ(body->begin, 8U);
  EXPECT_FALSE(findOpeningTag(kXml, "bod"));
}

TEST(XmlTags, AGreaterThanInAQuotedValueDoesNotEndTheTag) {
  constexpr std::string_view kXml = R"(<geom name="a>b" type='c>d'/>)";
  const auto geom = findOpeningTag(kXml, "geom");
  ASSERT_TRUE(geom);
  EXPECT_EQ(geom->end, kXml.size());
  EXPECT_TRUE(geom->selfClosing(kXml));
}

TEST(XmlTags, SearchesFromAnOffsetAndReportsNoneWhenAbsentOrUnterminated) {
  constexpr std::string_view kXml = R"(<body name="1"><body name="2"/></body>)";
  const auto first = findOpeningTag(kXml, "body");
  ASSERT_TRUE(first);
  const auto second = findOpeningTag(kXml, "body", first->end);
  ASSERT_TRUE(second);
  EXPECT_EQ(tagText(kXml, *second), R"(<body name="2"/>)");
  EXPECT_FALSE(findOpeningTag(kXml, "body", second->end));
  EXPECT_FALSE(findOpeningTag(kXml, "joint"));
  EXPECT_FALSE(findOpeningTag(R"(<robot name="open)", "robot"));
  EXPECT_FALSE(findOpeningTag("<!-- <robot> never closed", "robot"));
}

}  // namespace
}  // namespace comply
