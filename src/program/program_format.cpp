#include "program/program_format.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace pkm::program {
namespace {

struct FormatEntry {
  ProgramFormat format;
  std::string_view key;
  std::string_view name;
};

constexpr std::array<FormatEntry, 7> kFormats = {{
    {ProgramFormat::automatic, "auto", "decided from the content"},
    {ProgramFormat::gcode, "gcode", "G-code (RS274/NGC)"},
    {ProgramFormat::apt, "apt", "APT CL data"},
    {ProgramFormat::nx, "nx", "NX CLSF"},
    {ProgramFormat::creo, "creo", "Pro/CLfile (Creo)"},
    {ProgramFormat::catia, "catia", "CATIA APT"},
    {ProgramFormat::solidworks, "solidworks", "SolidWorks CAM / CAMWorks APT"},
}};

char upper(char c) {
  return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

bool contains_upper(std::string_view text, std::string_view upper_needle) {
  if (upper_needle.size() > text.size()) return false;
  for (std::size_t i = 0; i + upper_needle.size() <= text.size(); ++i) {
    bool match = true;
    for (std::size_t k = 0; k < upper_needle.size() && match; ++k)
      match = upper(text[i + k]) == upper_needle[k];
    if (match) return true;
  }
  return false;
}

// The CAM system a "$$" comment names, if any.
ProgramFormat marker_of_comment(std::string_view comment) {
  if (contains_upper(comment, "PRO/CLFILE") || comment.starts_with("$$->")) return ProgramFormat::creo;
  if (contains_upper(comment, "CATIA")) return ProgramFormat::catia;
  if (contains_upper(comment, "CAMWORKS") || contains_upper(comment, "SOLIDWORKS")) {
    return ProgramFormat::solidworks;
  }
  if (contains_upper(comment, "CENTERLINE DATA") || contains_upper(comment, "SIEMENS") ||
      contains_upper(comment, "UNIGRAPHICS")) {
    return ProgramFormat::nx;
  }
  return ProgramFormat::automatic;
}

// Major words of APT CL data as CAM systems write them; the ones only NX writes name it.
constexpr std::array<std::string_view, 44> kClWords = {
    "GOTO",   "FROM",   "RAPID",  "FEDRAT",    "TLAXIS",      "UNITS",  "UNIT",        "MULTAX",    "CIRCLE",
    "END",    "FINI",   "SPINDL", "DELAY",     "CUTCOM",      "COOLNT", "LOADTL",      "LOAD",      "CUTTER",
    "PARTNO", "PPRINT", "INSERT", "TPRINT",    "MACHIN",      "SELECT", "CLEARP",      "OPSTOP",    "OPSKIP",
    "CYCLE",  "GOHOME", "ROTABL", "CSYS",      "TRNTYP",      "SETUP",  "OPFEATSTART", "OPFEATEND", "TOOLNO",
    "INDIRV", "AUTOPS", "STOP",   "TOOL PATH", "END-OF-PATH", "MSYS",   "PAINT",       "TLDATA",
};
constexpr std::array<std::string_view, 5> kNxWords = {"TOOL PATH", "END-OF-PATH", "MSYS", "PAINT", "TLDATA"};
// SolidWorks CAM and CAMWorks write no comment naming themselves; these words of theirs do.
constexpr std::array<std::string_view, 5> kSolidWorksWords = {"UNIT", "TRNTYP", "OPFEATSTART", "OPFEATEND",
                                                              "MOVE_ATTRIB"};

bool is_solidworks_word(std::string_view word) {
  return word.starts_with("CSI_SET_") ||
         std::find(kSolidWorksWords.begin(), kSolidWorksWords.end(), word) != kSolidWorksWords.end();
}

// "GOTO  /1,2" → "GOTO"; "tool path/x" → "TOOL PATH"; "" when the line does not start with a word of letters.
std::string leading_word(std::string_view line) {
  std::string word;
  bool blank = false;
  for (const char c : line) {
    if (c == '/' || c == ',' || c == '(') break;
    if (is_blank(c)) {
      blank = !word.empty();
      continue;
    }
    const char u = upper(c);
    if (!((u >= 'A' && u <= 'Z') || u == '-' || u == '_')) return {};
    if (blank) word.push_back(' ');
    blank = false;
    word.push_back(u);
  }
  return word;
}

// A G-code line: a letter and a number ("G1", "n10", "X-1.5", "#1=", "o100", "o<sub>"), a comment in
// parentheses, '%', ';' or a block-delete '/'.
bool looks_like_gcode(std::string_view line) {
  const char first = line.front();
  if (first == '(' || first == '%' || first == ';' || first == '/' || first == '#') return true;
  const char u = upper(first);
  if (u < 'A' || u > 'Z') return false;
  std::size_t i = 1;
  while (i < line.size() && is_blank(line[i])) ++i;
  if (i >= line.size()) return false;
  const char c = line[i];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == '#' || c == '[' ||
         (u == 'O' && c == '<');
}

}  // namespace

std::string_view program_format_key(ProgramFormat format) {
  for (const FormatEntry& e : kFormats)
    if (e.format == format) return e.key;
  return "?";
}

std::string_view program_format_name(ProgramFormat format) {
  for (const FormatEntry& e : kFormats)
    if (e.format == format) return e.name;
  return "?";
}

std::optional<ProgramFormat> parse_program_format(std::string_view key) {
  for (const FormatEntry& e : kFormats) {
    if (e.key.size() == key.size() && std::equal(key.begin(), key.end(), e.key.begin(),
                                                 [](char a, char b) { return upper(a) == upper(b); }))
      return e.format;
  }
  return std::nullopt;
}

std::string_view program_format_keys() {
  return "auto, gcode, apt, nx, creo, catia, solidworks";
}

bool is_cl_format(ProgramFormat format) {
  return format != ProgramFormat::automatic && format != ProgramFormat::gcode;
}

ProgramFormat detect_program_format(std::string_view text) {
  // The first lines decide: a CAM system names itself in its header, and a few hundred statements are
  // plenty to tell CL data from G-code (a mixed file is refused by whichever reader reads it).
  constexpr int kLinesToRead = 400;
  int cl_lines = 0, gcode_lines = 0, read = 0;
  ProgramFormat marker = ProgramFormat::automatic;
  bool nx_words = false, solidworks_words = false;
  std::size_t pos = 0;
  while (pos < text.size() && read < kLinesToRead) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    while (!line.empty() && is_blank(line.front())) line.remove_prefix(1);
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    if (line.empty()) continue;
    ++read;
    if (line.starts_with("$$")) {
      ++cl_lines;
      if (marker == ProgramFormat::automatic) marker = marker_of_comment(line);
      continue;
    }
    const std::string word = leading_word(line);
    const bool solidworks_word = is_solidworks_word(word);
    if (!word.empty() &&
        (solidworks_word || std::find(kClWords.begin(), kClWords.end(), word) != kClWords.end())) {
      ++cl_lines;
      nx_words = nx_words || std::find(kNxWords.begin(), kNxWords.end(), word) != kNxWords.end();
      solidworks_words = solidworks_words || solidworks_word;
      if (marker == ProgramFormat::automatic && (word == "PARTNO" || word == "PPRINT"))
        marker = marker_of_comment(line);
    } else if (looks_like_gcode(line)) {
      ++gcode_lines;
    }
  }
  if (cl_lines <= gcode_lines) return ProgramFormat::gcode;
  if (marker != ProgramFormat::automatic) return marker;
  if (nx_words) return ProgramFormat::nx;
  return solidworks_words ? ProgramFormat::solidworks : ProgramFormat::apt;
}

}  // namespace pkm::program
