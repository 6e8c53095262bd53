// pkm report DIR [--out FILE] [--machine M] [--program P]: the HTML report of a `pkm plan` or `pkm
// interpolate` run from its output directory (docs/report.md): summary, plots and a 3-D animation in one file
// that opens offline in a browser.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/input_file.hpp"
#include "pipeline/folder_report.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

void add_report_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("report", "write the HTML report of a pkm plan or pkm interpolate run");
  auto directory = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto options = std::make_shared<report::ReportOptions>();
  cmd->add_option("directory", *directory, "the run's --out directory")->required();
  cmd->add_option("--out", *out, "the HTML file (default DIR/report.html)");
  cmd->add_option("--machine", options->machine_file,
                  "machine file (default: the one the run's summary names)");
  cmd->add_option("--program", options->program_file, "part program (default: the one the summary names)");
  cmd->callback([=, &exit_code] {
    // A --program that cannot be read is an error, not a report without the program's lines.
    if (!options->program_file.empty()) {
      if (auto program = read_text_input(options->program_file, "part program"); !program) {
        exit_code = report_error("report", program.error());
        return;
      }
    }
    const std::string file =
        out->empty() ? (std::filesystem::path(*directory) / "report.html").string() : *out;
    ProgressDisplay progress("report", "reading the run and writing the report");
    Status written = pipeline::write_folder_report(*directory, file, *options);
    progress.finish();
    if (!written) {
      Error error = written.error();
      // The run's machine could not be had: say which option names another.
      if (error.location.key == "machine") error.message += "; give it with --machine";
      exit_code = report_error("report", error);
      return;
    }
    std::cout << fmt::format("report: {}\n", file);
  });
}

}  // namespace pkm::cli
