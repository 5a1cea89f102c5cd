#include "written_inertials.hpp"

#include <tinyxml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include "comply/model/model_error.hpp"

namespace comply::model {
namespace {

constexpr std::array<const char*, 6> kInertiaAttributes{"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};

std::optional<std::string> attribute(const TiXmlElement* element, const char* name) {
  const char* value = element != nullptr ? element->Attribute(name) : nullptr;
  return value != nullptr ? std::optional<std::string>(value) : std::nullopt;
}

// urdfdom reads a number with a C-locale stream that must end exactly at the end of the text:
// leading blanks and one '+' pass, a trailing blank does not, and neither do NaN or infinity.
// Returns why `text` is not such a finite number, or nothing when it is.
std::optional<std::string> whyNotAFiniteNumber(std::string_view text) {
  std::size_t begin = 0;
  while (begin < text.size() && std::isspace(static_cast<unsigned char>(text[begin])) != 0) {
    ++begin;
  }
  if (begin < text.size() && text[begin] == '+') {
    ++begin;
    if (begin < text.size() && (text[begin] == '+' || text[begin] == '-')) {
      return "not a number";  // from_chars would read "+-1" as -1, the stream refuses it
    }
  }
  double value = 0.0;
  const char* const last = text.data() + text.size();
  const auto [end, error] = std::from_chars(text.data() + begin, last, value);
  if (error == std::errc::result_out_of_range) {
    return "out of a double's range";
  }
  if (error != std::errc() || end != last) {
    return "not a number";
  }
  if (!std::isfinite(value)) {
    return "not a finite number";
  }
  return std::nullopt;
}

// urdfdom splits a vector on ' ' alone, skips empty pieces and wants exactly three numbers.
bool isThreeFiniteNumbers(std::string_view text) {
  int numbers = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t stop = std::min(text.find(' ', start), text.size());
    const std::string_view piece = text.substr(start, stop - start);
    if (!piece.empty()) {
      if (whyNotAFiniteNumber(piece)) {
        return false;
      }
      ++numbers;
    }
    start = stop + 1;
  }
  return numbers == 3;
}

[[noreturn]] void refuse(const std::string& link_name, const std::string& complaint) {
  throw ModelError(ModelErrc::kInvalidInertia, "link '" + link_name + "': " + complaint);
}

// An origin may be left out (it is then zero); one that is written must be readable.
void requireVector(const std::string& link_name, const char* name,
                   const std::optional<std::string>& text) {
  if (text && !isThreeFiniteNumbers(*text)) {
    refuse(link_name,
           "<origin " + std::string(name) + "=\"" + *text + "\">: not three finite numbers");
  }
}

// urdfdom refuses an <inertial> without the mass or any inertia component as it refuses an
// unreadable one (and leaves zeros behind), so a missing value is refused here too.
void requireNumber(const std::string& link_name, const std::string& element, const char* name,
                   const std::optional<std::string>& text) {
  const std::string tag = "<" + element + " " + name;
  if (!text) {
    refuse(link_name, "<inertial> has no " + tag + ">");
  }
  if (const auto why = whyNotAFiniteNumber(*text)) {
    refuse(link_name, tag + "=\"" + *text + "\">: " + *why);
  }
}

}  // namespace

// The same walk urdfdom makes: the first <robot>, its <link> children, the first <inertial> of
// each and the first <origin>, <mass> and <inertia> in it.
WrittenInertials::WrittenInertials(const std::string& urdf_xml) {
  TiXmlDocument document;
  document.Parse(urdf_xml.c_str());
  const TiXmlElement* robot = document.FirstChildElement("robot");
  if (document.Error() || robot == nullptr) {
    throw ModelError(ModelErrc::kInvalidUrdf, "the URDF has no <robot> element to read");
  }
  for (const TiXmlElement* link = robot->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link")) {
    const TiXmlElement* inertial = link->FirstChildElement("inertial");
    const auto name = attribute(link, "name");
    if (inertial == nullptr || !name) {
      continue;
    }
    const TiXmlElement* origin = inertial->FirstChildElement("origin");
    const TiXmlElement* inertia = inertial->FirstChildElement("inertia");
    Inertial written{attribute(origin, "xyz"),
                     attribute(origin, "rpy"),
                     attribute(inertial->FirstChildElement("mass"), "value"),
                     {}};
    for (std::size_t i = 0; i < kInertiaAttributes.size(); ++i) {
      written.inertia[i] = attribute(inertia, kInertiaAttributes[i]);
    }
    by_link_.emplace(*name, std::move(written));
  }
}

void WrittenInertials::require(const std::string& link_name) const {
  const auto found = by_link_.find(link_name);
  if (found == by_link_.end()) {
    return;
  }
  const Inertial& written = found->second;
  requireVector(link_name, "xyz", written.origin_xyz);
  requireVector(link_name, "rpy", written.origin_rpy);
  requireNumber(link_name, "mass", "value", written.mass);
  for (std::size_t i = 0; i < kInertiaAttributes.size(); ++i) {
    requireNumber(link_name, "inertia", kInertiaAttributes[i], written.inertia[i]);
  }
}

}  // namespace comply::model
