#pragma once
// Each link's <inertial> as written in the URDF text. urdfdom does not refuse an <inertial> it
// cannot read: it logs the value, keeps the link and leaves its mass, inertia or both at zero (a
// mass of "nan", "inf", "abc" or "1 " weighs 0 kg), so the model would be built from numbers
// nobody wrote. The text is read again here, with urdfdom's own XML parser, so that every value
// of a link the model moves can be held to urdfdom's rules before the parsed model is trusted.

#include <array>
#include <map>
#include <optional>
#include <string>

namespace comply::model {

class WrittenInertials {
 public:
  /// Collects the <inertial> of every <link> of `urdf_xml` (text urdfdom has already parsed).
  explicit WrittenInertials(const std::string& urdf_xml);

  /// Throws ModelError (kInvalidInertia) naming the link and the attribute when the <inertial> of
  /// `link_name` lacks a value urdfdom requires or holds one that is not a finite number as
  /// urdfdom reads it. A link without <inertial> passes: its body's lumped mass is checked.
  void require(const std::string& link_name) const;

 private:
  /// Each value's text; nullopt where the attribute or its element is absent.
  struct Inertial {
    std::optional<std::string> origin_xyz;
    std::optional<std::string> origin_rpy;
    std::optional<std::string> mass;
    std::array<std::optional<std::string>, 6> inertia;  // ixx ixy ixz iyy iyz izz
  };

  std::map<std::string, Inertial> by_link_;
};

}  // namespace comply::model
