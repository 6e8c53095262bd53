#include "report/report_html.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "io/atomic_file.hpp"
#include "report/report_assets.hpp"

namespace pkm::report {

namespace {

/// Text inside <script> ends at the first "</script": JSON may say "<\/" for "</" ("\/" is a JSON escape).
std::string script_safe_json(const nlohmann::json& data) {
  std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + 64);
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && (text[i + 1] == '/' || text[i + 1] == '!')) {
      out += "\\u003c";  // also keeps "<!--" from opening an HTML comment
      continue;
    }
    out += text[i];
  }
  return out;
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

std::string report_html(const nlohmann::json& data) {
  const std::string title =
      data.contains("title") && data["title"].is_string() ? data["title"].get<std::string>() : "pkm report";
  std::string page;
  const std::string_view script = report_script(), style = report_style();
  page.reserve(script.size() + style.size() + 4096);
  page +=
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">";
  page += fmt::format("<title>{} — pkm</title><style>", html_escape(title));
  page += style;
  page += "</style></head>\n<body>\n<script type=\"application/json\" id=\"pkm-report-data\">";
  page += script_safe_json(data);
  page += "</script>\n<script>";
  page += script;
  page += "</script>\n</body></html>\n";
  return page;
}

Status write_report_html(const std::string& path, const nlohmann::json& data) {
  if (!report_page_built()) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("cannot write the report {}: this pkm was built without the report page "
                                  "(Node.js and npm were not found at build time; install them and rebuild)",
                                  path));
  }
  const std::filesystem::path file(path);
  if (file.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(file.parent_path(), error);
    if (error) {
      return make_error(ErrorCode::io, fmt::format("cannot create directory {}: {}",
                                                   file.parent_path().string(), error.message()));
    }
  }
  return write_file_atomically(path, report_html(data));
}

}  // namespace pkm::report
