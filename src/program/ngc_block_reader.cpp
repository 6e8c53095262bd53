// The RS274/NGC front end (contract in ngc_block_reader.hpp). The O-word control flow is LinuxCNC 2.9's own
// state machine, kept deliberately faithful (rs274 is the reference): a false condition, a loop exit, a
// break or a subroutine definition "skips" forward to the next O-word line with the same label; loops and
// calls jump back to the remembered position of a labelled line; a call of a subroutine not yet seen opens
// `<name>.ngc` on the subroutine path or, failing that, skips forward in the current file to its `sub` line.
// Labels other than sub/endsub/call/return are local to the subroutine they are in (LinuxCNC prefixes them
// with the subroutine's name). Jumps use byte offsets into text held in memory, so loops re-read nothing
// from disk and the reader's memory does not grow with the number of iterations.
//
// Known differences from rs274, on purpose: subroutine files are looked for on ReaderOptions::subroutine_path
// only (rs274 also tries the working directory and PROGRAM_PREFIX); lines longer than 255 characters are read
// (rs274 refuses them, "Command too long"); the end-of-file errors name the O-word that is not closed where
// rs274 says "File ended with no percent sign or program end"; the call depth bound is max_call_depth (rs274:
// 9 nested calls); reaching the end of the text (without M2 or '%') ends the program without an error.
#include "program/ngc_block_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <unordered_map>

#include "io/text_file.hpp"
#include "program/ngc_line_parser.hpp"
#include "program/ngc_parameter_store.hpp"

namespace pkm::program::ngc {

using gcode::error_at;
using gcode::LineRef;

// Named (not anonymous): BlockReader::Impl, which has external linkage, holds these types.
namespace reader_detail {

/// Where the next line starts, and the number of the line before it.
struct ReaderPosition {
  int file = 0;
  std::size_t offset = 0;
  int line = 0;
};

/// A labelled O-word line LinuxCNC remembers (its offset_map entry).
struct ReaderLabel {
  OKeyword type = OKeyword::none;
  ReaderPosition at;  ///< the start of the labelled line (jumping there re-reads it)
  int repeat_count = -1;
};

struct ReaderFrame {
  ReaderPosition return_to;
  std::string sub_name;
  int call_line = 0;  ///< the line of the call
  int call_file = 0;
};

struct ReaderNameHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};

// A scoped label ("sub#12", "#name", "name") as a program writes it: o12, o<name>.
std::string reader_written_label(std::string_view scoped) {
  const std::size_t hash = scoped.rfind('#');
  const std::string_view label = hash == std::string_view::npos ? scoped : scoped.substr(hash + 1);
  const bool number = !label.empty() && label.find_first_not_of("-0123456789") == std::string_view::npos;
  return number ? fmt::format("o{}", label) : fmt::format("o<{}>", label);
}

int reader_round_to_int(double x) {
  const double rounded = std::floor(x + 0.5);
  // LinuxCNC's (int) of a count beyond int's range gives INT_MIN on x86 (so `repeat [1e10]` runs its body
  // no time); in C++ that conversion is undefined, so the x86 answer is given here.
  if (!(std::fabs(rounded) < 2147483648.0)) return std::numeric_limits<int>::min();
  return static_cast<int>(rounded);
}

}  // namespace reader_detail

using namespace reader_detail;

struct BlockReader::Impl final : NamedParameterSource {
  Impl(std::string_view text, std::string source_name, const ReaderOptions& options_in,
       ParameterStore& parameters_in, const PredefinedParameters& predefined_in)
      : options(options_in), parameters(parameters_in), predefined(predefined_in) {
    texts.push_back(text);
    file_names.push_back(std::move(source_name));
  }

  // ---- what #<name> reads ----
  std::optional<double> named(std::string_view name) const override {
    if (auto value = parameters.named(name)) return value;
    if (name.empty() || name[0] != '_') return std::nullopt;
    if (name == "_value") return return_value;
    if (name == "_value_returned") return value_returned ? 1.0 : 0.0;
    if (name == "_call_level") return static_cast<double>(depth);
    return predefined.predefined(name);
  }
  bool is_predefined(std::string_view name) const {
    if (name.empty() || name[0] != '_') return false;
    return name == "_value" || name == "_value_returned" || name == "_call_level" ||
           predefined.predefined(name).has_value();
  }

  Result<bool> next(EvaluatedBlock& out);
  bool read_line();
  Result<bool> process_line(EvaluatedBlock& out);
  Status end_of_file_error() const;
  Status handle_o_word();
  Status read_o_word_values(OKeyword keyword, bool& ignore);
  Status control(OKeyword keyword);
  Status control_sub(OKeyword keyword);
  Status control_return(OKeyword keyword);
  Status control_call();
  Status control_loop(OKeyword keyword);
  Status control_if(OKeyword keyword);
  Status control_end_loop(OKeyword keyword);
  Status save_label(OKeyword type);
  Status jump_to(const ReaderLabel& label);
  Status open_subroutine_file();
  Result<double> evaluate(const ExpressionRef& expression, bool lenient = false);
  Status evaluate_items(EvaluatedBlock& out);
  Status count_executed();
  Status add_message(EvaluatedBlock& out);
  Error error(int column, std::string_view message) const { return error_at(where(), column, message); }
  LineRef where() const { return LineRef{file_names[static_cast<std::size_t>(file)], line}; }
  std::string line_text() const {  // as rs274 quotes it: without the blanks that end it
    std::string_view text = raw;
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
      text.remove_suffix(1);
    return std::string(text);
  }
  ReaderLabel* find_label() {
    auto found = labels.find(std::string_view(o_name));
    return found == labels.end() ? nullptr : &found->second;
  }
  bool skipping() const { return !skipping_o.empty(); }

  const ReaderOptions options;  ///< a copy: the caller's may be a temporary
  ParameterStore& parameters;
  const PredefinedParameters& predefined;

  std::vector<std::string_view> texts;  ///< [0] the caller's text, then the subroutine files' (owned below)
  std::vector<std::unique_ptr<std::string>> owned_texts;
  std::vector<std::string> file_names;

  // The line being read.
  ReaderPosition cursor;  ///< where the next line starts
  ReaderPosition line_start;
  int file = 0;
  int line = 0;
  std::string_view raw;
  NormalizedLine normalized;
  ParsedLine parsed;
  ExpressionEvaluator evaluator;
  std::string o_name;  ///< the current O-word's label, scoped as LinuxCNC scopes it
  std::string scratch;

  // LinuxCNC's O-word state.
  std::unordered_map<std::string, ReaderLabel, ReaderNameHash, std::equal_to<>> labels;
  std::string skipping_o;        ///< the label skipped to; empty when executing
  std::string skipping_to_sub;   ///< set while looking for a called subroutine's `sub` line
  ReaderPosition skipping_from;  ///< the line that started the skip (for errors at the end of the file)
  OKeyword skipping_keyword = OKeyword::none;
  bool defining_sub = false;
  std::string sub_name;  ///< the subroutine being defined (skipped) at level 0
  bool executed_if = false;
  bool doing_break = false;
  bool doing_continue = false;
  double test_value = 0.0;
  double return_value = 0.0;
  bool value_returned = false;
  double call_arguments[30] = {};
  int call_argument_count = 0;

  std::vector<ReaderFrame> frames;  ///< grows to the deepest call, never shrinks (no allocation per call)
  int depth = 0;

  bool percent_opened = false;
  bool any_block_yielded = false;  ///< a '%' after the first block ends the program (or is refused)
  bool finished = false;
  std::uint64_t executed = 0;
  int main_line = 0;

  std::vector<std::pair<int, double>> pending_numbers;
  std::vector<std::pair<std::uint32_t, double>> pending_names;  ///< item index, value
  std::string message_text;
};

// ---- reading lines ----

bool BlockReader::Impl::read_line() {
  const std::string_view text = texts[static_cast<std::size_t>(cursor.file)];
  if (cursor.offset >= text.size()) return false;
  line_start = cursor;
  const char* begin = text.data() + cursor.offset;
  const void* newline = std::memchr(begin, '\n', text.size() - cursor.offset);
  const std::size_t length = newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - begin)
                                     : text.size() - cursor.offset;
  raw = std::string_view(begin, length);
  cursor.offset += length + 1;
  cursor.line += 1;
  file = cursor.file;
  line = cursor.line;
  if (file == 0 && depth == 0) main_line = line;
  return true;
}

Status BlockReader::Impl::end_of_file_error() const {
  const LineRef at{file_names[static_cast<std::size_t>(skipping_from.file)], skipping_from.line};
  if (!skipping_to_sub.empty()) {
    const std::string& searched = file_names[static_cast<std::size_t>(cursor.file)];
    if (cursor.file != skipping_from.file)  // the subroutine's own file was found but does not define it
      return error_at(
          at, 1,
          fmt::format("subroutine o<{}> not found: {} has no 'o<{}> sub' (rs274: EOF seeking o-word "
                      "o<{}>)",
                      skipping_to_sub, searched, skipping_to_sub, skipping_to_sub));
    return error_at(
        at, 1,
        fmt::format("subroutine o<{}> not found: no '{}.ngc' on the subroutine path and no "
                    "'o<{}> sub' after this call in {} (rs274: EOF seeking o-word o<{}>)",
                    skipping_to_sub, skipping_to_sub, skipping_to_sub, searched, skipping_to_sub));
  }
  if (skipping()) {
    const char* closing = skipping_keyword == OKeyword::sub      ? "endsub"
                          : skipping_keyword == OKeyword::repeat ? "endrepeat"
                          : skipping_keyword == OKeyword::if_    ? "endif"
                                                                 : "endwhile";
    const std::string label = reader_written_label(skipping_o);
    return error_at(at, 1,
                    fmt::format("'{} {}' has no matching '{} {}': the file ends while skipping to it", label,
                                to_string(skipping_keyword), label, closing));
  }
  const ReaderFrame& frame = frames[static_cast<std::size_t>(depth - 1)];
  return error_at(
      LineRef{file_names[static_cast<std::size_t>(frame.call_file)], frame.call_line}, 1,
      fmt::format("subroutine o<{}> called here ends without 'o<{}> endsub' ({} ends)", frame.sub_name,
                  frame.sub_name, file_names[static_cast<std::size_t>(cursor.file)]));
}

Result<bool> BlockReader::Impl::next(EvaluatedBlock& out) {
  out.clear();
  if (finished) return false;
  for (;;) {
    if (!read_line()) {
      if (skipping() || !skipping_to_sub.empty() || depth > 0) return end_of_file_error().error();
      finished = true;
      return false;
    }
    auto produced = process_line(out);
    if (!produced || *produced || finished) return produced;
  }
}

// One line: true when it is a block for the executor, false when it was consumed here.
Result<bool> BlockReader::Impl::process_line(EvaluatedBlock& out) {
  if (skipping() && raw.find_first_of("oO%") == std::string_view::npos) return false;
  if (!skipping() && lex_simple_line(raw, out.words)) {  // most CAM lines: no expression to parse
    if (auto counted = count_executed(); !counted) return counted.error();
    if (out.words.empty()) return false;
    out.where = SourceRef{file, line, depth == 0 ? line : frames[0].call_line};
    any_block_yielded = true;
    return true;
  }
  out.words.clear();
  const LineRef here = where();
  if (auto parsed_ok = parse_line(raw, here, normalized, parsed, skipping()); !parsed_ok)
    return parsed_ok.error();
  if (parsed.percent) {
    if (!percent_opened && !any_block_yielded) {
      percent_opened = true;  // a '%' before the first block opens the program; the next one ends it
      return false;
    }
    if (!percent_opened) return error(1, "Bad character '%' used");
    finished = true;
    return false;
  }
  if (parsed.block_delete && options.block_delete) return false;
  if (parsed.is_o_word) {
    if (auto handled = handle_o_word(); !handled) return handled.error();
    return false;
  }
  if (skipping()) return false;
  if (auto counted = count_executed(); !counted) return counted.error();
  if (auto evaluated = evaluate_items(out); !evaluated) return evaluated.error();
  if (auto message = add_message(out); !message) return message.error();
  if (out.words.empty() && out.messages.empty()) return false;
  out.where = SourceRef{file, line, depth == 0 ? line : frames[0].call_line};
  out.block_delete = parsed.block_delete;
  any_block_yielded = true;
  return true;
}

Result<double> BlockReader::Impl::evaluate(const ExpressionRef& expression, bool lenient) {
  const EvaluationContext context{&parameters, this, lenient};
  return evaluator.evaluate(parsed.code, expression, context, where());
}

// Counts a line that is executed (not skipped) against max_blocks.
Status BlockReader::Impl::count_executed() {
  if (++executed > options.max_blocks)
    return error(1, fmt::format("more than {} blocks executed (the bound max_blocks; an endless loop?)",
                                options.max_blocks));
  return ok_status();
}

// ---- words and assignments ----

Status BlockReader::Impl::evaluate_items(EvaluatedBlock& out) {
  pending_numbers.clear();
  pending_names.clear();
  for (std::size_t i = 0; i < parsed.items.size(); ++i) {
    const LineItem& item = parsed.items[i];
    if (item.kind == ItemKind::set_number) {
      auto target = evaluate(item.target);
      if (!target) return target.error();
      int number = 0;
      if (!near_integer(*target, number)) return error(item.column, "Non integer value for integer");
      if (number < 1 || number >= kParameterCount) return error(item.column, "Parameter number out of range");
      if (ParameterStore::is_read_only(number)) return error(item.column, "Parameter is readonly");
      pending_numbers.emplace_back(number, 0.0);
    } else if (item.kind == ItemKind::set_named) {
      const std::string_view name =
          std::string_view(parsed.code.names).substr(item.name_begin, item.name_size);
      if (is_predefined(name))
        return error(item.column, fmt::format("Cannot assign to read-only parameter #<{}>", name));
      parameters.declare_named(name);  // LinuxCNC creates it while reading, before the value
      pending_names.emplace_back(static_cast<std::uint32_t>(i), 0.0);
    }
    double value = item.value;
    if (!item.constant) {
      auto evaluated = evaluate(item.expression);
      if (!evaluated) return evaluated.error();
      value = *evaluated;
    }
    if (item.kind == ItemKind::word) {
      out.words.push_back(gcode::Word{item.letter, value, item.column});
    } else if (item.kind == ItemKind::set_number) {
      pending_numbers.back().second = value;
    } else {
      pending_names.back().second = value;
    }
  }
  // All at once after the line, numbers first, as LinuxCNC does: `#1=2 #2=#1` gives #2 the old #1.
  for (const auto& [number, value] : pending_numbers) parameters.set(number, value);
  for (const auto& [index, value] : pending_names) {
    const LineItem& item = parsed.items[index];
    parameters.set_named(std::string_view(parsed.code.names).substr(item.name_begin, item.name_size), value);
  }
  return ok_status();
}

Status BlockReader::Impl::add_message(EvaluatedBlock& out) {
  const CommentKind kind = parsed.comment;
  if (kind == CommentKind::none || kind == CommentKind::plain) return ok_status();
  if (kind == CommentKind::msg) {
    out.messages.push_back(
        Message{MessageKind::msg, std::string(parsed.comment_text), parsed.comment_column});
    return ok_status();
  }
  if (kind == CommentKind::debug && !(parameters.get(5599) > 0.0)) return ok_status();  // #5599 gates DEBUG
  if (auto expanded = expand_parameters_in_comment(parsed.comment_text, parameters, *this, where(),
                                                   parsed.comment_column, message_text);
      !expanded)
    return expanded;
  if (kind == CommentKind::abort) return error(parsed.comment_column, message_text);
  out.messages.push_back(Message{kind == CommentKind::debug ? MessageKind::debug : MessageKind::print,
                                 message_text, parsed.comment_column});
  return ok_status();
}

// ---- O-words: reading (LinuxCNC's read_o) ----

Status BlockReader::Impl::handle_o_word() {
  const OWordHead& o = parsed.o;
  const OKeyword keyword = o.keyword;
  scratch.clear();
  if (o.named) {
    scratch = o.name;
  } else {
    auto number = evaluate(o.number);  // LinuxCNC reads the number even on lines it skips
    if (!number) return number.error();
    int n = 0;
    if (!near_integer(*number, n)) return error(o.column, "Non integer value for integer");
    fmt::format_to(std::back_inserter(scratch), "{}", n);
  }
  const bool global = keyword == OKeyword::sub || keyword == OKeyword::endsub || keyword == OKeyword::call ||
                      keyword == OKeyword::return_ || keyword == OKeyword::none;
  o_name.clear();
  if (!global) {
    if (depth > 0) {
      o_name = frames[static_cast<std::size_t>(depth - 1)].sub_name;
    } else if (defining_sub) {
      o_name = sub_name;
    }
    o_name.push_back('#');
  }
  o_name += scratch;
  bool ignore = false;
  if (auto read = read_o_word_values(keyword, ignore); !read) return read;
  if (ignore) return ok_status();
  if (skipping() && skipping_o != o_name) return ok_status();
  if (!skipping_to_sub.empty() && keyword != OKeyword::sub && keyword != OKeyword::none) return ok_status();
  if (!skipping())
    if (auto counted = count_executed(); !counted) return counted;
  return control(keyword);
}

// Reads what the O-word line carries (condition, returned value, call arguments) where LinuxCNC reads it;
// `ignore` when LinuxCNC leaves the line without effect.
Status BlockReader::Impl::read_o_word_values(OKeyword keyword, bool& ignore) {
  const int column = parsed.o.column;
  if (keyword == OKeyword::sub || keyword == OKeyword::none) {
    if (defining_sub) return error(column, "Nested subroutine definition");
    if (!skipping()) return parse_o_tail(normalized, where(), parsed);
    return ok_status();
  }
  const bool matches = !skipping() || skipping_o == o_name;
  if (keyword == OKeyword::endsub || keyword == OKeyword::return_) {
    if (!matches) {
      ignore = true;
      return ok_status();
    }
    if (auto tail = parse_o_tail(normalized, where(), parsed); !tail) return tail;
    double value = 0.0;  // evaluated before _value changes: `return [#<_value> * 2]` reads the old one
    if (!parsed.o_arguments.empty()) {
      auto evaluated = evaluate(parsed.o_arguments[0], defining_sub);
      if (!evaluated) return evaluated.error();
      value = *evaluated;
    }
    return_value = value;
    value_returned = !parsed.o_arguments.empty();
    return ok_status();
  }
  if (defining_sub || (keyword == OKeyword::call && skipping())) {
    ignore = true;
    return ok_status();
  }
  if (!matches) return ok_status();
  if (auto tail = parse_o_tail(normalized, where(), parsed); !tail) return tail;
  if (keyword == OKeyword::call) {
    call_argument_count = static_cast<int>(parsed.o_arguments.size());
    for (int i = 0; i < call_argument_count; ++i) {
      auto value = evaluate(parsed.o_arguments[static_cast<std::size_t>(i)]);
      if (!value) return value.error();
      call_arguments[i] = *value;
    }
  } else if (!parsed.o_arguments.empty()) {
    auto value = evaluate(parsed.o_arguments[0]);
    if (!value) return value.error();
    test_value = *value;
  }
  return ok_status();
}

// ---- O-words: control flow (LinuxCNC's convert_control_functions) ----

Status BlockReader::Impl::control(OKeyword keyword) {
  switch (keyword) {
    case OKeyword::none:
    case OKeyword::sub:
      return control_sub(keyword);
    case OKeyword::endsub:
    case OKeyword::return_:
      return control_return(keyword);
    case OKeyword::call:
      return control_call();
    case OKeyword::do_:
    case OKeyword::while_:
    case OKeyword::repeat:
      return control_loop(keyword);
    case OKeyword::if_:
    case OKeyword::elseif:
    case OKeyword::else_:
    case OKeyword::endif:
      return control_if(keyword);
    case OKeyword::break_:
    case OKeyword::continue_:
    case OKeyword::endwhile:
    case OKeyword::endrepeat:
      return control_end_loop(keyword);
  }
  return ok_status();
}

Status BlockReader::Impl::save_label(OKeyword type) {
  if (const ReaderLabel* existing = find_label()) {
    const bool same_line = existing->at.file == line_start.file && existing->at.line + 1 == line;
    if (same_line)
      return error(parsed.o.column, fmt::format("sub o<{}> found in illegal location (it was called before "
                                                "its definition was reached)",
                                                o_name));
    return error(parsed.o.column,
                 fmt::format("redefining sub o<{}>: already defined in {} line {}", o_name,
                             file_names[static_cast<std::size_t>(existing->at.file)], existing->at.line + 1));
  }
  labels.emplace(o_name, ReaderLabel{type, line_start, -1});
  return ok_status();
}

Status BlockReader::Impl::control_sub(OKeyword keyword) {
  if (skipping()) {  // reached the subroutine a call was looking for: remember it
    if (auto saved = save_label(keyword); !saved) return saved;
    skipping_o.clear();
  }
  skipping_to_sub.clear();
  if (keyword == OKeyword::none && depth != 0)
    return error(parsed.o.column, "Fanuc 'O....' subroutine must be called with 'M98'");
  if (keyword == OKeyword::none || depth != 0) return ok_status();  // a program number, or a call's entry
  if (defining_sub) return error(parsed.o.column, "Nested subroutine definition");
  if (auto saved = save_label(keyword); !saved) return saved;
  skipping_o = o_name;  // a definition: remember it and skip its body
  skipping_from = line_start;
  skipping_from.line = line;
  skipping_keyword = OKeyword::sub;
  defining_sub = true;
  sub_name = o_name;
  return ok_status();
}

Status BlockReader::Impl::control_return(OKeyword keyword) {
  if (depth == 0 && sub_name.empty())
    return error(parsed.o.column, fmt::format("not in a subroutine definition: '{}'", line_text()));
  if (skipping() && keyword == OKeyword::endsub) skipping_o.clear();
  if (depth > 0) {
    const ReaderFrame& frame = frames[static_cast<std::size_t>(depth - 1)];
    cursor = frame.return_to;
    parameters.pop_call();
    --depth;
    return ok_status();
  }
  if (keyword == OKeyword::endsub) {
    if (!defining_sub) return error(parsed.o.column, "Not in subroutine definition");
    skipping_o.clear();
    defining_sub = false;
    sub_name.clear();
  }
  return ok_status();
}

Status BlockReader::Impl::control_call() {
  if (depth >= options.max_call_depth)
    return error(parsed.o.column, fmt::format("Too many subroutine levels (more than {} nested calls, the "
                                              "bound max_call_depth)",
                                              options.max_call_depth));
  if (static_cast<std::size_t>(depth) == frames.size()) frames.emplace_back();
  ReaderFrame& frame = frames[static_cast<std::size_t>(depth)];
  frame.return_to = cursor;
  frame.sub_name = o_name;
  frame.call_line = line;
  frame.call_file = file;
  ++depth;
  parameters.push_call(call_arguments, call_argument_count);
  if (const ReaderLabel* label = find_label()) return jump_to(*label);
  if (auto found = open_subroutine_file(); !found) return found;
  skipping_o = o_name;  // look for its `sub` line: in the file just opened, or further down this one
  skipping_to_sub = o_name;
  skipping_from = line_start;
  skipping_from.line = line;
  skipping_keyword = OKeyword::call;
  return ok_status();
}

// Opens `<name>.ngc` from the subroutine path (LinuxCNC's SUBROUTINE_PATH) and moves the cursor to its start.
Status BlockReader::Impl::open_subroutine_file() {
  for (const std::string& folder : options.subroutine_path) {
    const std::string path = (std::filesystem::path(folder) / (o_name + ".ngc")).string();
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(path, ignored)) continue;
    auto text = read_text_file(path, "subroutine file");
    if (!text) return error(parsed.o.column, text.error().message);
    owned_texts.push_back(std::make_unique<std::string>(std::move(*text)));
    texts.emplace_back(*owned_texts.back());
    file_names.push_back(path);
    cursor = ReaderPosition{static_cast<int>(texts.size()) - 1, 0, 0};
    return ok_status();
  }
  return ok_status();
}

Status BlockReader::Impl::jump_to(const ReaderLabel& label) {
  cursor = label.at;
  return ok_status();
}

Status BlockReader::Impl::control_loop(OKeyword keyword) {
  ReaderLabel* label = find_label();
  if (keyword == OKeyword::do_) {
    skipping_o.clear();
    if (label == nullptr) labels.emplace(o_name, ReaderLabel{OKeyword::do_, line_start, -1});
    return ok_status();
  }
  const bool same_line = label != nullptr && label->at.file == line_start.file && label->at.line + 1 == line;
  if (label != nullptr && !same_line && !(keyword == OKeyword::while_ && label->type == OKeyword::do_))
    return error(parsed.o.column, fmt::format("duplicate O-word label: '{}' - defined in line {}",
                                              line_text(), label->at.line + 1));
  if (label == nullptr) label = &labels.emplace(o_name, ReaderLabel{keyword, line_start, -1}).first->second;
  skipping_o.clear();
  if (keyword == OKeyword::repeat) {
    if (label->type != OKeyword::repeat) return ok_status();
    if (label->repeat_count == -1) label->repeat_count = reader_round_to_int(test_value);
    if (label->repeat_count > 0) {
      --label->repeat_count;
      return ok_status();
    }
    label->repeat_count = -1;  // recomputed if the loop is entered again
  } else if (label->type == OKeyword::while_) {
    if (test_value != 0.0) return ok_status();
  } else {  // the `while` closing a `do`
    if (test_value != 0.0 && !doing_break) return jump_to(*label);
    doing_break = false;
    return ok_status();
  }
  skipping_o = o_name;
  skipping_from = line_start;
  skipping_from.line = line;
  skipping_keyword = keyword;
  return ok_status();
}

Status BlockReader::Impl::control_if(OKeyword keyword) {
  const ReaderLabel* label = find_label();
  if (keyword == OKeyword::if_) {
    if (label != nullptr && !(label->at.file == line_start.file && label->at.line + 1 == line))
      return error(parsed.o.column, fmt::format("duplicate O-word label - already defined in line {}: '{}'",
                                                label->at.line + 1, line_text()));
    if (label == nullptr) labels.emplace(o_name, ReaderLabel{OKeyword::if_, line_start, -1});
    executed_if = test_value != 0.0;
    if (executed_if) {
      skipping_o.clear();
    } else {
      skipping_o = o_name;
      skipping_from = line_start;
      skipping_from.line = line;
      skipping_keyword = OKeyword::if_;
    }
    return ok_status();
  }
  if (label == nullptr)
    return error(parsed.o.column, fmt::format("undefined O-word label: '{}'", line_text()));
  if (label->type != OKeyword::if_)
    return error(parsed.o.column, fmt::format("no matching 'if' label: '{}' (found '{}' in line {})",
                                              line_text(), to_string(label->type), label->at.line + 1));
  if (keyword == OKeyword::endif) {
    skipping_o.clear();
    executed_if = true;
  } else if (executed_if) {  // elseif/else after a branch ran: skip to the endif
    skipping_o = o_name;
  } else if (keyword == OKeyword::elseif ? test_value != 0.0 : skipping()) {
    skipping_o.clear();
    executed_if = true;
  }
  return ok_status();
}

Status BlockReader::Impl::control_end_loop(OKeyword keyword) {
  const ReaderLabel* label = find_label();
  if (label == nullptr)
    return error(parsed.o.column, fmt::format("undefined O-word label: '{}'", line_text()));
  const OKeyword type = label->type;
  if (keyword == OKeyword::break_ || keyword == OKeyword::continue_) {
    if (type != OKeyword::while_ && type != OKeyword::do_)
      return error(parsed.o.column, fmt::format("no matching while/do label: '{}' (found '{}' in line {})",
                                                line_text(), to_string(type), label->at.line + 1));
    // A continue met while already skipping to this label (the loop's condition was false) does nothing;
    // a break always marks a break, even then (LinuxCNC's flags, kept as they are: rs274 is the reference).
    if (keyword == OKeyword::continue_ && skipping()) return ok_status();
    if (!skipping()) {
      skipping_o = o_name;
      skipping_from = line_start;
      skipping_from.line = line;
      skipping_keyword = keyword;
    }
    if (keyword == OKeyword::break_) {
      doing_break = true;
    } else {
      doing_continue = true;
    }
    return ok_status();
  }
  if ((keyword == OKeyword::endrepeat && type != OKeyword::repeat) ||
      (keyword == OKeyword::endwhile && type != OKeyword::while_))
    return error(parsed.o.column, fmt::format("no matching label: '{}' (found '{}' in line {})", line_text(),
                                              to_string(type), label->at.line + 1));
  if (skipping() && skipping_o == o_name) {  // the loop ended (or a continue skipped here)
    skipping_o.clear();
    if (!doing_continue) return ok_status();
    doing_continue = false;
  }
  return jump_to(*label);
}

// ---- BlockReader ----

BlockReader::BlockReader(std::string_view text, std::string source_name, const ReaderOptions& options,
                         ParameterStore& parameters, const PredefinedParameters& predefined)
    : impl_(std::make_unique<Impl>(text, std::move(source_name), options, parameters, predefined)) {}

BlockReader::~BlockReader() = default;

Result<bool> BlockReader::next(EvaluatedBlock& out) {
  return impl_->next(out);
}

const std::vector<std::string>& BlockReader::files() const {
  return impl_->file_names;
}

int BlockReader::main_line() const {
  return impl_->main_line;
}

}  // namespace pkm::program::ngc
