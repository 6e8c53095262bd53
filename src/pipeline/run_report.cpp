#include "pipeline/run_report.hpp"

#include "report/report_data.hpp"
#include "report/report_html.hpp"

namespace pkm::pipeline {

Status stage_run_report(OutputSet& outputs, const std::string& report_path) {
  if (report_path.empty()) return ok_status();
  auto staged = outputs.stage_file(report_path);
  if (!staged) return staged.error();
  auto data = report::report_from_directory(outputs.staging_directory());
  if (!data) return data.error();
  return report::write_report_html(*staged, *data);
}

}  // namespace pkm::pipeline
