#include "pipeline/folder_report.hpp"

#include <filesystem>

#include "io/output_manifest.hpp"
#include "io/output_set.hpp"
#include "report/report_html.hpp"

namespace pkm::pipeline {

namespace {

namespace fs = std::filesystem;

bool is_inside(const std::string& file, const std::string& directory) {
  std::error_code error;
  const fs::path folder = fs::weakly_canonical(fs::absolute(directory), error);
  const fs::path parent = fs::weakly_canonical(fs::absolute(file), error).parent_path();
  const fs::path relative = parent.lexically_relative(folder);
  return !error && !relative.empty() && *relative.begin() != "..";
}

}  // namespace

const std::vector<std::string>& report_folder_commands() {
  static const std::vector<std::string> commands{"plan", "interpolate", "stiffness", "workspace",
                                                 "calibrate identify"};
  return commands;
}

Status write_folder_report(const std::string& directory, const std::string& file,
                           const report::ReportOptions& options) {
  // The files first, so that a file the reader cannot use is named as such; the set before anything is
  // written.
  auto data = report::report_from_directory(directory, options);
  if (!data) return data.error();
  if (Status checked = check_output_set(directory, report_folder_commands()); !checked) return checked;
  if (!is_inside(file, directory)) return report::write_report_html(file, *data);
  OutputSet outputs{"report"};
  if (Status joined = outputs.join_directory(directory, report_folder_commands()); !joined) return joined;
  auto staged = outputs.stage_file(file);
  if (!staged) return staged.error();
  if (Status written = report::write_report_html(*staged, *data); !written) return written;
  return outputs.commit();
}

}  // namespace pkm::pipeline
