// The RS274/NGC front end: assignments, messages, every O-word control-flow form, subroutines (in the program
// and in files on the subroutine path), bounds and errors with file:line:column. Expected messages were
// produced by LinuxCNC's rs274 (2.9) on the same programs.
#include "program/ngc_block_reader.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "program/ngc_parameter_store.hpp"

namespace ngc_brt = pkm::program::ngc;

namespace {

class NgcBrtMachine final : public ngc_brt::PredefinedParameters {
 public:
  std::optional<double> predefined(std::string_view name) const override {
    if (name == "_x") return 1.5;
    if (name == "_metric") return 1.0;
    return std::nullopt;
  }
};

struct NgcBrtRun {
  std::vector<ngc_brt::EvaluatedBlock> blocks;
  std::vector<std::string> messages;  ///< every message's text, in order
  std::string error;                  ///< empty when the program ran to its end
  std::vector<std::string> files;
  int main_line = 0;
};

// Runs `text` (named t.ngc) until the reader ends, an error, or an M2/M30 block.
NgcBrtRun ngc_brt_run(const std::string& text, const ngc_brt::ReaderOptions& options = {},
                      ngc_brt::ParameterStore* parameters = nullptr) {
  ngc_brt::ParameterStore own;
  NgcBrtMachine machine;
  ngc_brt::BlockReader reader(text, "t.ngc", options, parameters ? *parameters : own, machine);
  NgcBrtRun run;
  ngc_brt::EvaluatedBlock block;
  for (;;) {
    auto next = reader.next(block);
    if (!next) {
      run.error = next.error().message;
      break;
    }
    if (!*next) break;
    for (const auto& message : block.messages) run.messages.push_back(message.text);
    run.blocks.push_back(block);
    bool end = false;
    for (const auto& word : block.words)
      end = end || (word.letter == 'M' && (word.value == 2 || word.value == 30));
    if (end) break;
  }
  run.files = reader.files();
  run.main_line = reader.main_line();
  return run;
}

std::string ngc_brt_messages(const std::string& text, const ngc_brt::ReaderOptions& options = {}) {
  const NgcBrtRun run = ngc_brt_run(text, options);
  EXPECT_EQ(run.error, "") << text;
  std::string joined;
  for (const auto& message : run.messages) joined += message + "|";
  return joined;
}

std::string ngc_brt_error(const std::string& text, const ngc_brt::ReaderOptions& options = {}) {
  const NgcBrtRun run = ngc_brt_run(text, options);
  EXPECT_NE(run.error, "") << "expected an error for:\n" << text;
  return run.error;
}

}  // namespace

TEST(NgcBlockReader, WordsCarryValuesAndColumns) {
  const NgcBrtRun run = ngc_brt_run("N10 g1 X[1+2] y-#<_x> f 1 2 0 0\n/G0 Z5\nm2\n");
  ASSERT_EQ(run.error, "");
  ASSERT_EQ(run.blocks.size(), 2u);  // the block-delete line is skipped
  const auto& words = run.blocks[0].words;
  ASSERT_EQ(words.size(), 4u);
  EXPECT_EQ(words[0].letter, 'G');
  EXPECT_EQ(words[0].column, 5);
  EXPECT_DOUBLE_EQ(words[1].value, 3.0);
  EXPECT_EQ(words[1].column, 8);
  EXPECT_DOUBLE_EQ(words[2].value, -1.5);
  EXPECT_DOUBLE_EQ(words[3].value, 1200.0);
  EXPECT_EQ(run.blocks[0].where.line, 1);
  ngc_brt::ReaderOptions keep;
  keep.block_delete = false;
  const NgcBrtRun kept = ngc_brt_run("/G0 Z5\nm2\n", keep);
  ASSERT_EQ(kept.blocks.size(), 2u);
  EXPECT_TRUE(kept.blocks[0].block_delete);
}

TEST(NgcBlockReader, AssignmentsTakeEffectAfterTheLine) {
  ngc_brt::ParameterStore parameters;
  const NgcBrtRun run = ngc_brt_run("#1=2 #2=#1 G1 X#1\n#<a>=[#<a>+1] #<b>=#<a>\nm2\n", {}, &parameters);
  ASSERT_EQ(run.error, "");
  EXPECT_DOUBLE_EQ(run.blocks[0].words[1].value, 0.0);  // X read the old #1
  EXPECT_DOUBLE_EQ(parameters.get(1), 2.0);
  EXPECT_DOUBLE_EQ(parameters.get(2), 0.0);  // #2 got the old #1, as in rs274
  // LinuxCNC creates #<a> while reading the line, so its own value reads it as 0.
  EXPECT_EQ(parameters.named("a"), 1.0);
  EXPECT_EQ(parameters.named("b"), 0.0);
}

TEST(NgcBlockReader, MessagesAsRs274PrintsThem) {
  EXPECT_EQ(ngc_brt_messages("#1=5 (DEBUG,#1)\nm2\n"), "5.000000|");
  EXPECT_EQ(ngc_brt_messages("#2=2 #3=#2 (debug, #3 %d#2 %f#2 %.2f#2 #<_foo> #5602 #0)\nm2\n"),
            " 0.000000 2 2.0000 2.00 ###### ###### 0.00|");
  EXPECT_EQ(ngc_brt_messages("(MSG,first) (MSG,second)\n( msg, spaced)\n(MSG ,plain comment)\nm2\n"),
            "second| spaced|");
  EXPECT_EQ(ngc_brt_messages("#1=5\n(DEBUG,[#1] #< a b > #<nope> #[1] #1.5)\nm2\n"),
            "[5.000000] ###### ###### #[1] 5.000000.5|");
  EXPECT_EQ(ngc_brt_messages("(DEBUG,#<_x> #<_value> #<_value_returned>)\n#5599=0\n(DEBUG,hidden)\nm2\n"),
            "1.500000 0.000000 0.000000|");
  const NgcBrtRun run = ngc_brt_run("(PRINT,p=%d#5599)\nm2\n");
  ASSERT_EQ(run.blocks.size(), 2u);
  EXPECT_EQ(run.blocks[0].messages[0].kind, ngc_brt::MessageKind::print);
  EXPECT_EQ(run.blocks[0].messages[0].text, "p=1");
  EXPECT_EQ(run.blocks[0].messages[0].column, 1);
  EXPECT_EQ(ngc_brt_error("#1=7\n(ABORT,stopped at #1)\nm2\n"), "t.ngc:2:1: stopped at 7.000000");
}

TEST(NgcBlockReader, IfElseifElse) {
  const std::string program =
      "#1=[#1+1]\n"
      "o1 if [#1 eq 1]\n(DEBUG,one)\n"
      "  o2 if [0]\n(DEBUG,never)\n  o2 else\n(DEBUG,inner else)\n  o2 endif\n"
      "o1 elseif [#1 eq 2]\n(DEBUG,two)\n"
      "o1 else\n(DEBUG,other)\n"
      "o1 endif\n";
  EXPECT_EQ(ngc_brt_messages(program + "m2\n"), "one|inner else|");
  EXPECT_EQ(ngc_brt_messages("#1=1\n" + program + "m2\n"), "two|");
  EXPECT_EQ(ngc_brt_messages("#1=5\n" + program + "m2\n"), "other|");
}

TEST(NgcBlockReader, WhileWithBreakAndContinue) {
  // rs274 prints exactly these messages for this program.
  EXPECT_EQ(ngc_brt_messages("#1=0\no2 while [#1 lt 5]\n#1=[#1+1]\no3 if [#1 eq 2]\no2 continue\n"
                             "o3 elseif [#1 eq 4]\no2 break\no3 else\n(DEBUG,e#1)\no3 endif\n(DEBUG,b#1)\n"
                             "o2 endwhile\n(DEBUG,end #1)\nm2\n"),
            "e1.000000|b1.000000|e3.000000|b3.000000|end 4.000000|");
}

TEST(NgcBlockReader, AContinueInTheBodyOfALoopThatEndsIsSkippedOver) {
  // When the condition turns false, rs274 skips the body to the endwhile; the continue it passes must not
  // send it round again.
  EXPECT_EQ(ngc_brt_messages("#1=0\no1 while [#1 lt 2]\n#1=[#1+1]\no2 if [#1 gt 4]\no1 continue\no2 endif\n"
                             "o1 endwhile\n(DEBUG,done %d#1)\nm2\n"),
            "done 2|");
}

TEST(NgcBlockReader, DoWhileRepeatAndNesting) {
  EXPECT_EQ(ngc_brt_messages("#1=0\no5 do\n#1=[#1+1]\n(DEBUG,d#1)\no5 while [#1 lt 3]\nm2\n"),
            "d1.000000|d2.000000|d3.000000|");
  EXPECT_EQ(ngc_brt_messages("o1 do\n(DEBUG,once)\no1 while [0]\nm2\n"), "once|");
  EXPECT_EQ(ngc_brt_messages(
                "o1 repeat [3]\n(DEBUG,r)\no1 endrepeat\no2 repeat [0]\n(DEBUG,no)\no2 endrepeat\nm2\n"),
            "r|r|r|");
  EXPECT_EQ(
      ngc_brt_messages("#10=0\no7 while [#10 lt 2]\n#11=0\no8 repeat [2]\n#11=[#11+1]\n(DEBUG,%d#10 #11)\n"
                       "o8 endrepeat\n#10=[#10+1]\no7 endwhile\nm2\n"),
      "0 1|0 2|1 1|1 2|");
  EXPECT_EQ(ngc_brt_messages("#1=0\no1 do\n#1=[#1+1]\no2 if [#1 eq 3]\no1 break\no2 endif\no1 while [1]\n"
                             "(DEBUG,%d#1)\nm2\n"),
            "3|");
}

// A count beyond int's range: LinuxCNC's (int) gives INT_MIN on x86, so the body runs no time; in C++ the
// conversion was undefined (found by fuzz/fuzz_gcode's UBSan).
TEST(NgcBlockReader, RepeatCountsBeyondIntRunTheBodyNoTime) {
  EXPECT_EQ(ngc_brt_messages("o1 repeat [10**30]\n(DEBUG,r)\no1 endrepeat\n(DEBUG,after)\nm2\n"), "after|");
  EXPECT_EQ(ngc_brt_messages("o1 repeat [-10**30]\n(DEBUG,r)\no1 endrepeat\n(DEBUG,after)\nm2\n"), "after|");
}

TEST(NgcBlockReader, SubroutinesArgumentsReturnValuesAndRecursion) {
  EXPECT_EQ(ngc_brt_messages("o<s> call [3]\n(DEBUG,v=#<_value> r=#<_value_returned>)\n"
                             "o<s2> call [1] [2] [3]\n(DEBUG,v=#<_value> r=#<_value_returned> #1)\nm2\n"
                             "o<s> sub\n(DEBUG,in #1)\no<s> endsub [#1*2]\n"
                             "o<s2> sub\n#<loc>=[#1+#2+#3]\n(DEBUG,s2 #<loc> #<_call_level>)\no<s2> return\n"
                             "o<s2> endsub\nm2\n"),
            "in 3.000000|v=6.000000 r=1.000000|s2 6.000000 1.000000|v=0.000000 r=0.000000 0.000000|");
  EXPECT_EQ(ngc_brt_messages("o<fact> sub\no1 if [#1 le 1]\no<fact> return [1]\no1 endif\n"
                             "o<fact> call [#1-1]\no<fact> return [#1*#<_value>]\no<fact> endsub\n"
                             "o<fact> call [5]\n(DEBUG,%d#<_value>)\nm2\n"),
            "120|");
  // Locals of the caller are not visible in the subroutine.
  EXPECT_EQ(ngc_brt_error("#<here>=1\no<s> sub\n(DEBUG,#<here>)\n#1=#<here>\no<s> endsub\no<s> call\nm2\n"),
            "t.ngc:4:4: Named parameter #<here> not defined");
}

TEST(NgcBlockReader, CallsOfSubroutinesDefinedLaterAndInFiles) {
  // A subroutine after its call is found by reading on, as rs274 does.
  EXPECT_EQ(ngc_brt_messages(
                "o<later> call [4]\no<later> call [5]\nm2\no<later> sub\n(DEBUG,%d#1)\no<later> endsub\n"),
            "4|5|");
  const auto folder = std::filesystem::temp_directory_path() / "pkm_ngc_block_reader_subs";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  {
    std::ofstream out(folder / "ext.ngc");
    out << "o<other> sub\no<other> endsub\no<ext> sub\n(DEBUG,ext #1 #2)\nG1 X#1\no<ext> return [7]\no<ext> "
           "endsub\n";
  }
  ngc_brt::ReaderOptions options;
  options.subroutine_path = {(folder / "missing").string(), folder.string()};
  const NgcBrtRun run =
      ngc_brt_run("G0 X0\no<ext> call [1] [2]\n(DEBUG,#<_value>)\no<EXT> call [3]\nm2\n", options);
  ASSERT_EQ(run.error, "");
  EXPECT_EQ(run.messages,
            (std::vector<std::string>{"ext 1.000000 2.000000", "7.000000", "ext 3.000000 0.000000"}));
  ASSERT_EQ(run.files.size(), 2u);
  EXPECT_EQ(run.files[0], "t.ngc");
  EXPECT_EQ(run.files[1], (folder / "ext.ngc").string());
  // The G1 inside the file: its own file and line, and the main program's line that called it.
  const auto& move = run.blocks[2];
  EXPECT_EQ(move.words[0].letter, 'G');
  EXPECT_EQ(move.where.file, 1);
  EXPECT_EQ(move.where.line, 5);
  EXPECT_EQ(move.where.call_line, 2);
  EXPECT_EQ(run.main_line, 5);
  {
    std::ofstream out(folder / "empty.ngc");
    out << "(no subroutine here)\n";
  }
  EXPECT_EQ(ngc_brt_error("G0 X0\no<empty> call\nm2\n", options),
            "t.ngc:2:1: subroutine o<empty> not found: " + (folder / "empty.ngc").string() +
                " has no 'o<empty> sub' (rs274: EOF seeking o-word o<empty>)");
  std::filesystem::remove_all(folder);
}

TEST(NgcBlockReader, ProgramNumbersAndPercentLines) {
  const NgcBrtRun run = ngc_brt_run(
      "(a comment may come before the opening percent)\n%\nO0001\n(a program number line is ignored)\nG0 "
      "X1\n%\nG0 X2\n");
  ASSERT_EQ(run.error, "");
  ASSERT_EQ(run.blocks.size(), 1u);  // the second '%' ends the program
  EXPECT_EQ(run.main_line, 6);
  EXPECT_EQ(ngc_brt_error("G0 X1\n%\nm2\n"), "t.ngc:2:1: Bad character '%' used");
  EXPECT_EQ(ngc_brt_error("O100 G0 X1\nm2\n"), "t.ngc:1:6: Unknown control command in o word");
}

TEST(NgcBlockReader, BoundsRefuseAtTheLineThatCrossesThem) {
  ngc_brt::ReaderOptions options;
  options.max_blocks = 50;
  EXPECT_EQ(ngc_brt_error("o1 while [1]\nG0 X1\no1 endwhile\n", options),
            "t.ngc:3:1: more than 50 blocks executed (the bound max_blocks; an endless loop?)");
  options = {};
  options.max_call_depth = 5;
  const std::string error = ngc_brt_error("o<r> sub\no<r> call\no<r> endsub\no<r> call\nm2\n", options);
  EXPECT_EQ(error.rfind("t.ngc:2:1: Too many subroutine levels", 0), 0u) << error;
}

TEST(NgcBlockReader, ControlFlowErrorsWithFileLineColumn) {
  EXPECT_EQ(ngc_brt_error("G0 X1\n  o1 endwhile\nm2\n"),
            "t.ngc:2:3: undefined O-word label: '  o1 endwhile'");
  EXPECT_EQ(ngc_brt_error("o<s> sub\nG0 X1\nm2\n"),
            "t.ngc:1:1: 'o<s> sub' has no matching 'o<s> endsub': the file ends while skipping to it");
  EXPECT_EQ(ngc_brt_error("o1 if [0]\nG0 X1\nm2\n"),
            "t.ngc:1:1: 'o1 if' has no matching 'o1 endif': the file ends while skipping to it");
  EXPECT_EQ(
      ngc_brt_error("G0 X1\no<nowhere> call\nm2\n").rfind("t.ngc:2:1: subroutine o<nowhere> not found", 0),
      0u);
  EXPECT_EQ(ngc_brt_error("o1 if [1] G0 X1\no1 endif\nm2\n"),
            "t.ngc:1:11: Unexpected character after O-word");
  EXPECT_EQ(ngc_brt_error("o1 if [1]\no1 endif\no1 if [1]\no1 endif\nm2\n"),
            "t.ngc:3:1: duplicate O-word label - already defined in line 1: 'o1 if [1]'");
  EXPECT_EQ(ngc_brt_error("o1 repeat [2]\no1 break\no1 endrepeat\nm2\n"),
            "t.ngc:2:1: no matching while/do label: 'o1 break' (found 'repeat' in line 1)");
  EXPECT_EQ(ngc_brt_error("o<a> sub\no<b> sub\no<b> endsub\no<a> endsub\nm2\n"),
            "t.ngc:2:1: Nested subroutine definition");
  EXPECT_EQ(ngc_brt_error("o<a> endsub\nm2\n"), "t.ngc:1:1: not in a subroutine definition: 'o<a> endsub'");
  EXPECT_EQ(ngc_brt_error("o1 sub\no1 endsub\no1 sub\no1 endsub\nm2\n"),
            "t.ngc:3:1: redefining sub o<1>: already defined in t.ngc line 1");
  EXPECT_EQ(ngc_brt_error("o<s> call\no<s> sub\no<s> endsub\nm2\n")
                .rfind("t.ngc:2:1: sub o<s> found in illegal location", 0),
            0u);
  EXPECT_EQ(ngc_brt_error("o1 while 1\nm2\n"), "t.ngc:1:10: Left bracket missing after 'while'");
  EXPECT_EQ(ngc_brt_error("#5401=1\nm2\n"), "t.ngc:1:1: Parameter is readonly");
  EXPECT_EQ(ngc_brt_error("#<_x>=1\nm2\n"), "t.ngc:1:1: Cannot assign to read-only parameter #<_x>");
  EXPECT_EQ(ngc_brt_error("G1 X1 (unclosed\nm2\n"), "t.ngc:1:7: Unclosed comment found");
  EXPECT_EQ(ngc_brt_error("G0 o1\nm2\n"), "t.ngc:1:4: Bad character 'o' used");
  // Lines skipped by a false condition are not read, so errors in them do not count (as in rs274).
  EXPECT_EQ(ngc_brt_messages("o1 if [0]\nG1 X[1/0] &\no1 endif\n(DEBUG,ok)\nm2\n"), "ok|");
}

TEST(NgcBlockReader, LongLoopsRunInConstantMemoryAndQuickly) {
  ngc_brt::ParameterStore parameters;
  const auto start = std::chrono::steady_clock::now();
  const NgcBrtRun run = ngc_brt_run(
      "#1=0\no1 while [#1 lt 100000]\n#1=[#1+1]\no<s> call [#1]\nG1 X#<_value>\no1 endwhile\nm2\n"
      "o<s> sub\n#<twice>=[#1*2]\no<s> return [#<twice>]\no<s> endsub\n",
      {}, &parameters);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.error, "");
  ASSERT_EQ(run.blocks.size(), 100001u);
  EXPECT_DOUBLE_EQ(run.blocks[99999].words[1].value, 200000.0);
  EXPECT_LT(seconds, 5.0);
}
