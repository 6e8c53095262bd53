// A pkm built without Node.js has no report page (cmake/report_assets.cmake, PKM_REPORT_PAGE off): a report
// asked for fails with a message saying why, and the run's other files are not written either (the output
// set is committed as a whole). In a build with the page, tests/cli/report_cli_test.cpp covers the reports.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli/cli_support.hpp"
#include "report/report_assets.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

TEST(ReportPage, BuiltExactlyWhenTheBuildSaysSo) {
  EXPECT_EQ(report::report_page_built(), PKM_REPORT_PAGE != 0);
  EXPECT_EQ(report::report_script().empty(), PKM_REPORT_PAGE == 0);
}

#if !PKM_REPORT_PAGE
TEST(ReportPage, AReportWithoutThePageFailsSayingWhyAndWritesNothing) {
  const fs::path out = fs::temp_directory_path() / "pkm_report_page_missing";
  fs::remove_all(out);
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " +
                                 out.string() + " --report " + (out / "report.html").string());
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("built without the report page"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}
#endif

}  // namespace
}  // namespace pkm
