// The bad-input catalogue (docs/reliability.md): every case runs the real pkm binary on one bad input (a file
// or a command-line option) and checks the exact exit code, that stderr names the file with LINE:COLUMN (or
// the option) and the reason, that nothing crashed (exit < 128, no raw control bytes on the terminal), and
// for the commands that write files that the output folder still holds the previous complete run, or nothing
// from this one, and no stray temporaries. Inputs are written at run time into a temporary folder.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/catalogue_support.hpp"
#include "source_paths.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;
using test::catalogue_ch5;
using test::catalogue_expand;
using test::catalogue_line;
using test::catalogue_plan_sentinel;
using test::catalogue_run_pkm;
using test::catalogue_snapshot;
using test::CatalogueRun;
using test::CatalogueSnapshot;

// ---------------------------------------------------------------------------------------------------------
// Inputs

const char* const kCatalogueMachine =  // the smallest machine file: base for the YAML cases
    "type: planar2\n"
    "base_joints:\n"
    "  - [0.0, 0.0]\n"
    "  - [300.0, 40.0]\n"
    "home: [120.0, 250.0]\n";

void catalogue_write(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

// `head`, `piece` `times` over, `tail`: built by appending (GCC 12 warns falsely on "a" + std::string(n, c)).
std::string catalogue_repeat(const std::string& head, const std::string& piece, int times,
                             const std::string& tail) {
  std::string out = head;
  out.reserve(piece.size() * static_cast<std::size_t>(times));
  for (int i = 0; i < times; ++i) out += piece;
  out += tail;
  return out;
}

// Bytes a terminal would act on (ESC sequences, a bell, NUL) and bytes that are not UTF-8.
const std::string kCatalogueBinary = std::string("\x01\x02\x1b[31m\x07\xff\xfe\x00 G1\x7f", 15) + "\n";

void catalogue_write_inputs(const fs::path& t) {
  fs::create_directories(t / "adir.ngc");
  fs::create_directories(t / "adir.cl");
  fs::create_directories(t / "adir.yaml");
  fs::create_directories(t / "adir.tbl");
  fs::create_directories(t / "adir_load.yaml");
  catalogue_write(t / "empty.ngc", "");
  catalogue_write(t / "binary.ngc", kCatalogueBinary);
  catalogue_write(t / "binary.cl", kCatalogueBinary);
  catalogue_write(t / "bom.ngc", "\xEF\xBB\xBFG21 G90\nG1 X1 F100\nG1 X2\nM2\n");
  catalogue_write(t / "bom.cl", "\xEF\xBB\xBFUNITS/MM\nFEDRAT/100\nGOTO/1,0,0\nGOTO/2,0,0\nFINI\n");
  catalogue_write(t / "cr_only.ngc", "G21 G90\rG1 X1 F100\rG1 X2\rG1 X3\rM2\r");
  catalogue_write(t / "cr_only.cl", "UNITS/MM\rFEDRAT/100\rGOTO/1,0,0\rGOTO/2,0,0\rFINI\r");
  catalogue_write(t / "crlf.ngc", "G21 G90\r\nG1 X1 F100\r\nG1 X2\r\nM2\r\n");
  catalogue_write(t / "long_line.ngc", catalogue_repeat("G21 G90\nG1 X", "7", 2000000, " F100\nM2\n"));
  catalogue_write(t / "huge_number.ngc", catalogue_repeat("G21 G90\nG1 X", "9", 400, " F100\nM2\n"));
  catalogue_write(t / "unsupported.ngc", "G21 G90\nG1 X1 F100\n  G33 X2 K1\nM2\n");
  // The language's own errors: parameters, expressions, O-words, bounds, compensation.
  catalogue_write(t / "undefined_parameter.ngc", "G21 G90\nG0 X#<width>\nM2\n");
  catalogue_write(t / "divide_by_zero.ngc", "G21 G90\n#1 = 0\nG1 X[10 / #1] F100\nM2\n");
  catalogue_write(t / "unmatched_oword.ngc", "G21 G90\no100 if [1 GT 2]\nG1 X1 F100\n");
  catalogue_write(t / "stray_endwhile.ngc", "G21 G90\nG1 X1 F100\no7 endwhile\nM2\n");
  catalogue_write(t / "recursion.ngc",
                  "o<deeper> sub\n  o<deeper> call\no<deeper> endsub\nG21\no<deeper> call\nM2\n");
  catalogue_write(t / "endless_loop.ngc", "G21 G90\no1 while [1]\n  G1 X1 F100\no1 endwhile\nM2\n");
  catalogue_write(
      t / "gouge.ngc",
      "G21 G90 G17\nG0 X0 Y0\nG41.1 D10\nG1 X20 Y0 F100\nG1 X20 Y2\nG1 X22 Y2\nG1 X22 Y20\nG40 G1 X0 "
      "Y20\nM2\n");
  catalogue_write(t / "nan.cl", "UNITS/MM\nFEDRAT/100\nGOTO/1,nan,0\nFINI\n");
  catalogue_write(t / "unknown.cl", "UNITS/MM\nFEDRAT/100\n  FROBNICATE/1\nFINI\n");
  catalogue_write(t / "cutcom_no_cutter.apt",
                  "UNITS/MM\nFEDRAT/100\nGOTO/0,0,0\nCUTCOM/LEFT\nGOTO/10,0,0\nFINI\n");
  catalogue_write(t / "cycle_no_depth.apt", "UNITS/MM\nFEDRAT/100\nCYCLE/DRILL,RAPTO,2\nGOTO/0,0,0\nFINI\n");
  catalogue_write(t / "nurbs_counts.cls",
                  "TOOL PATH/S,TOOL,MILL\nFEDRAT/MMPM,100\nGOTO/0,0,0\nNURBS/\nKNOT/0.3,0.6,1.0\n"
                  "CNTRL/1,0,0\nCNTRL/2,1,0\nCNTRL/3,0,0\nCNTRL/4,1,0\nEND-OF-PATH\n");
  catalogue_write(t / "trntyp_offset.apt", "UNIT/MM\nTRNTYP/WORLD,10,0,0\nFINI\n");
  catalogue_write(
      t / "catia_surface.aptsource",
      "$$*CATIA0\nMULTAX\nFEDRAT/100,MMPM\nGOTO/0,0,0\nTLON,GOFWD/(CIRCLE/0,0,0,5),ON,(LINE/0,0,0,1,1,0)\n");
  catalogue_write(t / "unreachable.ngc", "G21 G90\nG1 X0 Y0 Z0 F3000\nG1 X900 F3000\nM2\n");
  catalogue_write(t / "tools.tbl", kCatalogueBinary);

  catalogue_write(t / "m_empty.yaml", "");
  catalogue_write(t / "m_binary.yaml", kCatalogueBinary);
  catalogue_write(t / "m_ok.yaml", kCatalogueMachine);
  catalogue_write(t / "m_bom.yaml", "\xEF\xBB\xBF" + std::string(kCatalogueMachine));
  std::string crlf, cr;
  for (const char c : std::string(kCatalogueMachine)) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    cr += c == '\n' ? '\r' : c;
  }
  catalogue_write(t / "m_crlf.yaml", crlf);
  catalogue_write(t / "m_cr_only.yaml", cr);
  catalogue_write(t / "m_duplicate.yaml", std::string(kCatalogueMachine) + "home: [100.0, 250.0]\n");
  catalogue_write(t / "m_duplicate_nested.yaml",
                  std::string(kCatalogueMachine) + "limits:\n  actuator_min: 100\n  actuator_min: 200\n");
  catalogue_write(t / "m_key_list.yaml", "type: planar2\n[a]: 1\n");
  catalogue_write(t / "m_key_nested.yaml", std::string(kCatalogueMachine) + "limits:\n  [a]: 1\n");
  catalogue_write(t / "m_name_list.yaml", "name: [1, 2]\n" + std::string(kCatalogueMachine));
  catalogue_write(t / "m_deep.yaml", catalogue_repeat("type: planar2\nhome: ", "[", 5000, "\n"));
  catalogue_write(t / "m_empty_home.yaml",
                  "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [300.0, 40.0]\nhome:\n");
  catalogue_write(t / "m_nan.yaml", "type: planar2\nbase_joints:\n  - [0.0, .nan]\n  - [300.0, 40.0]\n");
  catalogue_write(t / "m_huge.yaml",
                  "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [1e999, 40.0]\nhome: [120.0, 250.0]\n");
  catalogue_write(t / "m_wrong_type.yaml", std::string(kCatalogueMachine) + "limits: 5\n");
  catalogue_write(t / "m_unreachable_home.yaml",
                  "type: planar2\nbase_joints:\n  - [0.0, 0.0]\n  - [300.0, 40.0]\nhome: [120.0, 250.0]\n"
                  "limits:\n  actuator_max: 100\n");
  catalogue_write(t / "m_no_type.yaml", "base_joints:\n  - [0.0, 0.0]\n  - [300.0, 40.0]\n");
  catalogue_write(t / "m_typo.yaml", std::string(kCatalogueMachine) + "limit:\n  actuator_max: 100\n");
  catalogue_write(t / "m_units.yaml", "type: hexapod\nangles: radians\n");
  catalogue_write(t / "m_missing_section.yaml", "type: planar2\nhome: [120.0, 250.0]\n");
  catalogue_write(t / "m_scalar_point.yaml", "type: planar2\nbase_joints: 5\nhome: [120.0, 250.0]\n");
  catalogue_write(t / "m_dyn_negative_mass.yaml",
                  std::string(kCatalogueMachine) + "dynamics:\n  platform: {mass_kg: -2}\n");
  catalogue_write(t / "m_dyn_nan_mass.yaml",
                  std::string(kCatalogueMachine) + "dynamics:\n  platform: {mass_kg: .nan}\n");
  catalogue_write(
      t / "m_dyn_inertia.yaml",
      std::string(kCatalogueMachine) + "dynamics:\n  platform: {mass_kg: 2, inertia_kg_m2: [1, 1, 5]}\n");
  catalogue_write(t / "m_dyn_struts.yaml", std::string(kCatalogueMachine) +
                                               "dynamics:\n  platform: {mass_kg: 2}\n  struts:\n"
                                               "    - {lower: {mass_kg: 1, com_mm: 50}}\n");
  catalogue_write(t / "m_dyn_stiffness.yaml",
                  std::string(kCatalogueMachine) +
                      "dynamics:\n  platform: {mass_kg: 2}\n"
                      "  struts: {lower: {mass_kg: 1, com_mm: 50}, stiffness_N_mm: 0}\n");
  catalogue_write(t / "m_force_max.yaml",
                  std::string(kCatalogueMachine) + "limits:\n  actuator_force_max: 0\n");

  catalogue_write(t / "load_duplicate.yaml", "default:\n  tangential: 10\n  tangential: 20\n");
  catalogue_write(t / "load_key_list.yaml", "default:\n  [a]: 1\n");
  catalogue_write(t / "load_nan.yaml", "blocks:\n  - lines: [1, 2]\n    normal: .inf\n");
}

// A CL statement continued with '$' over 200 000 lines (quadratic once: 12.8 s; bench_planning's
// BM_ReadClContinuedStatement fits its reading time to O(N)).
void catalogue_write_continued_cl(const fs::path& t) {
  std::string text = "UNITS/MM\nFEDRAT/100\nGOTO/1 $\n";
  for (int i = 0; i < 200000; ++i) text += ",0 $\n";
  text += "\nFINI\n";
  catalogue_write(t / "continued.cl", text);
}

// ---------------------------------------------------------------------------------------------------------
// Running pkm

// ---------------------------------------------------------------------------------------------------------
// Output folders: the previous complete run (a sentinel) must survive a failed run unchanged.

std::vector<std::string> catalogue_stray_temporaries(const fs::path& root) {
  std::vector<std::string> stray;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos ||
        name.find(".pkm-staging") != std::string::npos)
      stray.push_back(entry.path().string());
  }
  return stray;
}

void catalogue_interpolate_sentinel(const fs::path& t) {
  const auto run = catalogue_run_pkm("interpolate " + catalogue_line() + " --machine " + catalogue_ch5() +
                                         " --period-ms 4 --method carrier --out " + (t / "irun").string(),
                                     t / "sentinel.err");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(fs::exists(t / "irun" / "contour.csv"));
}

// ---------------------------------------------------------------------------------------------------------
// The catalogue

struct CatalogueCase {
  const char* name;
  /// pkm's arguments; {t} is the case's temporary folder, {m} the ch5 hexapod, {line} the ch5 test line.
  std::string command;
  int exit_code;
  /// On stderr for a failure (on stdout when the case must succeed), after the same substitutions.
  std::vector<std::string> fragments;
  /// Made before the run (a sentinel run, a big input); the folder below is compared before and after.
  std::function<void(const fs::path&)> prepare = {};
  std::string unchanged = {};
};

std::vector<CatalogueCase> catalogue_cases() {
  const auto plan_sentinel = [](const fs::path& t) { catalogue_plan_sentinel(t); };
  const auto interpolate_sentinel = [](const fs::path& t) { catalogue_interpolate_sentinel(t); };
  const std::string plan = "plan {line} --machine {m} --no-path-error ";
  const auto plan_of = [](const std::string& program, const std::string& machine) {
    return "plan " + program + " --machine " + machine + " --no-path-error ";
  };
  const std::string interpolate = "interpolate {line} --machine {m} --period-ms 4 --method carrier ";
  const std::string interpret = "interpret ";
  const std::string optimize = "optimize " + test::source_path("examples/programs/planar_circle.ngc") +
                               " --machine " + test::source_path("examples/machines/planar3.yaml") +
                               " --law increment --step-mm 0.6981 ";
  std::vector<CatalogueCase> cases = {
      // --- part programs, CL files and tool tables: what the file is
      {"program_is_directory",
       interpret + "{t}/adir.ngc",
       2,
       {"{t}/adir.ngc: cannot read part program: is a directory"}},
      {"cl_is_directory",
       interpret + "{t}/adir.cl",
       2,
       {"{t}/adir.cl: cannot read part program: is a directory"}},
      {"program_is_dev_zero",
       interpret + "/dev/zero",
       2,
       {"/dev/zero: cannot read part program: is a device"}},
      {"program_missing",
       interpret + "{t}/missing.ngc",
       2,
       {"{t}/missing.ngc: cannot read part program: No such file"}},
      {"tool_table_is_directory",
       interpret + "{line} --tool-table {t}/adir.tbl",
       2,
       {"{t}/adir.tbl: cannot read tool table: is a directory"}},
      {"tool_table_is_dev_zero",
       interpret + "{line} --tool-table /dev/zero",
       2,
       {"/dev/zero: cannot read tool table: is a device"}},
      {"tool_table_binary",
       interpret + "{line} --tool-table {t}/tools.tbl",
       2,
       {"{t}/tools.tbl:1:1: unexpected byte 0x01"}},
      {"plan_program_is_directory",
       plan_of("{t}/adir.ngc", "{m}") + "--out {t}/out",
       2,
       {"adir.ngc: cannot read part program"}},
      // --- part programs: what is in them
      {"program_empty",
       plan_of("{t}/empty.ngc", "{m}") + "--out {t}/out",
       2,
       {"{t}/empty.ngc: the program moves nothing"}},
      {"program_binary", interpret + "{t}/binary.ngc", 2, {"{t}/binary.ngc:1:1: Bad character '\\001' used"}},
      {"cl_binary",
       interpret + "{t}/binary.cl",
       2,
       // Nothing in it reads as CL data: the content, not the name, picks the reader (here G-code's).
       {"{t}/binary.cl:1:1: Bad character '\\001' used"}},
      {"program_bom_accepted", interpret + "{t}/bom.ngc", 0, {"2 moves"}},
      {"cl_bom_accepted", interpret + "{t}/bom.cl", 0, {"2 moves"}},
      {"program_cr_only_accepted", interpret + "{t}/cr_only.ngc", 0, {"3 moves"}},
      {"cl_cr_only_accepted", interpret + "{t}/cr_only.cl", 0, {"2 moves"}},
      {"program_crlf_accepted", interpret + "{t}/crlf.ngc", 0, {"2 moves"}},
      {"program_very_long_line",
       interpret + "{t}/long_line.ngc",
       2,
       {"{t}/long_line.ngc:2:5: bad number format (conversion failed) parsing '7777",
        "(2000000 characters)"}},
      {"program_huge_number",
       interpret + "{t}/huge_number.ngc",
       2,
       {"{t}/huge_number.ngc:2:5: bad number format (conversion failed) parsing '9999", "(400 characters)"}},
      {"program_unsupported_code", interpret + "{t}/unsupported.ngc", 2, {"{t}/unsupported.ngc:3:3:", "G33"}},
      {"program_undefined_parameter",
       interpret + "{t}/undefined_parameter.ngc",
       2,
       {"{t}/undefined_parameter.ngc:2:5: Named parameter #<width> not defined"}},
      {"program_divide_by_zero",
       interpret + "{t}/divide_by_zero.ngc",
       2,
       {"{t}/divide_by_zero.ngc:3:", "Attempt to divide by zero"}},
      {"program_unclosed_oword",
       interpret + "{t}/unmatched_oword.ngc",
       2,
       {"{t}/unmatched_oword.ngc:", "o100"}},
      {"program_stray_endwhile",
       interpret + "{t}/stray_endwhile.ngc",
       2,
       {"{t}/stray_endwhile.ngc:3:1:", "o7 endwhile"}},
      {"program_recursion_too_deep",
       interpret + "{t}/recursion.ngc",
       2,
       {"{t}/recursion.ngc:2:", "Too many subroutine levels"}},
      {"program_endless_loop",
       interpret + "{t}/endless_loop.ngc --max-blocks 5000",
       2,
       {"{t}/endless_loop.ngc:", "5000"}},
      {"program_compensation_gouge", interpret + "{t}/gouge.ngc", 2, {"{t}/gouge.ngc:", "gouging"}},
      {"cl_nan_coordinate", interpret + "{t}/nan.cl", 2, {"{t}/nan.cl:3:8: bad number 'nan'"}},
      {"cl_unknown_statement",
       interpret + "{t}/unknown.cl",
       2,
       {"{t}/unknown.cl:3:3: unknown statement 'FROBNICATE'"}},
      {"cl_cutcom_without_cutter",
       interpret + "{t}/cutcom_no_cutter.apt",
       2,
       {"{t}/cutcom_no_cutter.apt:4:", "CUTCOM/LEFT needs the cutter's diameter (CUTTER/d or TLDATA)"}},
      {"cl_cycle_without_depth", interpret + "{t}/cycle_no_depth.apt", 2, {"{t}/cycle_no_depth.apt:3:"}},
      {"cl_nurbs_wrong_counts", interpret + "{t}/nurbs_counts.cls", 2, {"{t}/nurbs_counts.cls:4:"}},
      {"cl_trntyp_offset",
       interpret + "{t}/trntyp_offset.apt",
       2,
       {"{t}/trntyp_offset.apt:2:", "TRNTYP/WORLD with an offset is not supported"}},
      {"cl_catia_surface_motion",
       interpret + "{t}/catia_surface.aptsource",
       2,
       {"{t}/catia_surface.aptsource:5:1: 'TLON,GOFWD' is APT part-program motion"}},
      {"program_unknown_format",
       interpret + "{t}/nan.cl --format mastercam",
       2,
       {"unknown format 'mastercam': one of auto, gcode, apt, nx, creo, catia, solidworks"}},
      {"cl_continued_200k_lines",
       interpret + "{t}/continued.cl",
       2,
       {"{t}/continued.cl:200003:2: bad number '0 FINI'"},
       catalogue_write_continued_cl},
      {"program_beyond_joint_limit",
       plan_of("{t}/unreachable.ngc", "{m}") + "--out {t}/run",
       3,
       {"{t}/unreachable.ngc:3: ", "beyond limits.base_joint_max_deg", "hexapod_ch5.yaml:31"},
       plan_sentinel,
       "run"},
      // --- machine files: what the file is
      {"machine_is_directory",
       "check {t}/adir.yaml",
       2,
       {"{t}/adir.yaml: cannot read machine file: is a directory"}},
      {"machine_is_dev_zero", "check /dev/zero", 2, {"/dev/zero: cannot read machine file: is a device"}},
      {"machine_missing",
       "check {t}/nothing.yaml",
       2,
       {"{t}/nothing.yaml: cannot read machine file: No such file"}},
      {"machine_empty", "check {t}/m_empty.yaml", 2, {"{t}/m_empty.yaml:1:1: expected a mapping"}},
      {"machine_binary", "check {t}/m_binary.yaml", 2, {"{t}/m_binary.yaml:1:1: expected a mapping"}},
      // --- machine files: what is in them
      {"machine_bom_accepted", "check {t}/m_bom.yaml", 0, {"valid"}},
      {"machine_crlf_accepted", "check {t}/m_crlf.yaml", 0, {"valid"}},
      {"machine_cr_only_accepted", "check {t}/m_cr_only.yaml", 0, {"valid"}},
      {"machine_duplicate_key",
       "check {t}/m_duplicate.yaml",
       2,
       {"{t}/m_duplicate.yaml:6:1: home: given twice (first on line 5)"}},
      {"machine_duplicate_nested_key",
       "check {t}/m_duplicate_nested.yaml",
       2,
       {"{t}/m_duplicate_nested.yaml:8:3: limits.actuator_min: given twice (first on line 7)"}},
      {"machine_key_is_list",
       "check {t}/m_key_list.yaml",
       2,
       {"{t}/m_key_list.yaml:2:1: (top level): a key must be a plain word, not a list"}},
      {"machine_nested_key_is_list",
       "check {t}/m_key_nested.yaml",
       2,
       {"{t}/m_key_nested.yaml:7:3: limits: a key must be a plain word, not a list"}},
      {"machine_name_is_list",
       "check {t}/m_name_list.yaml",
       2,
       {"{t}/m_name_list.yaml:1:7: name: expected a word or a text, not a list"}},
      {"machine_deep_nesting",
       "check {t}/m_deep.yaml",
       2,
       {"{t}/m_deep.yaml:2:", ": not valid YAML: nested more than 499 levels deep"}},
      {"machine_empty_home",
       "check {t}/m_empty_home.yaml",
       2,
       {"{t}/m_empty_home.yaml:5:1: home: expected a list of 2 numbers, got nothing"}},
      {"machine_nan",
       "check {t}/m_nan.yaml",
       2,
       {"{t}/m_nan.yaml:3:11: base_joints[0][1]: expected a finite number"}},
      {"machine_huge_number",
       "check {t}/m_huge.yaml",
       2,
       {"{t}/m_huge.yaml:4:6: base_joints[1][0]: expected a finite number, got '1e999' (out of range)"}},
      {"machine_wrong_type",
       "check {t}/m_wrong_type.yaml",
       2,
       {"{t}/m_wrong_type.yaml:6:9: limits: expected a mapping of keys"}},
      {"machine_home_out_of_range",
       "check {t}/m_unreachable_home.yaml",
       2,
       {"{t}/m_unreachable_home.yaml:5:7: home: the home pose is outside the actuator range"}},
      {"machine_no_type",
       "check {t}/m_no_type.yaml",
       2,
       {"{t}/m_no_type.yaml:1:1: type: missing (expected a value)"}},
      {"machine_misspelt_section", "check {t}/m_typo.yaml", 2, {"{t}/m_typo.yaml:6:1: limit: unknown key"}},
      {"machine_wrong_angle_unit",
       "check {t}/m_units.yaml",
       2,
       {"{t}/m_units.yaml:2:9: angles: unknown angle convention 'radians'"}},
      {"machine_missing_section",
       "check {t}/m_missing_section.yaml",
       2,
       {"{t}/m_missing_section.yaml:1:1: base_joints: missing"}},
      {"machine_number_for_points",
       "check {t}/m_scalar_point.yaml",
       2,
       {"{t}/m_scalar_point.yaml:2:14: base_joints: expected a list of 2 points of 2 numbers, got a single "
        "value"}},
      {"machine_dynamics_negative_mass",
       "check {t}/m_dyn_negative_mass.yaml",
       2,
       {"{t}/m_dyn_negative_mass.yaml:7:23: dynamics.platform.mass_kg: a mass cannot be negative, got -2 "
        "kg"}},
      {"machine_dynamics_nan_mass",
       "check {t}/m_dyn_nan_mass.yaml",
       2,
       {"{t}/m_dyn_nan_mass.yaml:7:23: dynamics.platform.mass_kg: expected a finite number"}},
      {"machine_dynamics_impossible_inertia",
       "ik --machine {t}/m_dyn_inertia.yaml --pose 120,250",
       2,
       {"{t}/m_dyn_inertia.yaml:7:41: dynamics.platform.inertia_kg_m2: not the inertia of a real body"}},
      {"machine_dynamics_struts_list_length",
       "check {t}/m_dyn_struts.yaml",
       2,
       {"{t}/m_dyn_struts.yaml:9:5: dynamics.struts: expected one mapping for every strut or a list of 2 "
        "mappings (one per actuator), got a list of 1"}},
      {"machine_dynamics_zero_stiffness",
       "check {t}/m_dyn_stiffness.yaml",
       2,
       {"{t}/m_dyn_stiffness.yaml:8:61: dynamics.struts.stiffness_N_mm: must be positive, got 0 N/mm"}},
      {"machine_force_limit_zero",
       "check {t}/m_force_max.yaml",
       2,
       {"{t}/m_force_max.yaml:7:23: limits.actuator_force_max: must be positive"}},
      {"plan_machine_is_directory",
       plan_of("{line}", "{t}/adir.yaml") + "--out {t}/run",
       2,
       {"{t}/adir.yaml: cannot read machine file: is a directory"},
       plan_sentinel,
       "run"},
      // --- load files (optimize --load @FILE)
      {"load_inline_unknown_key",
       optimize + "--out {t}/o.ngc --load torque=5",
       2,
       {"pkm optimize: error: --load: 'torque=5': unknown key 'torque'"}},
      {"load_file_is_directory",
       optimize + "--out {t}/o.ngc --load @{t}/adir_load.yaml",
       2,
       {"--load: {t}/adir_load.yaml: cannot read load file: is a directory"}},
      {"load_file_duplicate_key",
       optimize + "--out {t}/o.ngc --load @{t}/load_duplicate.yaml",
       2,
       {"{t}/load_duplicate.yaml:3:3: default.tangential: given twice (first on line 2)"}},
      {"load_file_key_is_list",
       optimize + "--out {t}/o.ngc --load @{t}/load_key_list.yaml",
       2,
       {"{t}/load_key_list.yaml:2:3: default: a key must be a plain word"}},
      {"load_file_infinite_force",
       optimize + "--out {t}/o.ngc --load @{t}/load_nan.yaml",
       2,
       {"{t}/load_nan.yaml:3:13: blocks[0].normal", "finite"}},
      // --- numeric options
      {"plan_tolerance_negative",
       plan + "--out {t}/run --tolerance -1",
       2,
       {"--tolerance: must be ≥ 0 and ≤ 100 mm, got -1 mm"},
       plan_sentinel,
       "run"},
      {"plan_tolerance_nan",
       plan + "--out {t}/out --tolerance nan",
       2,
       {"--tolerance: must be a finite number"}},
      {"plan_override_zero",
       plan + "--out {t}/out --override 0",
       2,
       {"--override: must be > 0 and ≤ 200 %, got 0 %"}},
      {"plan_override_inf",
       plan + "--out {t}/out --override inf",
       2,
       {"--override: must be a finite number"}},
      {"plan_rate_huge", plan + "--out {t}/out --rate 1e308", 2, {"--rate: must be ≥ 1 and ≤ 100000 Hz"}},
      {"plan_rate_not_a_number",
       plan + "--out {t}/out --rate fast",
       2,
       {"--rate: expected a number", "'fast'"}},
      {"check_range_mm_nan", "check {m} --range-mm nan", 2, {"--range-mm: must be a finite number"}},
      {"check_range_mm_negative", "check {m} --range-mm -50", 2, {"--range-mm: must be ≥ 0"}},
      {"check_range_deg_huge", "check {m} --range-deg 1e308", 2, {"--range-deg: must be ≥ 0 and ≤ 180 deg"}},
      {"interpolate_period_zero",
       interpolate + "--out {t}/out --period-ms 0",
       2,
       {"--period-ms: must be ≥ 0.1 and ≤ 20 ms"}},
      {"interpolate_step_nan",
       interpolate + "--out {t}/out --step-mm nan",
       2,
       {"--step-mm: must be a finite number"}},
      {"interpolate_rho_negative",
       interpolate + "--out {t}/out --rho-max -1",
       2,
       {"--rho-max: must be ≥ 1e-06"}},
      {"interpolate_samples_fraction",
       interpolate + "--out {t}/out --error-samples 2.5",
       2,
       {"--error-samples: must be a whole number"}},
      {"interpolate_override_huge",
       interpolate + "--out {t}/out --override 1e308",
       2,
       {"--override: must be > 0 and ≤ 200 %"}},
      {"optimize_step_inf",
       optimize + "--out {t}/o.ngc --step-mm inf",
       2,
       {"--step-mm: must be a finite number"}},
      {"optimize_force_limit_negative",
       optimize + "--out {t}/o.ngc --force-limit -5",
       2,
       {"--force-limit: must be ≥ 0"}},
      {"bench_zero_poses",
       "bench kinematics --machine {m} --ik-poses 0",
       2,
       {"pkm bench kinematics: error: --ik-poses: must be ≥ 1"}},
      {"play_negative_periods", "play {t}/irun --periods -1", 2, {"--periods: must be ≥ 0"}},
      {"ik_pose_nan", "ik --machine {m} --pose nan,0,700,0,0,0", 2, {"--pose: 'nan' is not a number"}},
      {"ik_pose_huge", "ik --machine {m} --pose 1e308,0,700,0,0,0", 2, {"--pose: '1e308' is out of range"}},
      {"fk_actuators_inf",
       "fk --machine {m} --actuators inf,600,600,600,600,600",
       2,
       {"--actuators: 'inf' is not a number"}},
      {"ik_singular_pose", "jacobian --machine {m} --pose 0,0,150,0,0,0", 4, {"singular"}},
      {"unknown_option",
       "check {m} --frobnicate",
       2,
       {"pkm check: error: The following argument was not expected: --frobnicate"}},
      {"missing_required_option", "ik --pose 0,0,700,0,0,0", 2, {"pkm ik: error: --machine is required"}},
      // --- run folders read back (play, report)
      {"play_dev_zero", "play /dev/zero", 2, {"/dev/zero: cannot read the step stream: not a regular file"}},
      {"report_of_a_file", "report {t}/empty.ngc", 2, {"{t}/empty.ngc: no summary.json"}},
      {"report_summary_is_device",
       "report {t}/fake",
       2,
       {"{t}/fake/summary.json: cannot read run summary: is a device"},
       [](const fs::path& t) {
         fs::create_directories(t / "fake");
         fs::create_symlink("/dev/zero", t / "fake" / "summary.json");
       }},
      // --- outputs: a failure leaves the previous complete run, and no temporaries
      {"plan_report_is_directory",
       plan + "--out {t}/run --report {t}/adir.ngc",
       2,
       {"cannot write {t}/adir.ngc: Is a directory"},
       plan_sentinel,
       "run"},
      {"plan_path_csv_is_directory",
       plan + "--tables csv --out {t}/irun",
       2,
       {"cannot write {t}/irun/path.csv: Is a directory"},
       [](const fs::path& t) {
         catalogue_interpolate_sentinel(t);
         fs::create_directories(t / "irun" / "path.csv");
       },
       "irun"},
      {"interpolate_contour_csv_is_directory",
       interpolate + "--out {t}/run",
       2,
       {"cannot write {t}/run/contour.csv: Is a directory"},
       [](const fs::path& t) {
         catalogue_plan_sentinel(t);
         fs::create_directories(t / "run" / "contour.csv");
       },
       "run"},
      {"interpolate_report_is_directory",
       interpolate + "--out {t}/irun --report {t}/adir.ngc",
       2,
       {"cannot write {t}/adir.ngc: Is a directory"},
       interpolate_sentinel,
       "irun"},
      {"plan_report_folder_is_a_file",
       plan + "--out {t}/new/run --report {t}/empty.ngc/report.html",
       2,
       {"cannot create directory {t}/empty.ngc", "not a directory"},
       {},
       "new"},
      {"plan_out_is_a_file",
       plan + "--out {t}/empty.ngc",
       2,
       {"cannot create directory {t}/empty.ngc"},
       {},
       "empty.ngc"},
      {"plan_out_under_proc", plan + "--out /proc/pkm_no/run", 2, {"/proc/pkm_no/run"}},
      {"optimize_out_is_directory",
       optimize + "--out {t}/adir.ngc",
       2,
       {"cannot write {t}/adir.ngc: Is a directory"}},
      {"optimize_report_is_directory",
       optimize + "--out {t}/empty.ngc --report {t}/adir.cl",
       2,
       {"cannot write {t}/adir.cl: Is a directory"},
       {},
       "empty.ngc"},
  };
#if !PKM_REPORT_PAGE
  // Built without the report page (no Node.js): every report fails alike,
  // tests/cli/report_page_missing_test.cpp.
  std::erase_if(cases, [](const CatalogueCase& c) {
    return c.command.find("--report") != std::string::npos || c.command.rfind("report ", 0) == 0;
  });
#endif
  return cases;
}

// gtest prints a failing case by its name, not as bytes.
void PrintTo(const CatalogueCase& c, std::ostream* os) {
  *os << c.name;
}

class BadInputCatalogue : public testing::TestWithParam<CatalogueCase> {};

bool catalogue_has_raw_control_bytes(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n') || byte == 0x7F) return true;
  }
  return false;
}

TEST_P(BadInputCatalogue, FailsCleanly) {
  const CatalogueCase& c = GetParam();
  const fs::path t =
      fs::temp_directory_path() / ("pkm_catalogue_" + std::to_string(::getpid()) + "_" + c.name);
  fs::remove_all(t);
  fs::create_directories(t);
  catalogue_write_inputs(t);
  if (c.prepare) c.prepare(t);
  ASSERT_FALSE(testing::Test::HasFatalFailure());
  const fs::path watched = c.unchanged.empty() ? fs::path() : t / c.unchanged;
  const CatalogueSnapshot before = c.unchanged.empty() ? CatalogueSnapshot{} : catalogue_snapshot(watched);

  const std::string args = catalogue_expand(c.command, t);
  const CatalogueRun run = catalogue_run_pkm(args, t / "stderr.txt");

  EXPECT_FALSE(run.signalled) << "pkm " << args << " crashed: " << run.err;
  EXPECT_EQ(run.exit_code, c.exit_code) << "pkm " << args << "\nstderr: " << run.err;
  const std::string& where = c.exit_code == 0 ? run.out : run.err;
  for (const std::string& fragment : c.fragments) {
    const std::string expected = catalogue_expand(fragment, t);
    EXPECT_NE(where.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << where;
  }
  if (c.exit_code != 0) {
    EXPECT_NE(run.err.find("error:"), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n') <= 2, true) << "one line:\n" << run.err;
  }
  EXPECT_FALSE(catalogue_has_raw_control_bytes(run.err)) << run.err;
  if (!c.unchanged.empty()) {
    EXPECT_EQ(catalogue_snapshot(watched), before) << c.unchanged << " changed";
  }
  EXPECT_TRUE(catalogue_stray_temporaries(t).empty())
      << "left behind: " << testing::PrintToString(catalogue_stray_temporaries(t));
  if (!HasFailure()) fs::remove_all(t);
}

std::string catalogue_case_name(const testing::TestParamInfo<CatalogueCase>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInputCatalogue, testing::ValuesIn(catalogue_cases()), catalogue_case_name);

TEST(BadInputCatalogueSize, HasAtLeastSixtyCases) {
  EXPECT_GE(catalogue_cases().size(), 60u);
}

}  // namespace
}  // namespace pkm
