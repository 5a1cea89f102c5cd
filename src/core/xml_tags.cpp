#include "comply/core/xml_tags.hpp"

namespace comply {

std::optional<XmlTag> findOpeningTag(std::string_view xml, std::string_view name,
                                     std::size_t from) {
  const auto skipPast = [&](std::size_t at, std::string_view terminator) {
    const std::size_t found = xml.find(terminator, at);
    return found == std::string_view::npos ? xml.size() : found + terminator.size();
  };
  constexpr std::string_view kNameEnds = " \t\r\n/>";
  std::size_t i = from;
  while ((i = xml.find('<', i)) != std::string_view::npos) {
    const std::string_view rest = xml.substr(i);
    if (rest.starts_with("<!--")) {
      i = skipPast(i + 4, "-->");
    } else if (rest.starts_with("<![CDATA[")) {
      i = skipPast(i + 9, "]]>");
    } else if (rest.starts_with("<?")) {
      i = skipPast(i + 2, "?>");
    } else if (rest.starts_with("<!")) {
      i = skipPast(i + 2, ">");
    } else {
      std::size_t name_end = i + 1;
      while (name_end < xml.size() && kNameEnds.find(xml[name_end]) == std::string_view::npos) {
        ++name_end;
      }
      if (xml.substr(i + 1, name_end - i - 1) == name) {
        char quote = 0;
        for (std::size_t j = name_end; j < xml.size(); ++j) {
          if (quote != 0) {
            quote = xml[j] == quote ? '\0' : quote;
          } else if (xml[j] == '"' || xml[j] == '\'') {
            quote = xml[j];
          } else if (xml[j] == '>') {
            return XmlTag{i, j + 1};
          }
        }
        return std::nullopt;
      }
      i = name_end;
    }
  }
  return std::nullopt;
}

}  // namespace comply
