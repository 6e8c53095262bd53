// The RS274/NGC parameter store: numbered parameters, #1–#30 per call level, named locals and globals, and
// LinuxCNC's .var files.
#include "program/ngc_parameter_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ngc_pst = pkm::program::ngc;

namespace {

std::filesystem::path ngc_pst_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("pkm_ngc_parameter_store_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

std::string ngc_pst_read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST(NgcParameterStore, NumberedParametersAndTheirRange) {
  ngc_pst::ParameterStore store;
  EXPECT_DOUBLE_EQ(store.get(5599), 1.0);  // DEBUG output enabled, as LinuxCNC starts
  store.set(31, 2.5);
  store.set(5601, -1.0);
  EXPECT_DOUBLE_EQ(store.get(31), 2.5);
  EXPECT_DOUBLE_EQ(store.get(5601), -1.0);
  store.set(0, 9.0);
  store.set(5602, 9.0);
  EXPECT_DOUBLE_EQ(store.get(0), 0.0);
  EXPECT_DOUBLE_EQ(store.get(5602), 0.0);
  EXPECT_TRUE(ngc_pst::ParameterStore::is_read_only(5400));
  EXPECT_TRUE(ngc_pst::ParameterStore::is_read_only(5421));
  EXPECT_FALSE(ngc_pst::ParameterStore::is_read_only(5221));
}

TEST(NgcParameterStore, CallArgumentsBelongToTheirLevel) {
  ngc_pst::ParameterStore store;
  store.set(1, 11.0);
  store.set(30, 30.0);
  store.set(31, 31.0);
  const double arguments[] = {1.0, 2.0};
  store.push_call(arguments, 2);
  EXPECT_EQ(store.call_level(), 1);
  EXPECT_DOUBLE_EQ(store.get(1), 1.0);
  EXPECT_DOUBLE_EQ(store.get(2), 2.0);
  EXPECT_DOUBLE_EQ(store.get(3), 0.0);
  EXPECT_DOUBLE_EQ(store.get(30), 0.0);
  EXPECT_DOUBLE_EQ(store.get(31), 31.0);  // #31 and up are global
  store.set(1, 5.0);
  store.set(31, 32.0);
  store.pop_call();
  EXPECT_EQ(store.call_level(), 0);
  EXPECT_DOUBLE_EQ(store.get(1), 11.0);
  EXPECT_DOUBLE_EQ(store.get(30), 30.0);
  EXPECT_DOUBLE_EQ(store.get(31), 32.0);
}

TEST(NgcParameterStore, NamedLocalsPerLevelGlobalsEverywhere) {
  ngc_pst::ParameterStore store;
  store.set_named("Feed Rate", 100.0);
  store.set_named("_Global", 7.0);
  EXPECT_EQ(store.named("feedrate"), 100.0);
  EXPECT_EQ(store.named("FEED RATE"), 100.0);
  store.push_call(nullptr, 0);
  EXPECT_FALSE(store.named("feedrate").has_value());  // the caller's locals are not visible
  EXPECT_EQ(store.named("_global"), 7.0);
  store.set_named("inner", 1.0);
  store.set_named("_global", 8.0);
  EXPECT_EQ(store.named("inner"), 1.0);
  store.pop_call();
  EXPECT_FALSE(store.named("inner").has_value());
  EXPECT_EQ(store.named("_global"), 8.0);
  EXPECT_EQ(store.named("feedrate"), 100.0);
  store.push_call(nullptr, 0);
  EXPECT_FALSE(store.named("inner").has_value());  // a new call starts without the last one's locals
  store.declare_named("fresh");
  EXPECT_EQ(store.named("fresh"), 0.0);
  store.set_named("fresh", 3.0);
  store.declare_named("fresh");  // declaring keeps an existing value
  EXPECT_EQ(store.named("fresh"), 3.0);
  store.pop_call();
}

TEST(NgcParameterStore, VarFileRoundTrip) {
  const auto folder = ngc_pst_folder("round_trip");
  const auto path = (folder / "pkm.var").string();
  {
    std::ofstream out(path);
    out << "31\t1.500000\n5161\t10.456000\nnot a parameter line\n5221\t-2.000000\n5400\t3.000000\n";
  }
  ngc_pst::ParameterStore store;
  store.set(100, 42.0);
  ASSERT_TRUE(store.load_var_file(path).ok());
  EXPECT_DOUBLE_EQ(store.get(31), 1.5);
  EXPECT_DOUBLE_EQ(store.get(5161), 10.456);
  EXPECT_DOUBLE_EQ(store.get(5221), -2.0);
  EXPECT_DOUBLE_EQ(store.get(100), 0.0);   // LinuxCNC zeroes what the file does not list
  EXPECT_DOUBLE_EQ(store.get(5599), 1.0);  // and then enables DEBUG output
  store.set(31, 2.25);
  store.set(5222, 0.125);
  store.set(5231, 99.0);  // not persisted: not in the file, not one LinuxCNC keeps
  store.set(100, 5.0);
  ASSERT_TRUE(store.save_var_file(path).ok());
  const std::string text = ngc_pst_read(path);
  EXPECT_NE(text.find("31\t2.250000\n"), std::string::npos);
  EXPECT_NE(text.find("5161\t10.456000\n"), std::string::npos);
  EXPECT_NE(text.find("5222\t0.125000\n"), std::string::npos);
  EXPECT_NE(text.find("5220\t0.000000\n"), std::string::npos);  // always kept
  EXPECT_NE(text.find("5390\t0.000000\n"), std::string::npos);
  EXPECT_NE(text.find("5400\t3.000000\n"), std::string::npos);  // listed in the file before
  EXPECT_EQ(text.find("5231\t"), std::string::npos);
  EXPECT_EQ(text.find("100\t"), std::string::npos);
  EXPECT_EQ(text.find("not a parameter"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path + ".new"));
  ngc_pst::ParameterStore again;
  ASSERT_TRUE(again.load_var_file(path).ok());
  for (int n = 1; n < ngc_pst::kParameterCount; ++n) {
    const double expected = (n == 100 || n == 5231) ? 0.0 : store.get(n);  // not persisted
    EXPECT_DOUBLE_EQ(again.get(n), expected) << "#" << n;
  }
  std::filesystem::remove_all(folder);
}

TEST(NgcParameterStore, VarFileErrorsAndAMissingFile) {
  const auto folder = ngc_pst_folder("errors");
  ngc_pst::ParameterStore store;
  EXPECT_TRUE(store.load_var_file((folder / "missing.var").string()).ok());
  const auto unordered = (folder / "unordered.var").string();
  {
    std::ofstream out(unordered);
    out << "5221\t1\n5161\t2\n";
  }
  auto result = store.load_var_file(unordered);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("out of order"), std::string::npos) << result.error().message;
  const auto range = (folder / "range.var").string();
  {
    std::ofstream out(range);
    out << "5602\t1\n";
  }
  result = store.load_var_file(range);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("out of range"), std::string::npos) << result.error().message;
  // Saving where no file exists yet writes the parameters LinuxCNC always keeps.
  const auto fresh = (folder / "fresh.var").string();
  ASSERT_TRUE(store.save_var_file(fresh).ok());
  const std::string text = ngc_pst_read(fresh);
  EXPECT_EQ(text.rfind("5161\t0.000000\n", 0), 0u);
  std::filesystem::remove_all(folder);
}
