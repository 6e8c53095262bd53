// Reading a run's CSV files back for the report (report/csv_table.hpp): numbers, empty fields, and errors
// that name the file, the line and the column.
#include "report/csv_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace pkm {
namespace {

std::string csv_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_csv_table_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(CsvReader, ReadsNumbersAndEmptyFieldsAsNan) {
  const std::string file = csv_file("ok.csv", "time_s,line,error_mm\n0.001,12,\n0.002,13,1.5e-05\n");
  report::CsvReader csv;
  ASSERT_TRUE(csv.open(file).ok());
  EXPECT_EQ(csv.column("line"), 1);
  EXPECT_EQ(csv.column("nothing"), -1);
  EXPECT_FALSE(csv.require("nothing").ok());
  std::vector<double> row;
  ASSERT_TRUE(csv.next(row));
  EXPECT_DOUBLE_EQ(row[0], 0.001);
  EXPECT_TRUE(std::isnan(row[2]));
  ASSERT_TRUE(csv.next(row));
  EXPECT_DOUBLE_EQ(row[2], 1.5e-5);
  EXPECT_FALSE(csv.next(row));
  EXPECT_FALSE(csv.error().has_value());
  auto rows = report::count_csv_rows(file);
  ASSERT_TRUE(rows.ok());
  EXPECT_EQ(*rows, 2);
}

TEST(CsvReader, MalformedRowsNameTheFileLineAndColumn) {
  struct Case {
    std::string text;
    std::string expected;
  };
  for (const Case& c : std::vector<Case>{{"a,b\n1,2\n3,x\n", "bad.csv:3: b: 'x' is not a number"},
                                         {"a,b\n1,2\n3\n", "bad.csv:3: 1 of 2 columns"},
                                         {"a,b\n1,2,3\n", "bad.csv:2: more than the header's 2 columns"}}) {
    const std::string file = csv_file("bad.csv", c.text);
    report::CsvReader csv;
    ASSERT_TRUE(csv.open(file).ok());
    std::vector<double> row;
    while (csv.next(row)) {
    }
    ASSERT_TRUE(csv.error().has_value()) << c.text;
    EXPECT_NE(csv.error()->message.find(c.expected), std::string::npos) << csv.error()->message;
  }
  report::CsvReader missing;
  EXPECT_FALSE(missing.open("/nonexistent/path.csv").ok());
}

}  // namespace
}  // namespace pkm
