#pragma once
// The report page's script and style sheet, bundled from web/ (three.js, uPlot and pkm's own page code) by
// npm and esbuild at build time and compiled into pkm (cmake/embed_report_assets.cmake), so a report is one
// file that needs no network.
#include <string_view>

namespace pkm::report {

std::string_view report_script();
std::string_view report_style();

}  // namespace pkm::report
