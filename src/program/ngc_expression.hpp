#pragma once
// RS274/NGC expressions as LinuxCNC 2.9 reads them: numbers (`1.`, `.5`, `+3`), `#n`, `##n`, `#[expr]`,
// `#<name>`, bracketed expressions with `**` (highest), `* / MOD`, `+ -`, `EQ NE GT GE LT LE`, `AND OR XOR`
// (lowest), all left to right within a level, unary minus/plus binding tighter than `**` (so [-2**2] is 4),
// and the functions SIN COS TAN ASIN ACOS (degrees), ATAN[a]/[b], ABS EXP LN SQRT ROUND FIX FUP and
// EXISTS[#<name>]. Errors carry LinuxCNC's reasons ("Attempt to divide by zero", "Named parameter #<x> not
// defined", …) at file:line:column.
//
// An expression is parsed once into flat postfix code (ExpressionCode, reused line after line) and then
// evaluated on a value stack that keeps its capacity, so evaluation does not allocate once warm.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/gcode_lexer.hpp"

namespace pkm::program::ngc {

class ParameterStore;

/// A line as LinuxCNC's parser sees it: blanks removed and letters lower-cased outside comments (comments
/// are kept as written), each character with the 1-based column it had in the original line. `text` ends
/// with a '\0' sentinel that is not part of the line (size() excludes it).
struct NormalizedLine {
  std::string text;
  std::vector<int> columns;  ///< columns[i] for text[i]; columns[size()] is just past the line
  std::size_t size() const { return text.size() - 1; }
  char at(std::size_t i) const { return text[i]; }
  int column(std::size_t i) const { return columns[i < columns.size() ? i : columns.size() - 1]; }
};

/// Fills `out` from a raw line; fails (LinuxCNC's "Nested comment found" / "Unclosed comment found") at
/// the offending column.
Status normalize_line(std::string_view raw, const gcode::LineRef& where, NormalizedLine& out);

enum class OpCode : std::uint8_t {
  number,         ///< push value
  parameter,      ///< push #value (a constant number)
  parameter_at,   ///< pop n, push #n
  named,          ///< push #<name>
  exists_named,   ///< push 1 if #<name> exists, else 0
  exists_number,  ///< push 1 if the constant number is a parameter number
  exists_at,      ///< pop n, push 1 if n is a parameter number
  negate,
  check,  ///< refuse NaN and infinity (LinuxCNC checks every value it reads)
  abs,
  acos,
  asin,
  atan2,
  cos,
  exp,
  fix,
  fup,
  ln,
  round,
  sin,
  sqrt,
  tan,
  power,
  times,
  divide,
  modulo,
  plus,
  minus,
  eq,
  ne,
  gt,
  ge,
  lt,
  le,
  and_,
  or_,
  xor_,
};

struct Instruction {
  OpCode op = OpCode::number;
  int column = 0;                ///< where the operator, function, number or '#' was written
  double value = 0.0;            ///< number or parameter number
  std::uint32_t name_begin = 0;  ///< named parameters: the name in ExpressionCode::names
  std::uint32_t name_size = 0;
};

/// Where one expression's code lies in an ExpressionCode.
struct ExpressionRef {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  int column = 0;  ///< of its first character
};

/// The code of all expressions of one line; clear() keeps the capacity.
struct ExpressionCode {
  std::vector<Instruction> code;
  std::string names;  ///< normalised parameter names, back to back
  void clear() {
    code.clear();
    names.clear();
  }
  std::string_view name(const Instruction& instruction) const {
    return std::string_view(names).substr(instruction.name_begin, instruction.name_size);
  }
};

/// Parses a LinuxCNC "real value" at line.text[pos]: a number, a parameter, a function or a bracketed
/// expression, with leading unary signs; `pos` is left just after it.
Status parse_real_value(const NormalizedLine& line, std::size_t& pos, const gcode::LineRef& where,
                        ExpressionCode& code, ExpressionRef& out);
/// Parses a bracketed expression (line.text[pos] must be '[').
Status parse_bracketed_expression(const NormalizedLine& line, std::size_t& pos, const gcode::LineRef& where,
                                  ExpressionCode& code, ExpressionRef& out);
/// Reads a `<name>` at line.text[pos] (which must be '<'), normalised, appending it to `name`; LinuxCNC's
/// "Named parameter not terminated" when the '>' is missing.
Status read_parameter_name(const NormalizedLine& line, std::size_t& pos, const gcode::LineRef& where,
                           std::string& name);

/// What #<name> reads: the normalised name's value, or nullopt when it is not defined.
class NamedParameterSource {
 public:
  virtual ~NamedParameterSource() = default;
  virtual std::optional<double> named(std::string_view normalised_name) const = 0;
};

struct EvaluationContext {
  const ParameterStore* numbered = nullptr;
  const NamedParameterSource* names = nullptr;
  /// LinuxCNC reads undefined names as 0 inside a subroutine definition it is skipping.
  bool undefined_names_read_zero = false;
};

/// LinuxCNC's integer reading: a value within 0.0001 of an integer is that integer, anything else is
/// "Non integer value for integer".
bool near_integer(double value, int& out);

class ExpressionEvaluator {
 public:
  Result<double> evaluate(const ExpressionCode& code, const ExpressionRef& expression,
                          const EvaluationContext& context, const gcode::LineRef& where);

 private:
  /// Pushes what a numbered or named parameter instruction reads (or whether it exists).
  Status push_parameter(const ExpressionCode& code, const Instruction& instruction,
                        const EvaluationContext& context, const gcode::LineRef& where);
  std::vector<double> stack_;
};

/// Parses and evaluates `text` as one real value (tests, tools); the source is named `source_name`, line 1.
Result<double> evaluate_expression_text(std::string_view text, const EvaluationContext& context,
                                        const std::string& source_name = "expression");

}  // namespace pkm::program::ngc
