#pragma once
// Finding elements in XML text, enough to splice MuJoCo fragments into a model: MuJoCo 2.2 loads
// models from files only, so a scene is put together as text, with no XML library.

#include <cstddef>
#include <optional>
#include <string_view>

namespace comply {

/// An opening tag's place in the text.
struct XmlTag {
  std::size_t begin = 0;  ///< at its '<'
  std::size_t end = 0;    ///< one past its '>'
  /// <name .../>: an element without content.
  [[nodiscard]] bool selfClosing(std::string_view xml) const {
    return end >= 2 && xml[end - 2] == '/';
  }
};

/// The first opening tag `<name ...>` at or after `from` that stands outside comments, CDATA
/// sections, processing instructions and declarations (DOCTYPE). It ends at the first '>' outside
/// a quoted attribute value. None when there is no such tag or it is not terminated.
std::optional<XmlTag> findOpeningTag(std::string_view xml, std::string_view name,
                                     std::size_t from = 0);

}  // namespace comply
