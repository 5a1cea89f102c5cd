#include "comply/pipeline/command_bus_variant.hpp"

#include <algorithm>
#include <iterator>

#include "comply/pipeline/force_axes.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {

CommandBus emptyBus(int command_kind) noexcept {
  if (command_kind == COMPLY_COMMAND_CARTESIAN) {
    return comply_cartesian_command{};
  }
  return comply_joint_command{};
}

const void* busPointer(const CommandBus& bus) noexcept {
  return std::visit([](const auto& typed) -> const void* { return &typed; }, bus);
}

void mergeInto(CommandBus& active, const CommandBus& incoming) noexcept {
  std::visit(
      [&incoming](auto& into) {
        using Bus = std::decay_t<decltype(into)>;
        if (const Bus* from = std::get_if<Bus>(&incoming)) {
          schema::mergeBus(into, *from);
        }
      },
      active);
}

void seedFromMeasured(CommandBus& bus, const MeasuredPose& measured) noexcept {
  std::visit([&measured](auto& typed) { schema::seedReference(typed, measured); }, bus);
}

void stopMotion(CommandBus& bus) noexcept {
  std::visit([](auto& typed) { schema::stopMotion(typed); }, bus);
}

void holdMeasured(CommandBus& bus, const MeasuredPose& measured) noexcept {
  seedFromMeasured(bus, measured);
  std::visit(
      [](auto& typed) {
        if constexpr (requires { typed.wrench_feedforward; }) {
          std::fill(std::begin(typed.wrench_feedforward), std::end(typed.wrench_feedforward), 0.0);
        }
        std::fill(std::begin(typed.torque_feedforward), std::end(typed.torque_feedforward), 0.0);
      },
      bus);
}

void anchorForceAxes(CommandBus& bus, const MeasuredPose& measured) noexcept {
  if (auto* cartesian = std::get_if<comply_cartesian_command>(&bus)) {
    anchorForceAxes(*cartesian, measured.tcp_position, measured.tcp_orientation);
  }
}

}  // namespace comply::pipeline
