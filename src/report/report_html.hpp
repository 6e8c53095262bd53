#pragma once
// One self-contained HTML file: the page's bundled script and style, and the report's data
// (docs/report-data.md) as JSON in a script element.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm::report {

/// Text for HTML or SVG markup and attribute values: < > & " as entities.
std::string html_escape(std::string_view text);
/// The whole page for `data`.
std::string report_html(const nlohmann::json& data);
/// Writes the page to `path` (staged: no partial file on failure); creates its directory.
Status write_report_html(const std::string& path, const nlohmann::json& data);

}  // namespace pkm::report
