#pragma once
// The body regions an unexpected contact may meet, with the biomechanical limits the contact-speed
// stage bounds the TCP's speed by (contact_speed.hpp, contact_speed.* options).
//
// Source: ISO/TS 15066:2016, Robots and robotic devices - Collaborative robots, Annex A:
//   Table A.2  the maximum permissible quasi-static force per body region; for transient contact
//              (an impact the body part can recoil from) twice it, except for the skull and
//              forehead and the face, where the table allows no transient contact;
//              the effective spring constant of each region;
//   Table A.3  the effective mass of each region (an adult of 75 kg).
// The regions are the table's body regions, not its 29 specific areas (the neck's front, for one,
// is far softer than its sides: 10 N/mm against the 50 N/mm here); where a finer value is known,
// contact_speed.force_limit_n and stiffness_n_per_m override the region's. docs/safety.md lists
// the values and which of them were checked against a second source.

#include "comply/core/enum_names.hpp"

namespace comply::pipeline {

enum class BodyRegion {
  kSkullForehead,
  kFace,
  kNeck,
  kBackShoulders,
  kChest,
  kAbdomen,
  kPelvis,
  kUpperArms,
  kLowerArms,
  kHands,
  kThighs,
  kLowerLegs,
};
inline constexpr EnumNames<BodyRegion, 12> kBodyRegionNames{
    {{BodyRegion::kSkullForehead, "skull_forehead"},
     {BodyRegion::kFace, "face"},
     {BodyRegion::kNeck, "neck"},
     {BodyRegion::kBackShoulders, "back_shoulders"},
     {BodyRegion::kChest, "chest"},
     {BodyRegion::kAbdomen, "abdomen"},
     {BodyRegion::kPelvis, "pelvis"},
     {BodyRegion::kUpperArms, "upper_arms"},
     {BodyRegion::kLowerArms, "lower_arms"},
     {BodyRegion::kHands, "hands"},
     {BodyRegion::kThighs, "thighs"},
     {BodyRegion::kLowerLegs, "lower_legs"}}};

/// quasi_static: the body part cannot move away (clamped against something): the quasi-static
/// force limit. transient: a short impact the body part recoils from: twice it, where allowed.
enum class ContactKind { kQuasiStatic, kTransient };
inline constexpr EnumNames<ContactKind, 2> kContactKindNames{
    {{ContactKind::kQuasiStatic, "quasi_static"}, {ContactKind::kTransient, "transient"}}};

/// One row of ISO/TS 15066 Annex A.
struct BodyRegionLimits {
  double quasi_static_force_n = 0.0;  ///< Table A.2: maximum permissible quasi-static force
  bool transient_allowed = true;      ///< Table A.2: transient contact permitted at all
  double stiffness_n_per_m = 0.0;     ///< Table A.2: effective spring constant
  double effective_mass_kg = 0.0;     ///< Table A.3
};

/// The region's row.
constexpr BodyRegionLimits bodyRegionLimits(BodyRegion region) noexcept {
  switch (region) {
    case BodyRegion::kSkullForehead:
      return {130.0, false, 150e3, 4.4};
    case BodyRegion::kFace:
      return {65.0, false, 75e3, 4.4};
    case BodyRegion::kNeck:
      return {150.0, true, 50e3, 1.2};
    case BodyRegion::kBackShoulders:
      return {210.0, true, 35e3, 40.0};
    case BodyRegion::kChest:
      return {140.0, true, 25e3, 40.0};
    case BodyRegion::kAbdomen:
      return {110.0, true, 10e3, 40.0};
    case BodyRegion::kPelvis:
      return {180.0, true, 25e3, 40.0};
    case BodyRegion::kUpperArms:
      return {150.0, true, 30e3, 3.0};
    case BodyRegion::kLowerArms:
      return {160.0, true, 40e3, 2.0};
    case BodyRegion::kHands:
      return {140.0, true, 75e3, 0.6};
    case BodyRegion::kThighs:
      return {220.0, true, 50e3, 75.0};
    case BodyRegion::kLowerLegs:
      return {130.0, true, 60e3, 75.0};
  }
  return {};
}

/// Transient contact is permitted at twice the quasi-static force (Annex A).
inline constexpr double kTransientForceFactor = 2.0;

/// The force a contact of `kind` with a region of `limits` may reach [N]; 0 where the table
/// permits no such contact.
constexpr double forceLimit(const BodyRegionLimits& limits, ContactKind kind) noexcept {
  if (kind == ContactKind::kQuasiStatic) {
    return limits.quasi_static_force_n;
  }
  return limits.transient_allowed ? kTransientForceFactor * limits.quasi_static_force_n : 0.0;
}

}  // namespace comply::pipeline
