#include "io/yaml_stream_check.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <sstream>
#include <vector>

namespace pkm {

namespace {

// Sizes are summed with a ceiling: a bomb's true size overflows 64 bits long before the parser is done.
std::uint64_t yaml_saturating_add(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t ceiling = std::uint64_t{1} << 62;
  return std::min(ceiling, std::min(a, ceiling) + std::min(b, ceiling));
}

// Where the quoted text that opens at `open` ends: the offset of its closing quote, or npos. Inside "…" a
// backslash escapes the next byte; inside '…' a doubled '' is a quote.
std::size_t yaml_closing_quote(std::string_view text, std::size_t open) {
  const char quote = text[open];
  for (std::size_t i = open + 1; i < text.size(); ++i) {
    if (quote == '"' && text[i] == '\\') {
      ++i;
    } else if (text[i] == quote) {
      if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;
      } else {
        return i;
      }
    }
  }
  return std::string_view::npos;
}

}  // namespace

class YamlStreamEvents : public YAML::EventHandler {
 public:
  explicit YamlStreamEvents(YamlStreamCheck& check) : check_(check) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < check.text_.size(); ++i) {
      if (check.text_[i] == '\n') line_starts_.push_back(i + 1);
    }
  }

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ == 2) {
      fail(mark, "second YAML document",
           "a pkm file holds one document (remove this '---' line, or what follows it)");
    }
  }
  void OnDocumentEnd() override {}
  void OnAnchor(const YAML::Mark& /*mark*/, const std::string& name) override { pending_name_ = name; }

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                const std::string& /*value*/) override {
    check_quote(mark);
    leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (anchor == 0 || anchor >= anchors_.size()) return;  // yaml-cpp itself refuses an unknown anchor
    const Anchor& named = anchors_[anchor];
    if (named.open) {
      fail(mark, "alias *" + named.name,
           fmt::format("the alias is inside the node that &{} names ({}:{}): an endless cycle", named.name,
                       named.line, named.column));
      return;
    }
    alias_nodes_ = yaml_saturating_add(alias_nodes_, named.size);
    if (alias_nodes_ > kMaxYamlAliasNodes) {
      fail(mark, "alias *" + named.name,
           fmt::format("aliases expand the file to more than {} nodes (this one alone adds {}): refused as "
                       "an alias bomb",
                       kMaxYamlAliasNodes, named.size));
      return;
    }
    add_to_parent(named.size);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value style) override {
    open(mark, anchor, style == YAML::EmitterStyle::Flow ? '[' : 0);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value style) override {
    open(mark, anchor, style == YAML::EmitterStyle::Flow ? '{' : 0);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Anchor {
    std::string name;
    int line = 0;  // 1-based, for messages
    int column = 0;
    bool open = false;       // the node is still being read: an alias to it now is a cycle
    std::uint64_t size = 0;  // nodes of the node, its aliases expanded
  };
  struct OpenNode {
    YAML::anchor_t anchor;
    std::uint64_t size;
    bool flow;
  };

  Anchor& anchor_at(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (anchors_.size() <= anchor) anchors_.resize(anchor + 1);
    Anchor& named = anchors_[anchor];
    named.name = pending_name_;
    named.line = mark.line + 1;
    named.column = mark.column + 1;
    pending_name_.clear();
    return named;
  }
  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (anchor != 0) anchor_at(mark, anchor).size = 1;
    add_to_parent(1);
  }
  // `bracket`: '[' or '{' for a flow collection (0 for a block one), kept open for explain().
  void open(const YAML::Mark& mark, YAML::anchor_t anchor, char bracket) {
    if (anchor != 0) anchor_at(mark, anchor).open = true;
    stack_.push_back({anchor, 1, bracket != 0});
    if (bracket != 0) check_.open_flows_.push_back({mark.line + 1, mark.column + 1, bracket});
  }
  void close() {
    if (stack_.empty()) return;
    const OpenNode done = stack_.back();
    stack_.pop_back();
    if (done.flow && !check_.open_flows_.empty()) check_.open_flows_.pop_back();
    if (done.anchor != 0 && done.anchor < anchors_.size()) {
      anchors_[done.anchor].open = false;
      anchors_[done.anchor].size = done.size;
    }
    add_to_parent(done.size);
  }
  void add_to_parent(std::uint64_t size) {
    if (!stack_.empty()) stack_.back().size = yaml_saturating_add(stack_.back().size, size);
  }

  // A quoted scalar starts at its quote; yaml-cpp's marks count lines from 0 and columns in bytes.
  void check_quote(const YAML::Mark& mark) {
    if (mark.line < 0 || static_cast<std::size_t>(mark.line) >= line_starts_.size()) return;
    const std::string_view text = check_.text_;
    const std::size_t open = line_starts_[static_cast<std::size_t>(mark.line)] +
                             static_cast<std::size_t>(std::max(mark.column, 0));
    if (open >= text.size() || (text[open] != '"' && text[open] != '\'')) return;
    const std::size_t close = yaml_closing_quote(text, open);
    const std::size_t line_end = std::min(text.find('\n', open), text.size());
    if (close == std::string_view::npos) {
      fail(mark, "unclosed quote", fmt::format("the {} opened here is never closed", text[open]));
    } else if (close > line_end) {
      const auto close_line =
          std::upper_bound(line_starts_.begin(), line_starts_.end(), close) - line_starts_.begin();
      fail(mark, "unclosed quote",
           fmt::format("the {} opened here is not closed on this line (the next {} is on line {}); a "
                       "quoted text must end on the line where it starts",
                       text[open], text[open], close_line));
    }
  }

  // "FILE:LINE:COLUMN: WHAT: reason"; WHAT names the thing ("alias *r"), it is no key of the file.
  void fail(const YAML::Mark& mark, const std::string& what, const std::string& reason) {
    if (check_.found_) return;
    check_.found_ = check_.located(mark.line + 1, mark.column + 1, what, reason);
  }

  YamlStreamCheck& check_;
  std::vector<std::size_t> line_starts_;
  std::vector<Anchor> anchors_;  // by yaml-cpp's anchor number (1, 2, …; 0 is "no anchor")
  std::vector<OpenNode> stack_;
  std::string pending_name_;
  std::uint64_t alias_nodes_ = 0;
  int documents_ = 0;
};

YamlStreamCheck::YamlStreamCheck(std::string_view text, std::string source_name)
    : text_(text), source_(std::move(source_name)) {}

Error YamlStreamCheck::located(int line, int column, const std::string& what,
                               const std::string& reason) const {
  Error error =
      make_error(ErrorCode::bad_input, fmt::format("{}:{}:{}: {}: {}", source_, line, column, what, reason));
  error.location.file = source_;
  error.location.line = line;
  error.location.column = column;
  return error;
}

std::optional<Error> YamlStreamCheck::tab_indentation(int error_line) const {
  std::size_t start = 0;
  for (int line = 1; start <= text_.size() && line <= error_line; ++line) {
    const std::size_t end = std::min(text_.find('\n', start), text_.size());
    if (line >= error_line - 1) {
      const std::size_t indent_end = text_.find_first_not_of(" \t", start);
      const std::size_t tab = text_.find('\t', start);
      if (tab < std::min(indent_end, end)) {
        return located(line, static_cast<int>(tab - start) + 1, "not valid YAML",
                       "a TAB in the indentation (YAML indents with spaces only)");
      }
    }
    start = end + 1;
  }
  return std::nullopt;
}

std::optional<Error> YamlStreamCheck::explain(const YAML::Exception& e) const {
  if (found_) return found_;
  const std::string_view message = e.msg;
  if (!open_flows_.empty() &&
      (message == YAML::ErrorMsg::END_OF_SEQ_FLOW || message == YAML::ErrorMsg::END_OF_MAP_FLOW)) {
    const OpenFlow& open = open_flows_.back();
    return located(open.line, open.column, "not valid YAML",
                   fmt::format("the {} opened here is never closed with a {}", open.bracket,
                               open.bracket == '[' ? ']' : '}'));
  }
  if (!e.mark.is_null() && e.mark.line >= 0) return tab_indentation(e.mark.line + 1);
  return std::nullopt;
}

void YamlStreamCheck::run() {
  std::istringstream in{std::string(text_)};
  YAML::Parser parser(in);
  YamlStreamEvents events(*this);
  // The second document is refused at its start; reading it to its end costs no more than reading it.
  while (!found_ && parser.HandleNextDocument(events)) {
  }
}

}  // namespace pkm
