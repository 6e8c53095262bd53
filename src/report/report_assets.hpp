#pragma once
// The report page's script and style sheet, bundled from web/ (three.js, uPlot and pkm's own page code) by
// npm and esbuild at build time and compiled into pkm (cmake/embed_report_assets.cmake), so a report is one
// file that needs no network.
#include <string_view>

namespace pkm::report {

std::string_view report_script();
std::string_view report_style();
/// False in a build made without Node.js (cmake/report_page_missing.cpp): no page to write a report with.
bool report_page_built();

}  // namespace pkm::report
