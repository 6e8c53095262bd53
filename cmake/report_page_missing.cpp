// The report page's assets in a build without Node.js (cmake/report_assets.cmake): none. write_report_html
// refuses with a message saying why, instead of writing a page that shows nothing.
#include "report/report_assets.hpp"

namespace pkm::report {

std::string_view report_script() { return {}; }
std::string_view report_style() { return {}; }
bool report_page_built() { return false; }

}  // namespace pkm::report
