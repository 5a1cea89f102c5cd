// JSON and YAML reading and writing of both command kinds: exact round trips, the field mask,
// shorthand, errors that name the key, and the `initial:` block of a controller file.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <nlohmann/json.hpp>

#include "comply/core/input_error.hpp"
#include "comply/schema/json.hpp"
#include "schema_support.hpp"

namespace comply::schema {
namespace {

using nlohmann::json;
using test::distinctCartesian;
using test::distinctJoint;
using test::kDof;
using test::sameBytes;

template <typename Command>
Parsed<Command> read(const json& object, bool shorthand = false) {
  ReadOptions<Command> options;
  options.allow_shorthand = shorthand;
  return fromJson(object, kDof, options);
}

/// Expects an InputError of `code` whose key is `key` and whose message holds `fragment`.
template <typename Command>
void expectError(const json& object, InputErrc code, const std::string& key,
                 const std::string& fragment, bool shorthand = false) {
  try {
    (void)read<Command>(object, shorthand);
    FAIL() << "accepted " << object.dump();
  } catch (const InputError& error) {
    EXPECT_EQ(error.code(), code) << error.what();
    EXPECT_EQ(error.key(), key) << error.what();
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(SchemaJson, RoundTripsBothKindsBitForBit) {
  CartesianCommand cartesian = distinctCartesian();
  cartesian.fields = CommandField::kStiffness | CommandField::kTaskFrame;
  const Parsed<CartesianCommand> c = read<CartesianCommand>(json::parse(toJson(cartesian).dump()));
  EXPECT_EQ(c.command.fields, cartesian.fields);
  EXPECT_TRUE(sameBytes(toBus(c.command, kDof), toBus(cartesian, kDof)));
  EXPECT_EQ(c.keys, (FieldSet{1} << 22) - 1);  // every row of the table

  JointCommand joint = distinctJoint();
  joint.fields = CommandField::kAll;
  const Parsed<JointCommand> j = read<JointCommand>(json::parse(toJson(joint).dump()));
  EXPECT_EQ(j.command.fields, CommandField::kAll);
  EXPECT_TRUE(sameBytes(toBus(j.command, kDof), toBus(joint, kDof)));
}

TEST(SchemaJson, MaskFollowsTheKeysOrTheFieldsList) {
  const auto gains = read<CartesianCommand>(json{{"damping_mode", "ratio"}, {"stamp", 0.5}});
  EXPECT_EQ(gains.command.fields, CommandField::kDamping);
  EXPECT_EQ(gains.command.damping_mode, DampingMode::kRatio);
  EXPECT_EQ(gains.command.stamp_s, 0.5);
  EXPECT_EQ(gains.keys, FieldSet{1} << 8);

  const auto listed = read<JointCommand>(json{{"fields", {"position", "damping"}}});
  EXPECT_EQ(listed.command.fields, CommandField::kPosition | CommandField::kDamping);
  EXPECT_EQ(listed.keys, 0U);
}

TEST(SchemaJson, AbsentKeysKeepTheBase) {
  ReadOptions<CartesianCommand> options;
  options.base = distinctCartesian();
  const auto parsed =
      fromJson(json{{"stiffness_rotational", {1, 0, 0, 0, 2, 0, 0, 0, 3}}}, kDof, options);
  EXPECT_EQ(parsed.command.stiffness_rotational(2, 2), 3.0);
  EXPECT_EQ(parsed.command.stiffness_translational, options.base->stiffness_translational);
}

TEST(SchemaJson, ShorthandForBlocksAndVectors) {
  const json object{{"stiffness_translational", 100},
                    {"stiffness_rotational", {1, 2, 3}},
                    {"damping_translational", {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}}},
                    {"damping_ratio", 0.7},
                    {"nullspace_stiffness", 5}};
  const CartesianCommand c = read<CartesianCommand>(object, true).command;
  EXPECT_EQ(c.stiffness_translational, 100.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(c.stiffness_rotational, Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix());
  EXPECT_EQ(c.damping_translational(1, 1), 2.0);
  EXPECT_EQ(c.damping_ratio, Vector6d::Constant(0.7));
  EXPECT_EQ(c.nullspace_stiffness, JointVector::Constant(kDof, 5.0));
  EXPECT_EQ(read<JointCommand>(json{{"stiffness", 7}}, true).command.stiffness,
            JointVector::Constant(kDof, 7.0));
  // Without shorthand the same is a size error.
  expectError<CartesianCommand>(json{{"stiffness_rotational", {1, 2, 3}}}, InputErrc::kWrongSize,
                                "stiffness_rotational", "has 3 numbers, expected 9");
  expectError<CartesianCommand>(json{{"stiffness_rotational", {1, 2}}}, InputErrc::kWrongSize,
                                "stiffness_rotational", "expected 1, 3 or 9", true);
  expectError<CartesianCommand>(json{{"orientation", 1.0}}, InputErrc::kWrongSize, "orientation",
                                "expected 4", true);
}

TEST(SchemaJson, ErrorsNameTheKey) {
  expectError<CartesianCommand>(json{{"stifness", 1}}, InputErrc::kUnknownKey, "stifness",
                                "unknown command field 'stifness'");
  expectError<JointCommand>(json{{"position", {1, 2}}}, InputErrc::kWrongSize, "position",
                            "'position' has 2 numbers, expected 3");
  expectError<JointCommand>(json{{"damping", {1, "a", 3}}}, InputErrc::kWrongType, "damping",
                            "list of numbers");
  expectError<CartesianCommand>(json{{"damping_mode", "critical"}}, InputErrc::kInvalidValue,
                                "damping_mode", "\"absolute\" or \"ratio\"");
  expectError<CartesianCommand>(json{{"fields", {"pose"}}}, InputErrc::kInvalidValue, "fields",
                                "unknown group \"pose\"");
  expectError<CartesianCommand>(json{{"stamp", "now"}}, InputErrc::kWrongType, "stamp", "number");
  expectError<CartesianCommand>(json::array(), InputErrc::kWrongType, "", "JSON object");
}

TEST(SchemaYaml, ConvertsNumbersAndRefusesNonFinite) {
  const json value =
      yamlToJson(YAML::Load("{a: [1, 2.5], b: text, c: {d: -3}}"), "file.yaml", "root");
  EXPECT_EQ(value["a"][1], 2.5);
  EXPECT_EQ(value["b"], "text");
  EXPECT_EQ(value["c"]["d"], -3.0);
  try {
    (void)yamlToJson(YAML::Load("{a: [1, .nan]}"), "file.yaml", "root");
    FAIL() << "NaN accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "root.a[1]");
    EXPECT_NE(std::string(error.what()).find("not a finite number"), std::string::npos);
  }
  EXPECT_THROW((void)yamlToJson(YAML::Load("{a: .inf}"), "f", "root"), InputError);
}

TEST(SchemaInitial, DefaultsAndShorthandForBothKinds) {
  const json object = yamlToJson(YAML::Load("{stiffness: 50, stiffness_translational: [1, 2, 3], "
                                            "damping_mode: absolute, torque_feedforward: 0.5}"),
                                 "controller.yaml", "initial");
  const InitialCommands initial = readInitialCommands(object, kDof, "controller.yaml");
  EXPECT_EQ(initial.joint.stiffness, JointVector::Constant(kDof, 50.0));
  EXPECT_EQ(initial.joint.damping, JointVector::Constant(kDof, 10.0));
  EXPECT_EQ(initial.cartesian.stiffness_translational(2, 2), 3.0);
  EXPECT_EQ(initial.cartesian.stiffness_rotational, 30.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(initial.cartesian.damping_mode, DampingMode::kAbsolute);
  EXPECT_EQ(initial.joint.torque_feedforward, JointVector::Constant(kDof, 0.5));
  EXPECT_EQ(initial.cartesian.torque_feedforward, JointVector::Constant(kDof, 0.5));
  EXPECT_EQ(initial.cartesian.fields, CommandField::kAll);

  const InitialCommands defaults = readInitialCommands(json(), kDof, "controller.yaml");
  EXPECT_EQ(defaults.cartesian.damping_mode, DampingMode::kRatio);
  EXPECT_EQ(defaults.cartesian.nullspace_damping, JointVector::Constant(kDof, 0.5));
}

TEST(SchemaInitial, RefusesUnknownSeededAndInvalidKeys) {
  const auto expect = [](const json& object, InputErrc code, const std::string& key) {
    try {
      (void)readInitialCommands(object, kDof, "c.yaml");
      FAIL() << "accepted " << object.dump();
    } catch (const InputError& error) {
      EXPECT_EQ(error.code(), code) << error.what();
      EXPECT_EQ(error.key(), key) << error.what();
    }
  };
  expect(json{{"stifness", 1}}, InputErrc::kUnknownKey, "initial.stifness");
  expect(json{{"twist", {0, 0, 0, 0, 0, 0}}}, InputErrc::kInvalidValue, "initial.twist");
  expect(json{{"nullspace_stiffness", -1}}, InputErrc::kOutOfRange, "initial.nullspace_stiffness");
  expect(json{{"task_frame", {0, 0, 0, 2}}}, InputErrc::kOutOfRange, "initial.task_frame");
  expect(json{{"stiffness_rotational", {1, 2}}}, InputErrc::kWrongSize,
         "initial.stiffness_rotational");
}

TEST(ParseJson, NestingIsBoundedWhileParsing) {
  const auto nested = [](int levels) {
    return std::string(static_cast<std::size_t>(levels), '[') +
           std::string(static_cast<std::size_t>(levels), ']');
  };
  EXPECT_NO_THROW(parseJson(nested(kMaxJsonDepth), "shallow.json"));
  try {
    parseJson(nested(100'000), "deep.json");  // overflowed the stack after parsing, before
    FAIL() << "a 100,000-level document was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("deep.json"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("nested deeper than 64"), std::string::npos);
  }
  EXPECT_THROW(parseJson("{\"a\": ", "cut.json"), nlohmann::json::parse_error);
}

}  // namespace
}  // namespace comply::schema
