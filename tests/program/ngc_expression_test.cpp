// RS274/NGC expressions: LinuxCNC's precedence, functions and errors (checked against rs274 2.9 by hand),
// and random expression trees printed to RS274 text, evaluated both by the parser and by an independent
// recursive evaluator written here.
#include "program/ngc_expression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "program/ngc_parameter_store.hpp"

namespace ngc_et = pkm::program::ngc;

namespace {

// Evaluates `text` with `store` (numbered and named parameters).
pkm::Result<double> ngc_et_eval(const std::string& text, const ngc_et::ParameterStore& store) {
  ngc_et::EvaluationContext context;
  context.numbered = &store;
  return ngc_et::evaluate_expression_text(text, context, "e.ngc");
}

double ngc_et_value(const std::string& text) {
  ngc_et::ParameterStore store;
  auto result = ngc_et_eval(text, store);
  if (!result) {
    ADD_FAILURE() << text << ": " << result.error().message;
    return std::nan("");
  }
  return *result;
}

std::string ngc_et_error(const std::string& text) {
  ngc_et::ParameterStore store;
  auto result = ngc_et_eval(text, store);
  if (result) {
    ADD_FAILURE() << text << " gave " << *result << ", expected an error";
    return {};
  }
  return result.error().message;
}

}  // namespace

TEST(NgcExpression, PrecedenceIsLinuxCncs) {
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 + 2 * 3]"), 7.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[2 ** 3 ** 2]"), 64.0);  // left to right, as rs274
  EXPECT_DOUBLE_EQ(ngc_et_value("[-2 ** 2]"), 4.0);       // the sign belongs to the number
  EXPECT_DOUBLE_EQ(ngc_et_value("[-[2] ** 2]"), 4.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[10 - 4 - 3]"), 3.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[2 * 3 ** 2]"), 18.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 + 2 gt 2]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[2 + 3 gt 4 and 1]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 lt 2 xor 0]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[0 or 0]"), 0.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 + 2 * 3 - 4 / 2 ** 2 mod 3]"), 6.0);
}

TEST(NgcExpression, OperatorsAndFunctionsAsRs274) {
  EXPECT_DOUBLE_EQ(ngc_et_value("[5 mod -3]"), 2.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[-5 mod 3]"), 1.0);      // never negative
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 eq 1.00001]"), 1.0);  // EQ within 0.0001
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 ne 1.00001]"), 0.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1.00001 le 1]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1.00001 gt 1]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("round[-2.5]"), -3.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("round[2.4999]"), 2.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("fix[-2.5]"), -3.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("fup[-2.5]"), -2.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("abs[-3]"), 3.0);
  EXPECT_NEAR(ngc_et_value("sin[30]"), 0.5, 1e-15);
  EXPECT_NEAR(ngc_et_value("cos[60]"), 0.5, 1e-15);
  EXPECT_NEAR(ngc_et_value("tan[45]"), 1.0, 1e-15);
  EXPECT_NEAR(ngc_et_value("asin[0.5]"), 30.0, 1e-12);
  EXPECT_NEAR(ngc_et_value("acos[0.5]"), 60.0, 1e-12);
  EXPECT_NEAR(ngc_et_value("atan[1]/[-1]"), 135.0, 1e-12);
  EXPECT_NEAR(ngc_et_value("exp[1]"), std::exp(1.0), 1e-15);
  EXPECT_NEAR(ngc_et_value("ln[10]"), std::log(10.0), 1e-15);
  EXPECT_NEAR(ngc_et_value("SQRT[2]"), std::sqrt(2.0), 1e-15);
  EXPECT_DOUBLE_EQ(ngc_et_value("[1.]"), 1.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[.5]"), 0.5);
  EXPECT_DOUBLE_EQ(ngc_et_value("+3"), 3.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("-[1+2]"), -3.0);
  EXPECT_DOUBLE_EQ(ngc_et_value("[ 1 2 . 5 ]"), 12.5);  // blanks are ignored, also inside numbers
  EXPECT_DOUBLE_EQ(ngc_et_value("[1 A N D 1]"), 1.0);
}

TEST(NgcExpression, ParametersNumberedIndirectAndNamed) {
  ngc_et::ParameterStore store;
  store.set(2, 7.0);
  store.set(7, 3.5);
  store.set_named("Tool Length", 12.0);
  store.set_named("_Glob", -1.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("#2", store), 7.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("##2", store), 3.5);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("#[#2]", store), 3.5);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("#[5 + 2.00001]", store), 3.5);  // within 0.0001 of an integer
  EXPECT_DOUBLE_EQ(*ngc_et_eval("#<toollength>", store), 12.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("#< Tool Length >", store), 12.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("[#<_glob> * 2]", store), -2.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("exists[#<toollength>]", store), 1.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("exists[#<nothing>]", store), 0.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("exists[#5601]", store), 1.0);
  EXPECT_DOUBLE_EQ(*ngc_et_eval("exists[#5602]", store), 0.0);
}

TEST(NgcExpression, ErrorsCarryLinuxCncsReasonsAndColumns) {
  EXPECT_EQ(ngc_et_error("[1/0]"), "e.ngc:1:3: Attempt to divide by zero");
  EXPECT_EQ(ngc_et_error("asin[2]"), "e.ngc:1:1: Argument to asin out of range");
  EXPECT_EQ(ngc_et_error("acos[-2]"), "e.ngc:1:1: Argument to acos out of range");
  EXPECT_EQ(ngc_et_error("ln[0]"), "e.ngc:1:1: Zero or negative argument to ln");
  EXPECT_EQ(ngc_et_error("sqrt[-1]"), "e.ngc:1:1: Negative argument to sqrt");
  EXPECT_EQ(ngc_et_error("[1 + #<zz>]"), "e.ngc:1:6: Named parameter #<zz> not defined");
  EXPECT_EQ(ngc_et_error("foo[1]"), "e.ngc:1:1: Unknown word starting with f");
  EXPECT_EQ(ngc_et_error("kk[1]"), "e.ngc:1:1: Unknown word where unary operation could be");
  EXPECT_EQ(ngc_et_error("[1 ** ]"), "e.ngc:1:7: bad number format (conversion failed) parsing ''");
  EXPECT_EQ(ngc_et_error("[1 + 2"), "e.ngc:1:7: Unclosed expression");
  EXPECT_EQ(ngc_et_error("[-2 ** 0.5]"), "e.ngc:1:5: Attempt to raise negative to non integer power");
  EXPECT_EQ(ngc_et_error("[10 ** 400]"), "e.ngc:1:1: Calculation resulted in 'infinity'");
  EXPECT_EQ(ngc_et_error("[1 mod 0]"), "e.ngc:1:1: Calculation resulted in 'not a number'");
  EXPECT_EQ(ngc_et_error("[1 qq 2]"), "e.ngc:1:4: Unknown operation");
  EXPECT_EQ(ngc_et_error("[1 and 2 aa]"), "e.ngc:1:10: Unknown operation name starting with a");
  EXPECT_EQ(ngc_et_error("1.5.5"), "e.ngc:1:1: bad number format (trailing characters) parsing '1.5.5'");
  EXPECT_EQ(ngc_et_error("atan[1]"), "e.ngc:1:8: Slash missing after first atan argument");
  EXPECT_EQ(ngc_et_error("atan[1]/2"), "e.ngc:1:9: Left bracket missing after slash with atan");
  EXPECT_EQ(ngc_et_error("sin 1"), "e.ngc:1:5: Left bracket missing after unary operation name");
  EXPECT_EQ(ngc_et_error("#5602"), "e.ngc:1:1: Parameter number out of range");
  EXPECT_EQ(ngc_et_error("#0"), "e.ngc:1:1: Parameter number out of range");
  EXPECT_EQ(ngc_et_error("#1.5"), "e.ngc:1:1: Non integer value for integer");
  EXPECT_EQ(ngc_et_error("#<a"), "e.ngc:1:2: Named parameter not terminated");
  EXPECT_EQ(ngc_et_error("exists[1]"), "e.ngc:1:8: Expected # reading parameter");
  EXPECT_EQ(ngc_et_error(""), "e.ngc:1:1: No characters found in reading real value");
}

// ---- random expression trees against an independent evaluator ----

namespace {

// A tree as printed: a flat bracket `[v0 op v1 op v2 …]` whose precedence the printer leaves to the reader,
// a function, a negation, a number or a parameter.
struct NgcEtNode {
  enum Kind { number, parameter, named, negate, function, atan, flat } kind = number;
  double value = 0.0;
  int parameter_number = 0;
  std::string function_name;
  std::vector<std::unique_ptr<NgcEtNode>> operands;
  std::vector<std::string> operators;  ///< between operands (flat)
};

const char* const kNgcEtOperators[] = {"+",  "-",  "*",  "/",  "mod", "**", "eq", "ne",
                                       "gt", "ge", "lt", "le", "and", "or", "xor"};
const char* const kNgcEtFunctions[] = {"sin",   "cos",  "tan", "abs", "fix",  "fup",
                                       "round", "sqrt", "exp", "ln",  "asin", "acos"};

std::unique_ptr<NgcEtNode> ngc_et_random_tree(std::mt19937& random, int depth) {
  auto node = std::make_unique<NgcEtNode>();
  std::uniform_int_distribution<int> pick(0, depth <= 0 ? 2 : 7);
  const int choice = pick(random);
  if (choice == 0 || choice == 1) {
    node->kind = NgcEtNode::number;
    node->value = std::uniform_int_distribution<int>(-4000, 4000)(random) / 1000.0;
  } else if (choice == 2) {
    node->kind = std::uniform_int_distribution<int>(0, 1)(random) ? NgcEtNode::parameter : NgcEtNode::named;
    node->parameter_number = std::uniform_int_distribution<int>(1, 9)(random);
  } else if (choice == 3) {
    node->kind = NgcEtNode::negate;
    node->operands.push_back(ngc_et_random_tree(random, depth - 1));
  } else if (choice == 4) {
    node->kind = NgcEtNode::function;
    node->function_name = kNgcEtFunctions[std::uniform_int_distribution<int>(0, 11)(random)];
    node->operands.push_back(ngc_et_random_tree(random, depth - 1));
  } else if (choice == 5) {
    node->kind = NgcEtNode::atan;
    node->operands.push_back(ngc_et_random_tree(random, depth - 1));
    node->operands.push_back(ngc_et_random_tree(random, depth - 1));
  } else {
    node->kind = NgcEtNode::flat;
    const int count = std::uniform_int_distribution<int>(1, 5)(random);
    for (int i = 0; i < count; ++i) {
      node->operands.push_back(ngc_et_random_tree(random, depth - 1));
      if (i + 1 < count)
        node->operators.emplace_back(kNgcEtOperators[std::uniform_int_distribution<int>(0, 14)(random)]);
    }
  }
  return node;
}

std::string ngc_et_print(const NgcEtNode& node) {
  switch (node.kind) {
    case NgcEtNode::number: {
      char text[32];
      std::snprintf(text, sizeof text, "%.3f", node.value);
      return text;
    }
    case NgcEtNode::parameter:
      return "#" + std::to_string(node.parameter_number);
    case NgcEtNode::named:
      return "#<p" + std::to_string(node.parameter_number) + ">";
    case NgcEtNode::negate:
      return "-[" + ngc_et_print(*node.operands[0]) + "]";
    case NgcEtNode::function:
      return node.function_name + "[" + ngc_et_print(*node.operands[0]) + "]";
    case NgcEtNode::atan:
      return "atan[" + ngc_et_print(*node.operands[0]) + "]/[" + ngc_et_print(*node.operands[1]) + "]";
    case NgcEtNode::flat: {
      std::string text = "[";
      for (std::size_t i = 0; i < node.operands.size(); ++i) {
        if (i > 0) text += " " + node.operators[i - 1] + " ";
        text += ngc_et_print(*node.operands[i]);
      }
      return text + "]";
    }
  }
  return {};
}

// The independent evaluator: nullopt for anything LinuxCNC refuses (domain errors, NaN, infinity).
using NgcEtValue = std::optional<double>;

int ngc_et_level(const std::string& op) {
  if (op == "**") return 5;
  if (op == "*" || op == "/" || op == "mod") return 4;
  if (op == "+" || op == "-") return 3;
  if (op == "and" || op == "or" || op == "xor") return 1;
  return 2;  // relational
}

NgcEtValue ngc_et_apply(const std::string& op, double a, double b) {
  const double tolerance = 0.0001;
  if (op == "+") return a + b;
  if (op == "-") return a - b;
  if (op == "*") return a * b;
  if (op == "/") return b == 0.0 ? NgcEtValue{} : NgcEtValue{a / b};
  if (op == "mod") {
    const double r = std::fmod(a, b);
    return r < 0 ? r + std::fabs(b) : r;
  }
  if (op == "**") return (a < 0 && std::floor(b) != b) ? NgcEtValue{} : NgcEtValue{std::pow(a, b)};
  if (op == "eq") return std::fabs(a - b) < tolerance ? 1.0 : 0.0;
  if (op == "ne") return std::fabs(a - b) >= tolerance ? 1.0 : 0.0;  // NaN: 0, as LinuxCNC
  if (op == "gt") return a > b ? 1.0 : 0.0;
  if (op == "ge") return (a >= b || std::fabs(a - b) < tolerance) ? 1.0 : 0.0;
  if (op == "lt") return a < b ? 1.0 : 0.0;
  if (op == "le") return (a <= b || std::fabs(a - b) < tolerance) ? 1.0 : 0.0;
  if (op == "and") return (a != 0 && b != 0) ? 1.0 : 0.0;
  if (op == "or") return (a != 0 || b != 0) ? 1.0 : 0.0;
  return ((a != 0) != (b != 0)) ? 1.0 : 0.0;
}

NgcEtValue ngc_et_evaluate(const NgcEtNode& node, const double* parameters);

// Evaluates operands[first..] of a flat node down to operators of `level` or above, by precedence climbing
// (the parser uses an operator stack instead).
NgcEtValue ngc_et_climb(const NgcEtNode& node, const double* parameters, std::size_t& index, int level) {
  NgcEtValue left = ngc_et_evaluate(*node.operands[index], parameters);
  while (left && index < node.operators.size() && ngc_et_level(node.operators[index]) >= level) {
    const std::string& op = node.operators[index];
    ++index;
    NgcEtValue right = ngc_et_climb(node, parameters, index, ngc_et_level(op) + 1);
    if (!right) return right;
    left = ngc_et_apply(op, *left, *right);
  }
  return left;
}

NgcEtValue ngc_et_checked(NgcEtValue v) {
  return (v && std::isfinite(*v)) ? v : NgcEtValue{};
}

NgcEtValue ngc_et_function(const std::string& name, double x) {
  const long double pi = 3.141592653589793238462643383279502884L;
  const auto radians = static_cast<long double>(x) * pi / 180.0L;
  const auto degrees = [&](double r) {
    return static_cast<double>(static_cast<long double>(r) * 180.0L / pi);
  };
  if (name == "sin") return static_cast<double>(std::sin(radians));
  if (name == "cos") return static_cast<double>(std::cos(radians));
  if (name == "tan") return static_cast<double>(std::tan(radians));
  if (name == "abs") return std::fabs(x);
  if (name == "fix") return std::floor(x);
  if (name == "fup") return std::ceil(x);
  if (name == "round") return static_cast<double>(static_cast<long>(x + (x < 0 ? -0.5 : 0.5)));
  if (name == "sqrt") return x < 0 ? NgcEtValue{} : NgcEtValue{std::sqrt(x)};
  if (name == "exp") return std::exp(x);
  if (name == "ln") return x <= 0 ? NgcEtValue{} : NgcEtValue{std::log(x)};
  if (name == "asin") return (x < -1 || x > 1) ? NgcEtValue{} : NgcEtValue{degrees(std::asin(x))};
  return (x < -1 || x > 1) ? NgcEtValue{} : NgcEtValue{degrees(std::acos(x))};
}

NgcEtValue ngc_et_evaluate(const NgcEtNode& node, const double* parameters) {
  switch (node.kind) {
    case NgcEtNode::number:
      return node.value;
    case NgcEtNode::parameter:
    case NgcEtNode::named:
      return parameters[node.parameter_number];
    case NgcEtNode::negate: {
      NgcEtValue v = ngc_et_evaluate(*node.operands[0], parameters);
      return v ? NgcEtValue{-*v} : v;
    }
    case NgcEtNode::function: {
      NgcEtValue v = ngc_et_evaluate(*node.operands[0], parameters);
      return v ? ngc_et_checked(ngc_et_function(node.function_name, *v)) : v;
    }
    case NgcEtNode::atan: {
      NgcEtValue y = ngc_et_evaluate(*node.operands[0], parameters);
      NgcEtValue x = y ? ngc_et_evaluate(*node.operands[1], parameters) : y;
      if (!x) return x;
      const long double pi = 3.141592653589793238462643383279502884L;
      return static_cast<double>(static_cast<long double>(std::atan2(*y, *x)) * 180.0L / pi);
    }
    case NgcEtNode::flat: {
      std::size_t index = 0;
      return ngc_et_checked(ngc_et_climb(node, parameters, index, 0));
    }
  }
  return {};
}

}  // namespace

TEST(NgcExpression, RandomTreesAgreeWithAnIndependentEvaluator) {
  std::mt19937 random(20261206);
  ngc_et::ParameterStore store;
  double parameters[10] = {};
  for (int n = 1; n <= 9; ++n) {
    parameters[n] = (n - 5) * 0.75;
    store.set(n, parameters[n]);
    store.set_named("p" + std::to_string(n), parameters[n]);
  }
  int values = 0;
  int errors = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const auto tree = ngc_et_random_tree(random, 4);
    const std::string text = ngc_et_print(*tree);
    const NgcEtValue expected = ngc_et_evaluate(*tree, parameters);
    const auto actual = ngc_et_eval(text, store);
    if (!expected) {
      EXPECT_FALSE(actual.ok()) << text << " gave " << (actual ? *actual : 0.0);
      ++errors;
      continue;
    }
    ASSERT_TRUE(actual.ok()) << text << ": " << actual.error().message;
    EXPECT_NEAR(*actual, *expected, 1e-9 * std::max(1.0, std::fabs(*expected))) << text;
    ++values;
  }
  EXPECT_GT(values, 2000);  // the generator must mostly produce valid expressions
  EXPECT_GT(errors, 50);    // and some that LinuxCNC refuses
}

TEST(NgcExpression, EvaluationReusesItsBuffers) {
  const pkm::program::gcode::LineRef where{std::string("e.ngc"), 1};
  ngc_et::NormalizedLine line;
  ASSERT_TRUE(ngc_et::normalize_line("[#1 + sin[#2] * 2 ** 3 - [4 mod 3]]", where, line).ok());
  ngc_et::ExpressionCode code;
  ngc_et::ExpressionRef expression;
  std::size_t pos = 0;
  ASSERT_TRUE(ngc_et::parse_real_value(line, pos, where, code, expression).ok());
  ngc_et::ParameterStore store;
  store.set(1, 1.0);
  store.set(2, 90.0);
  ngc_et::EvaluationContext context;
  context.numbered = &store;
  ngc_et::ExpressionEvaluator evaluator;
  for (int i = 0; i < 3; ++i) {
    auto value = evaluator.evaluate(code, expression, context, where);
    ASSERT_TRUE(value.ok()) << value.error().message;
    EXPECT_DOUBLE_EQ(*value, 1.0 + 8.0 - 1.0);
  }
}
