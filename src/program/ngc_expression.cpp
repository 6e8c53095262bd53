#include "program/ngc_expression.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "program/ngc_parameter_store.hpp"

namespace pkm::program::ngc {

using gcode::error_at;
using gcode::LineRef;

namespace {

// LinuxCNC 2.9's TOLERANCE_EQUAL: EQ, NE, LE and GE treat values this close as equal.
constexpr double kExpressionEqualTolerance = 0.0001;
// LinuxCNC converts degrees with the long double pi (M_PIl); doing the same keeps the last bits equal.
constexpr long double kExpressionPiLong = 3.141592653589793238462643383279502884L;

bool expression_is_digit(char c) {
  return c >= '0' && c <= '9';
}

int expression_precedence(OpCode op) {
  switch (op) {
    case OpCode::and_:
    case OpCode::or_:
    case OpCode::xor_:
      return 2;
    case OpCode::eq:
    case OpCode::ne:
    case OpCode::gt:
    case OpCode::ge:
    case OpCode::lt:
    case OpCode::le:
      return 3;
    case OpCode::plus:
    case OpCode::minus:
      return 4;
    case OpCode::times:
    case OpCode::divide:
    case OpCode::modulo:
      return 5;
    case OpCode::power:
      return 6;
    default:
      return 1;  // the closing bracket
  }
}

void expression_emit(ExpressionCode& code, OpCode op, int column, double value = 0.0) {
  code.code.push_back(Instruction{op, column, value, 0, 0});
}

bool expression_starts_with(const NormalizedLine& line, std::size_t pos, std::string_view word) {
  return std::string_view(line.text).substr(pos, word.size()) == word;
}

// Reads a binary operator or the closing bracket at line.text[pos] (LinuxCNC's read_operation).
// `closing` tells the bracket apart from the operators.
Status expression_read_binary_operator(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                                       OpCode& op, bool& closing) {
  struct Named {
    std::string_view text;
    OpCode op;
  };
  static constexpr Named kNamed[] = {{"and", OpCode::and_}, {"mod", OpCode::modulo}, {"or", OpCode::or_},
                                     {"xor", OpCode::xor_}, {"eq", OpCode::eq},      {"ne", OpCode::ne},
                                     {"ge", OpCode::ge},    {"gt", OpCode::gt},      {"le", OpCode::le},
                                     {"lt", OpCode::lt}};
  const char c = line.at(pos);
  const int column = line.column(pos);
  closing = false;
  switch (c) {
    case ']':
      closing = true;
      ++pos;
      return ok_status();
    case '+':
      op = OpCode::plus;
      ++pos;
      return ok_status();
    case '-':
      op = OpCode::minus;
      ++pos;
      return ok_status();
    case '/':
      op = OpCode::divide;
      ++pos;
      return ok_status();
    case '*':
      op = line.at(pos + 1) == '*' ? OpCode::power : OpCode::times;
      pos += op == OpCode::power ? 2 : 1;
      return ok_status();
    case '\0':
      return error_at(where, column, "Unclosed expression");
    default:
      break;
  }
  for (const Named& named : kNamed) {
    if (named.text[0] == c && expression_starts_with(line, pos, named.text)) {
      op = named.op;
      pos += named.text.size();
      return ok_status();
    }
  }
  if (c == 'a' || c == 'm' || c == 'o' || c == 'x' || c == 'e' || c == 'n' || c == 'g' || c == 'l')
    return error_at(where, column, fmt::format("Unknown operation name starting with {}", c));
  return error_at(where, column, "Unknown operation");
}

// A number for a message: a run of millions of digits is named by its start and its length.
std::string expression_quoted_number(std::string_view run) {
  constexpr std::size_t kShown = 32;
  if (run.size() <= kShown) return fmt::format("'{}'", run);
  return fmt::format("'{}…' ({} characters)", run.substr(0, kShown), run.size());
}

// A number as LinuxCNC reads it: signs, then digits and points; the whole run must convert.
Status expression_parse_number(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                               ExpressionCode& code) {
  const std::size_t start = pos;
  std::size_t end = pos;
  while (line.at(end) == '+' || line.at(end) == '-') ++end;
  while (expression_is_digit(line.at(end)) || line.at(end) == '.') ++end;
  const std::string_view run = std::string_view(line.text).substr(start, end - start);
  std::size_t p = 0;
  bool negative = false;
  if (p < run.size() && (run[p] == '+' || run[p] == '-')) negative = run[p++] == '-';
  double value = 0.0;
  const char* first = run.data() + p;
  const char* last = run.data() + run.size();
  const bool starts_well = p < run.size() && (expression_is_digit(run[p]) || run[p] == '.');
  const auto [ptr, ec] = starts_well ? std::from_chars(first, last, value, std::chars_format::fixed)
                                     : std::from_chars_result{first, std::errc::invalid_argument};
  if (ec != std::errc())
    return error_at(
        where, line.column(start),
        fmt::format("bad number format (conversion failed) parsing {}", expression_quoted_number(run)));
  if (ptr != last)
    return error_at(
        where, line.column(start),
        fmt::format("bad number format (trailing characters) parsing {}", expression_quoted_number(run)));
  expression_emit(code, OpCode::number, line.column(start), negative ? -value : value);
  pos = end;
  return ok_status();
}

// `#…` at line.text[pos]: a name, or a real value giving the number. `exists` asks whether it exists.
Status expression_parse_parameter(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                                  ExpressionCode& code, bool exists) {
  const int column = line.column(pos);
  ++pos;
  if (line.at(pos) == '<') {
    const std::size_t begin = code.names.size();
    if (auto read = read_parameter_name(line, pos, where, code.names); !read) return read;
    code.code.push_back(Instruction{exists ? OpCode::exists_named : OpCode::named, column, 0.0,
                                    static_cast<std::uint32_t>(begin),
                                    static_cast<std::uint32_t>(code.names.size() - begin)});
    return ok_status();
  }
  const std::size_t first = code.code.size();
  ExpressionRef index;
  if (auto read = parse_real_value(line, pos, where, code, index); !read) return read;
  if (code.code.size() == first + 1 && code.code[first].op == OpCode::number) {
    code.code[first].op = exists ? OpCode::exists_number : OpCode::parameter;  // a constant number: #12
    code.code[first].column = column;
  } else {
    expression_emit(code, exists ? OpCode::exists_at : OpCode::parameter_at, column);
  }
  return ok_status();
}

struct ExpressionFunction {
  std::string_view name;
  OpCode op;
};
// In LinuxCNC's order of trial: a longer name sharing a first letter is tried where LinuxCNC tries it.
constexpr ExpressionFunction kExpressionFunctions[] = {
    {"abs", OpCode::abs},   {"acos", OpCode::acos}, {"asin", OpCode::asin},    {"atan", OpCode::atan2},
    {"cos", OpCode::cos},   {"exp", OpCode::exp},   {"exists", OpCode::check}, {"fix", OpCode::fix},
    {"fup", OpCode::fup},   {"ln", OpCode::ln},     {"round", OpCode::round},  {"sin", OpCode::sin},
    {"sqrt", OpCode::sqrt}, {"tan", OpCode::tan},
};

// EXISTS[#…]: LinuxCNC's read_bracketed_parameter.
Status expression_parse_exists(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                               ExpressionCode& code) {
  ++pos;  // '['
  if (line.at(pos) != '#') return error_at(where, line.column(pos), "Expected # reading parameter");
  if (auto read = expression_parse_parameter(line, pos, where, code, true); !read) return read;
  if (line.at(pos) != ']') return error_at(where, line.column(pos), "Expected ] reading bracketed parameter");
  ++pos;
  return ok_status();
}

// A function call at line.text[pos] (a letter): LinuxCNC's read_unary.
Status expression_parse_function(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                                 ExpressionCode& code) {
  const int column = line.column(pos);
  const char first = line.at(pos);
  const ExpressionFunction* found = nullptr;
  for (const ExpressionFunction& function : kExpressionFunctions) {
    if (function.name[0] == first && expression_starts_with(line, pos, function.name)) {
      found = &function;
      break;
    }
  }
  if (found == nullptr) {
    if (std::string_view("aceflrst").find(first) != std::string_view::npos)
      return error_at(where, column, fmt::format("Unknown word starting with {}", first));
    return error_at(where, column, "Unknown word where unary operation could be");
  }
  pos += found->name.size();
  if (line.at(pos) != '[')
    return error_at(where, line.column(pos), "Left bracket missing after unary operation name");
  if (found->name == "exists") return expression_parse_exists(line, pos, where, code);
  ExpressionRef argument;
  if (auto read = parse_bracketed_expression(line, pos, where, code, argument); !read) return read;
  if (found->op == OpCode::atan2) {
    if (line.at(pos) != '/')
      return error_at(where, line.column(pos), "Slash missing after first atan argument");
    ++pos;
    if (line.at(pos) != '[')
      return error_at(where, line.column(pos), "Left bracket missing after slash with atan");
    if (auto read = parse_bracketed_expression(line, pos, where, code, argument); !read) return read;
  }
  expression_emit(code, found->op, column);
  expression_emit(code, OpCode::check, column);
  return ok_status();
}

}  // namespace

Status normalize_line(std::string_view raw, const LineRef& where, NormalizedLine& out) {
  out.text.clear();
  out.columns.clear();
  bool comment = false;
  int comment_column = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const char c = raw[i];
    const int column = static_cast<int>(i) + 1;
    if (!comment && c == ';') {  // the rest of the line, as written
      for (; i < raw.size(); ++i) {
        out.text.push_back(raw[i]);
        out.columns.push_back(static_cast<int>(i) + 1);
      }
      break;
    }
    if (comment) {
      if (c == '(') return error_at(where, column, "Nested comment found");
      if (c == ')') comment = false;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      continue;
    } else if (c == '(') {
      comment = true;
      comment_column = column;
    }
    out.text.push_back((!comment && c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c);
    out.columns.push_back(column);
  }
  if (comment) return error_at(where, comment_column, "Unclosed comment found");
  out.text.push_back('\0');
  out.columns.push_back(static_cast<int>(raw.size()) + 1);
  return ok_status();
}

Status read_parameter_name(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                           std::string& name) {
  const int column = line.column(pos);
  for (std::size_t p = pos + 1; p < line.size(); ++p) {
    if (line.at(p) == '>') {
      pos = p + 1;
      return ok_status();
    }
    name.push_back(line.at(p));
  }
  return error_at(where, column, "Named parameter not terminated");
}

Status parse_real_value(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                        ExpressionCode& code, ExpressionRef& out) {
  out.begin = static_cast<std::uint32_t>(code.code.size());
  out.column = line.column(pos);
  const char c = line.at(pos);
  const char next = c == '\0' ? '\0' : line.at(pos + 1);
  Status status = ok_status();
  if (c == '\0') {
    status = error_at(where, line.column(pos), "No characters found in reading real value");
  } else if (c == '[') {
    ExpressionRef inner;
    status = parse_bracketed_expression(line, pos, where, code, inner);
    if (status) expression_emit(code, OpCode::check, out.column);
  } else if (c == '#') {
    status = expression_parse_parameter(line, pos, where, code, false);
  } else if ((c == '+' || c == '-') && next != '\0' && !expression_is_digit(next) && next != '.') {
    ++pos;  // a sign before a bracket, a parameter or a function
    ExpressionRef operand;
    status = parse_real_value(line, pos, where, code, operand);
    if (status && c == '-') expression_emit(code, OpCode::negate, out.column);
  } else if (c >= 'a' && c <= 'z') {
    status = expression_parse_function(line, pos, where, code);
  } else {
    status = expression_parse_number(line, pos, where, code);
  }
  out.end = static_cast<std::uint32_t>(code.code.size());
  return status;
}

Status parse_bracketed_expression(const NormalizedLine& line, std::size_t& pos, const LineRef& where,
                                  ExpressionCode& code, ExpressionRef& out) {
  out.begin = static_cast<std::uint32_t>(code.code.size());
  out.column = line.column(pos);
  ++pos;  // '['
  // Operators waiting for their right operand; precedences only rise along the stack, so five levels
  // (logical, relational, additive, multiplicative, power) bound its depth.
  struct Pending {
    OpCode op;
    int column;
  };
  Pending pending[8];
  int depth = 0;
  for (;;) {
    ExpressionRef operand;
    if (auto read = parse_real_value(line, pos, where, code, operand); !read) return read;
    const int column = line.column(pos);
    OpCode op = OpCode::check;
    bool closing = false;
    if (auto read = expression_read_binary_operator(line, pos, where, op, closing); !read) return read;
    const int level = closing ? 1 : expression_precedence(op);
    while (depth > 0 && expression_precedence(pending[depth - 1].op) >= level) {
      --depth;
      expression_emit(code, pending[depth].op, pending[depth].column);
    }
    if (closing) break;
    pending[depth++] = Pending{op, column};
  }
  out.end = static_cast<std::uint32_t>(code.code.size());
  return ok_status();
}

bool near_integer(double value, int& out) {
  if (!(std::fabs(value) < 2.0e9)) return false;
  const double below = std::floor(value);
  if (value - below > 0.9999) {
    out = static_cast<int>(std::ceil(value));
    return true;
  }
  out = static_cast<int>(below);
  return value - below <= 0.0001;
}

namespace {

double expression_to_degrees(double radians) {
  return static_cast<double>(static_cast<long double>(radians) * 180.0L / kExpressionPiLong);
}
long double expression_to_radians(double degrees) {
  return static_cast<long double>(degrees) * kExpressionPiLong / 180.0L;
}

// LinuxCNC's ROUND: half away from zero, through a C int.
double expression_round_like_linuxcnc(double value) {
  const double shifted = value + (value < 0.0 ? -0.5 : 0.5);
  if (!(std::fabs(shifted) < 2147483648.0)) return -2147483648.0;  // what the int conversion gives on x86
  return static_cast<double>(static_cast<int>(shifted));
}

// A function of one value; an error message (with `ok` false) for LinuxCNC's domain errors.
double expression_apply_function(OpCode op, double x, const char*& error) {
  switch (op) {
    case OpCode::abs:
      return std::fabs(x);
    case OpCode::acos:
      if (x < -1.0 || x > 1.0) error = "Argument to acos out of range";
      return expression_to_degrees(std::acos(x));
    case OpCode::asin:
      if (x < -1.0 || x > 1.0) error = "Argument to asin out of range";
      return expression_to_degrees(std::asin(x));
    case OpCode::cos:
      return static_cast<double>(std::cos(expression_to_radians(x)));
    case OpCode::exp:
      return std::exp(x);
    case OpCode::fix:
      return std::floor(x);
    case OpCode::fup:
      return std::ceil(x);
    case OpCode::ln:
      if (x <= 0.0) error = "Zero or negative argument to ln";
      return std::log(x);
    case OpCode::round:
      return expression_round_like_linuxcnc(x);
    case OpCode::sin:
      return static_cast<double>(std::sin(expression_to_radians(x)));
    case OpCode::sqrt:
      if (x < 0.0) error = "Negative argument to sqrt";
      return std::sqrt(x);
    case OpCode::tan:
      return static_cast<double>(std::tan(expression_to_radians(x)));
    default:
      return x;
  }
}

double expression_truth(bool value) {
  return value ? 1.0 : 0.0;
}

double expression_apply_binary(OpCode op, double a, double b, const char*& error) {
  switch (op) {
    case OpCode::power:
      if (a < 0.0 && std::floor(b) != b) error = "Attempt to raise negative to non integer power";
      return std::pow(a, b);
    case OpCode::times:
      return a * b;
    case OpCode::divide:
      if (b == 0.0) error = "Attempt to divide by zero";
      return a / b;
    case OpCode::modulo: {
      const double r = std::fmod(a, b);
      return r < 0.0 ? r + std::fabs(b) : r;  // LinuxCNC's MOD is never negative
    }
    case OpCode::plus:
      return a + b;
    case OpCode::minus:
      return a - b;
    case OpCode::eq:
      return expression_truth(std::fabs(a - b) < kExpressionEqualTolerance);
    case OpCode::ne:
      return expression_truth(std::fabs(a - b) >= kExpressionEqualTolerance);
    case OpCode::gt:
      return expression_truth(a > b);
    case OpCode::ge:
      return expression_truth(std::fabs(a - b) < kExpressionEqualTolerance || a >= b);
    case OpCode::lt:
      return expression_truth(a < b);
    case OpCode::le:
      return expression_truth(std::fabs(a - b) < kExpressionEqualTolerance || a <= b);
    case OpCode::and_:
      return expression_truth(a != 0.0 && b != 0.0);
    case OpCode::or_:
      return expression_truth(a != 0.0 || b != 0.0);
    case OpCode::xor_:
      return expression_truth((a != 0.0) != (b != 0.0));
    default:
      return a;
  }
}

}  // namespace

Status ExpressionEvaluator::push_parameter(const ExpressionCode& code, const Instruction& in,
                                           const EvaluationContext& context, const LineRef& where) {
  if (in.op == OpCode::named || in.op == OpCode::exists_named) {
    const std::string_view name = code.name(in);
    const std::optional<double> value = context.names->named(name);
    if (in.op == OpCode::exists_named) {
      stack_.push_back(expression_truth(value.has_value()));
    } else if (value) {
      stack_.push_back(*value);
    } else if (context.undefined_names_read_zero) {
      stack_.push_back(0.0);
    } else {
      return error_at(where, in.column, fmt::format("Named parameter #<{}> not defined", name));
    }
    return ok_status();
  }
  double raw = in.value;  // the constant number, or the value computed before this instruction
  if (in.op == OpCode::parameter_at || in.op == OpCode::exists_at) {
    raw = stack_.back();
    stack_.pop_back();
  }
  int number = 0;
  if (!near_integer(raw, number)) return error_at(where, in.column, "Non integer value for integer");
  const bool in_range = number >= 1 && number < kParameterCount;
  if (in.op == OpCode::exists_number || in.op == OpCode::exists_at) {
    stack_.push_back(expression_truth(in_range));
    return ok_status();
  }
  if (!in_range) return error_at(where, in.column, "Parameter number out of range");
  stack_.push_back(context.numbered->get(number));
  return ok_status();
}

Result<double> ExpressionEvaluator::evaluate(const ExpressionCode& code, const ExpressionRef& expression,
                                             const EvaluationContext& context, const LineRef& where) {
  stack_.clear();
  for (std::uint32_t i = expression.begin; i < expression.end; ++i) {
    const Instruction& in = code.code[i];
    const char* error = nullptr;
    switch (in.op) {
      case OpCode::number:
        stack_.push_back(in.value);
        break;
      case OpCode::parameter:
      case OpCode::parameter_at:
      case OpCode::exists_number:
      case OpCode::exists_at:
      case OpCode::named:
      case OpCode::exists_named:
        if (auto pushed = push_parameter(code, in, context, where); !pushed) return pushed.error();
        break;
      case OpCode::negate:
        stack_.back() = -stack_.back();
        break;
      case OpCode::check:
        if (std::isnan(stack_.back()))
          return error_at(where, in.column, "Calculation resulted in 'not a number'");
        if (std::isinf(stack_.back()))
          return error_at(where, in.column, "Calculation resulted in 'infinity'");
        break;
      case OpCode::atan2: {
        const double x = stack_.back();
        stack_.pop_back();
        stack_.back() = expression_to_degrees(std::atan2(stack_.back(), x));
        break;
      }
      case OpCode::abs:
      case OpCode::acos:
      case OpCode::asin:
      case OpCode::cos:
      case OpCode::exp:
      case OpCode::fix:
      case OpCode::fup:
      case OpCode::ln:
      case OpCode::round:
      case OpCode::sin:
      case OpCode::sqrt:
      case OpCode::tan:
        stack_.back() = expression_apply_function(in.op, stack_.back(), error);
        break;
      default: {
        const double b = stack_.back();
        stack_.pop_back();
        stack_.back() = expression_apply_binary(in.op, stack_.back(), b, error);
        break;
      }
    }
    if (error != nullptr) return error_at(where, in.column, error);
  }
  return stack_.empty() ? 0.0 : stack_.back();
}

namespace {

// Reads names straight from a store (no predefined names): what evaluate_expression_text offers.
class ExpressionStoreNames final : public NamedParameterSource {
 public:
  explicit ExpressionStoreNames(const ParameterStore& store) : store_(store) {}
  std::optional<double> named(std::string_view name) const override { return store_.named(name); }

 private:
  const ParameterStore& store_;
};

}  // namespace

Result<double> evaluate_expression_text(std::string_view text, const EvaluationContext& context,
                                        const std::string& source_name) {
  const LineRef where{source_name, 1};
  NormalizedLine line;
  if (auto normalized = normalize_line(text, where, line); !normalized) return normalized.error();
  ExpressionCode code;
  ExpressionRef expression;
  std::size_t pos = 0;
  if (auto parsed = parse_real_value(line, pos, where, code, expression); !parsed) return parsed.error();
  if (pos != line.size()) return error_at(where, line.column(pos), "Unexpected characters after expression");
  ExpressionEvaluator evaluator;
  EvaluationContext effective = context;
  std::optional<ExpressionStoreNames> store_names;
  if (effective.names == nullptr && effective.numbered != nullptr) {
    store_names.emplace(*effective.numbered);
    effective.names = &*store_names;
  }
  return evaluator.evaluate(code, expression, effective, where);
}

}  // namespace pkm::program::ngc
