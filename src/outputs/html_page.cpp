#include "outputs/html_page.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/error.h"
#include "common/quoting.h"

namespace aerobox {
namespace {

void Replace(std::string* text, const std::string& marker, const std::string& with) {
  const size_t at = text->find(marker);
  if (at == std::string::npos) throw std::logic_error("html page: no marker " + marker);
  text->replace(at, marker.size(), with);
}

}  // namespace

std::string ReadPageScript(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || text.str().empty()) {
    throw InputError({path, 0}, "report.html",
                     "the page's script is missing: install libjs-three and libjs-chart.js "
                     "(tools/setup.sh), or leave the page out with --no-report");
  }
  return text.str();
}

std::string FillPage(std::string page, const PageParts& parts) {
  std::string data = parts.data_json;  // never "</script>" inside the page's data
  for (size_t at = data.find("</"); at != std::string::npos; at = data.find("</", at + 3)) {
    data.replace(at, 2, "<\\/");
  }
  Replace(&page, "AEROBOX_TITLE", XmlEscaped(parts.title));
  for (const auto& [marker, script] : parts.scripts) Replace(&page, marker, script);
  Replace(&page, "/*AEROBOX_DATA*/", data);
  return page;
}

}  // namespace aerobox
