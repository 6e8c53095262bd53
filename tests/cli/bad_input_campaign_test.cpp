// The bad inputs of the fault campaign (docs/reliability.md, "The campaign's cases"), in the style of the
// bad-input catalogue: each case runs the real pkm binary on one input written at run time and checks the
// exact exit code, that stderr names the file with LINE:COLUMN (or the option) and the reason, that nothing
// crashed or hung (exit < 128, well under the time limit), that neither stdout nor stderr carries raw control
// bytes or broken UTF-8, and that no output was written (a new --out folder does not exist afterwards, or an
// earlier complete run is byte for byte unchanged).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/catalogue_support.hpp"
#include "io/printable_text.hpp"
#include "source_paths.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------------
// Inputs

const char* const kCampaignMachine =  // the smallest machine file, as the catalogue's
    "type: planar2\n"
    "base_joints:\n"
    "  - [0.0, 0.0]\n"
    "  - [300.0, 40.0]\n"
    "home: [120.0, 250.0]\n";

void campaign_write(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

// `levels` anchors of nine aliases each on top of a list of nine numbers: 9^levels nodes when expanded.
std::string campaign_bomb(const std::string& head, const std::string& tail_key) {
  std::string text = head + "x0: &x0 [1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i < 10; ++i) {
    text += "x" + std::to_string(i) + ": &x" + std::to_string(i) + " [";
    for (int k = 0; k < 9; ++k) text += (k ? ", *x" : "*x") + std::to_string(i - 1);
    text += "]\n";
  }
  return text + tail_key + ": *x9\n";
}

// The ch5 hexapod's own file with line `line` (1-based) changed by `edit`.
std::string campaign_ch5_with(int line, const std::function<std::string(const std::string&)>& edit) {
  std::istringstream in(test::catalogue_read(test::source_path("examples/machines/hexapod_ch5.yaml")));
  std::string out;
  int at = 0;
  for (std::string text; std::getline(in, text);) out += (++at == line ? edit(text) : text) + "\n";
  return out;
}

void campaign_write_inputs(const fs::path& t) {
  const std::string machine = kCampaignMachine;
  // YAML aliases, documents, quotes, bytes
  campaign_write(t / "m_alias_cycle.yaml", "name: &r [*r]\n" + machine);
  campaign_write(t / "m_alias_cycle_map.yaml", machine + "limits: &l {actuator_max: *l}\n");
  campaign_write(t / "m_alias_bomb.yaml", campaign_bomb(machine, "description"));
  campaign_write(t / "m_second_document.yaml", machine + "---\nhome: [100.0, 250.0]\n");
  campaign_write(t / "m_nul_in_name.yaml", std::string("name: ab\0tc\n", 11) + machine);
  campaign_write(t / "m_escape_in_name.yaml", "name: \"\\e[2J\\e[31mred\"\n" + machine);
  campaign_write(t / "m_latin1_name.yaml", "name: caf\xe9 \xff\n" + machine);
  campaign_write(t / "m_\x1b[31mred.yaml", machine);
  campaign_write(t / "m_quote.yaml", campaign_ch5_with(6, [](const std::string&) { return "name: \"ch5"; }));
  campaign_write(t / "m_quote_never_closed.yaml", machine + "description: 'open\n");
  campaign_write(t / "m_unclosed_bracket.yaml",
                 "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [300.0, 40.0\nhome: [120.0, 250.0]\n");
  campaign_write(t / "m_tab_indent.yaml", machine + "limits:\n\tactuator_max: 500\n");
  campaign_write(t / "m_home_angle.yaml",
                 campaign_ch5_with(65, [](const std::string&) { return "home: [0, 0, 700, 0, 1e300, 0]"; }));
  campaign_write(t / "m_base_joint_huge.yaml",
                 "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [1e308, 40.0]\nhome: [120.0, 250.0]\n");
  campaign_write(t / "m_inf.yaml", "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [.inf, 40.0]\n");
  // Load files
  campaign_write(t / "load_alias_cycle.yaml", "default: &r {tangential: *r}\n");
  campaign_write(t / "load_alias_bomb.yaml", campaign_bomb("default: {tangential: 10}\n", "blocks"));
  campaign_write(t / "load_second_document.yaml", "default: {tangential: 10}\n---\ndefault: {normal: 5}\n");
  campaign_write(t / "load_far_block.yaml",
                 "default: {tangential: 10}\nblocks:\n  - {lines: [500, 600], normal: 5}\n");
  campaign_write(t / "load_far_line.csv", "line,fx_N\n6,10\n900,20\n");
  campaign_write(t / "load_huge_force.yaml", "default:\n  force: [0, 1e300, 0]\n");
}

// ---------------------------------------------------------------------------------------------------------
// Running pkm

// Text a terminal shows as it is: every line unchanged by the one escape pkm applies to what it prints.
bool campaign_is_printable(const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (printable_text(line, line.size() + 1) != line) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------------------
// The cases

struct CampaignCase {
  const char* name;
  /// pkm's arguments; {t} is the case's temporary folder, {m} the ch5 hexapod, {line} the ch5 test line.
  std::string command;
  int exit_code;
  /// On stderr for a failure (on stdout when the case must succeed), after the same substitutions.
  std::vector<std::string> fragments;
  /// A folder under {t} that must be the same after the run as before ("new": must not appear).
  std::string unchanged = {};
  std::function<void(const fs::path&)> prepare = {};
};

std::vector<CampaignCase> campaign_yaml_cases() {
  const std::string stiffness = "stiffness {line} --machine {m} --out {t}/new ";
  return {
      {"machine_alias_cycle",
       "check {t}/m_alias_cycle.yaml",
       2,
       {"{t}/m_alias_cycle.yaml:1:11: alias *r: the alias is inside the node that &r names (1:7): an endless "
        "cycle"}},
      {"machine_alias_cycle_in_mapping",
       "check {t}/m_alias_cycle_map.yaml",
       2,
       {"{t}/m_alias_cycle_map.yaml:6:27: alias *l: the alias is inside the node that &l names (6:9)"}},
      {"machine_alias_bomb",
       "check {t}/m_alias_bomb.yaml",
       2,
       {"{t}/m_alias_bomb.yaml:", ": alias *x", "aliases expand the file to more than 100000 nodes"}},
      {"load_alias_cycle",
       stiffness + "--load @{t}/load_alias_cycle.yaml",
       2,
       {"--load: {t}/load_alias_cycle.yaml:1:26: alias *r: the alias is inside the node that &r names "
        "(1:10)"},
       "new"},
      {"load_alias_bomb",
       stiffness + "--load @{t}/load_alias_bomb.yaml",
       2,
       {"{t}/load_alias_bomb.yaml:", "aliases expand the file to more than 100000 nodes"},
       "new"},
      {"machine_second_document",
       "check {t}/m_second_document.yaml",
       2,
       {"{t}/m_second_document.yaml:6:1: second YAML document: a pkm file holds one document"}},
      {"load_second_document",
       stiffness + "--load @{t}/load_second_document.yaml",
       2,
       {"{t}/load_second_document.yaml:2:1: second YAML document"},
       "new"},
      {"machine_unclosed_quote",
       "check {t}/m_quote.yaml",
       2,
       {"{t}/m_quote.yaml:6:7: unclosed quote: the \" opened here is not closed on this line (the next \" is "
        "on line 56)"}},
      {"machine_quote_never_closed",
       "check {t}/m_quote_never_closed.yaml",
       2,
       {"{t}/m_quote_never_closed.yaml:6:14: unclosed quote: the ' opened here is never closed"}},
      {"machine_unclosed_bracket",
       "check {t}/m_unclosed_bracket.yaml",
       2,
       {"{t}/m_unclosed_bracket.yaml:4:5: not valid YAML: the [ opened here is never closed with a ]"}},
      {"machine_tab_in_indentation",
       "check {t}/m_tab_indent.yaml",
       2,
       {"{t}/m_tab_indent.yaml:7:1: not valid YAML: a TAB in the indentation (YAML indents with spaces "
        "only)"}},
      {"machine_nul_in_name",
       "check {t}/m_nul_in_name.yaml",
       2,
       {"{t}/m_nul_in_name.yaml:1:9: not valid YAML: a NUL byte (\\x00)"}},
      {"machine_escape_sequence_in_name",
       "check {t}/m_escape_in_name.yaml",
       2,
       {"{t}/m_escape_in_name.yaml:1:7: name: a control character (\\x1B) at byte 1: a name is one line of "
        "printable text"}},
      {"machine_name_not_utf8",
       "check {t}/m_latin1_name.yaml",
       2,
       {"{t}/m_latin1_name.yaml:1:7: name: a byte that is not UTF-8 (\\xE9) at byte 4: a name is one line of "
        "UTF-8 text"}},
      {"check_prints_an_escape_in_the_path_escaped",
       "check '{t}/m_\x1b[31mred.yaml'",
       0,
       {"m_\\x1B[31mred.yaml: valid"}},
      {"machine_home_angle_huge",
       "check {t}/m_home_angle.yaml",
       2,
       {"{t}/m_home_angle.yaml:65:22: home[4]: an angle of 1e+300 deg is not an orientation"}},
      {"machine_base_joint_huge",
       "check {t}/m_base_joint_huge.yaml",
       2,
       {"{t}/m_base_joint_huge.yaml:4:6: base_joints[1][0]: 1e+308 is too large for a coordinate"}},
      {"machine_infinity_named",
       "check {t}/m_inf.yaml",
       2,
       {"{t}/m_inf.yaml:4:6: base_joints[1][0]: expected a finite number, got '.inf'"}},
  };
}

std::vector<CampaignCase> campaign_command_cases() {
  const std::string stiffness = "stiffness {line} --machine {m} --out {t}/new ";
  const std::string plan = "plan {line} --machine {m} --no-path-error ";
  const std::string optimize = "optimize " + test::source_path("examples/programs/planar_circle.ngc") +
                               " --machine " + test::source_path("examples/machines/planar3.yaml") +
                               " --law increment --step-mm 0.6981 --out {t}/new/o.ngc ";
  const auto plan_sentinel = [](const fs::path& t) { test::catalogue_plan_sentinel(t); };
  return {
      {"jacobian_refuses_what_ik_refuses",
       "jacobian --machine {m} --pose 0,0,1200,0,0,0",
       3,
       {"pkm jacobian: error: pose unreachable within the actuator range"}},
      {"pose_out_of_range_for_a_number",
       "ik --machine {m} --pose 1e999,0,700,0,0,0",
       2,
       {"--pose: '1e999' is out of range (at most 1e+06 in size; item 1 of '1e999,0,700,0,0,0')"}},
      {"ik_refuses_the_same_pose",
       "ik --machine {m} --pose 0,0,1200,0,0,0",
       3,
       {"pkm ik: error: pose unreachable within the actuator range"}},
      {"stiffness_load_beyond_any_machine",
       stiffness + "--load tangential=1e300",
       2,
       {"--load: 'tangential=1e300': 1e+300 N is beyond any machine's load (at most 1e+08 N in size)"},
       "new"},
      {"stiffness_load_out_of_range",
       stiffness + "--load tangential=1e999",
       2,
       {"--load: 'tangential=1e999': tangential: '1e999' is out of range for a number"},
       "new"},
      {"stiffness_load_nan",
       stiffness + "--load normal=nan",
       2,
       {"--load: 'normal=nan': normal: expected a finite number, got 'nan'"},
       "new"},
      {"load_file_force_beyond_any_machine",
       stiffness + "--load @{t}/load_huge_force.yaml",
       2,
       {"{t}/load_huge_force.yaml:2:14: default.force[1]: 1e+300 N is beyond any machine's load"},
       "new"},
      {"load_block_for_lines_the_program_lacks",
       stiffness + "--load @{t}/load_far_block.yaml",
       2,
       {"--load: {t}/load_far_block.yaml:3:13: blocks[0].lines: a load for lines 500 to 600, but {line} has "
        "7 "
        "lines: the load would never act"},
       "new"},
      {"load_csv_row_for_a_line_the_program_lacks",
       plan + "--dynamics --out {t}/run --load @{t}/load_far_line.csv",
       2,
       {"--load: {t}/load_far_line.csv:3:1: line: a load for line 900, but {line} has 7 lines"},
       "run",
       plan_sentinel},
      {"optimize_load_block_for_lines_the_program_lacks",
       optimize + "--load @{t}/load_far_block.yaml",
       2,
       {"{t}/load_far_block.yaml:3:13: blocks[0].lines: a load for lines 500 to 600, but ",
        "planar_circle.ngc has"},
       "new"},
      {"strategies_load_block_for_lines_a_program_lacks",
       "strategies --machine {m} --out {t}/new --program {line} --load @{t}/load_far_block.yaml",
       2,
       {"--load: {t}/load_far_block.yaml:3:13: blocks[0].lines: a load for lines 500 to 600, but {line} has "
        "7 "
        "lines"},
       "new"},
      {"report_program_missing",
       "report {t}/run --program {t}/missing.ngc",
       2,
       {"pkm report: error: {t}/missing.ngc: cannot read part program: No such file"},
       "run",
       plan_sentinel},
      {"optimize_bounds_nan",
       optimize + "--bounds nan,nan",
       2,
       {"--bounds nan,nan: LO 'nan' is not a number"},
       "new"},
      {"optimize_bounds_reversed",
       optimize + "--bounds 30,5",
       2,
       {"--bounds 30,5: LO must be below HI (degrees), got 30 and 5"},
       "new"},
      {"option_too_large_for_any_number",
       plan + "--out {t}/new --tolerance 1e999",
       2,
       {"--tolerance: must be ≥ 0 and ≤ 100 mm, got 1e999 (too large for any number)"},
       "new"},
      {"option_too_small_to_tell_from_zero",
       plan + "--out {t}/new --override 1e-999",
       2,
       {"--override: must be > 0 and ≤ 200 %, got 1e-999 (too small to tell from 0: write 0)"},
       "new"},
  };
}

std::vector<CampaignCase> campaign_cases() {
  std::vector<CampaignCase> cases = campaign_yaml_cases();
  for (CampaignCase& c : campaign_command_cases()) cases.push_back(std::move(c));
#if !PKM_REPORT_PAGE
  // Built without the report page (no Node.js): every report fails alike (report_page_missing_test.cpp).
  std::erase_if(cases, [](const CampaignCase& c) { return c.command.rfind("report ", 0) == 0; });
#endif
  return cases;
}

void PrintTo(const CampaignCase& c, std::ostream* os) {
  *os << c.name;
}

class BadInputCampaign : public testing::TestWithParam<CampaignCase> {};

TEST_P(BadInputCampaign, FailsCleanly) {
  const CampaignCase& c = GetParam();
  const fs::path t =
      fs::temp_directory_path() / ("pkm_campaign_" + std::to_string(::getpid()) + "_" + c.name);
  fs::remove_all(t);
  fs::create_directories(t);
  campaign_write_inputs(t);
  if (c.prepare) c.prepare(t);
  ASSERT_FALSE(testing::Test::HasFatalFailure());
  const fs::path watched = c.unchanged.empty() ? fs::path() : t / c.unchanged;
  const test::CatalogueSnapshot before =
      c.unchanged.empty() ? test::CatalogueSnapshot{} : test::catalogue_snapshot(watched);

  const std::string args = test::catalogue_expand(c.command, t);
  const test::CatalogueRun run = test::catalogue_run_pkm(args, t / "stderr.txt");

  EXPECT_LT(run.exit_code, 128) << "pkm " << args << " crashed: " << run.err;
  EXPECT_EQ(run.exit_code, c.exit_code) << "pkm " << args << "\nstderr: " << run.err;
  const std::string& where = c.exit_code == 0 ? run.out : run.err;
  for (const std::string& fragment : c.fragments) {
    const std::string expected = test::catalogue_expand(fragment, t);
    EXPECT_NE(where.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << where;
  }
  if (c.exit_code != 0) {
    EXPECT_NE(run.err.find("error:"), std::string::npos) << run.err;
    // One line; a usage error (CLI11's check of an option) has the --help hint below it.
    const std::string hint = "\nRun with --help for more information.\n";
    const bool usage = run.err.size() > hint.size() && run.err.ends_with(hint);
    EXPECT_LE(std::count(run.err.begin(), run.err.end(), '\n'), usage ? 2 : 1) << "one line:\n" << run.err;
  }
  EXPECT_TRUE(campaign_is_printable(run.err)) << run.err;
  EXPECT_TRUE(campaign_is_printable(run.out)) << run.out;
  EXPECT_LT(run.seconds, 8.0) << "pkm " << args;
  if (!c.unchanged.empty()) {
    EXPECT_EQ(test::catalogue_snapshot(watched), before) << c.unchanged << " changed";
  }
  if (!HasFailure()) fs::remove_all(t);
}

std::string campaign_case_name(const testing::TestParamInfo<CampaignCase>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInputCampaign, testing::ValuesIn(campaign_cases()), campaign_case_name);

}  // namespace
}  // namespace pkm
