// The profile file of `pkm spif program --profile`: rows read as written, and every malformed file refused
// naming its line, column and column name.
#include "io/spif_profile_file.hpp"

#include <gtest/gtest.h>

namespace pkm {
namespace {

TEST(SpifProfileFile, RowsAndCommentsAreRead) {
  auto rows =
      parse_spif_profile("# a hyperbolic cone\ndepth_mm,radius_mm\n0,75\n\n 10 , 70\n20,60.5\n", "p.csv");
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 3u);
  EXPECT_EQ((*rows)[1][0], 10.0);
  EXPECT_EQ((*rows)[2][1], 60.5);
}

TEST(SpifProfileFile, MalformedFilesAreNamed) {
  struct Case {
    const char* text;
    const char* where;
  };
  for (const Case& c :
       {Case{"depth,radius\n0,75\n10,70\n", "p.csv:1:1: header"},
        Case{"depth_mm,radius_mm\n1,75\n10,70\n", "p.csv:2:1: depth_mm"},
        Case{"depth_mm,radius_mm\n0,75\n10,70\n10,60\n", "p.csv:4:1: depth_mm"},
        Case{"depth_mm,radius_mm\n0,75\n10,-1\n", "p.csv:3:4: radius_mm"},
        Case{"depth_mm,radius_mm\n0,75\n10,x\n", "p.csv:3:4: radius_mm"},
        Case{"depth_mm,radius_mm\n0,75,1\n", "p.csv:2:1: row"}, Case{"depth_mm,radius_mm\n0,75\n", "rows"}}) {
    auto rows = parse_spif_profile(c.text, "p.csv");
    ASSERT_FALSE(rows) << c.text;
    EXPECT_NE(rows.error().message.find(c.where), std::string::npos) << rows.error().message;
  }
}

}  // namespace
}  // namespace pkm
