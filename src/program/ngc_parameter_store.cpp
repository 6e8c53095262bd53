#include "program/ngc_parameter_store.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <set>

#include "io/atomic_file.hpp"

namespace pkm::program::ngc {

namespace {

constexpr int kStoreDebugEnableParameter = 5599;  // LinuxCNC shows (DEBUG,…) only while #5599 > 0

// The parameters LinuxCNC writes to the .var file even when the file did not list them.
bool store_always_persisted(int n) {
  if (n >= 5161 && n <= 5169) return true;  // G28 home
  if (n >= 5181 && n <= 5189) return true;  // G30 home
  if (n >= 5210 && n <= 5219) return true;  // G92 applied flag and offsets
  if (n == 5220) return true;               // selected coordinate system
  if (n >= 5221 && n <= 5390) {             // G54 … G59.3: X … W and the XY rotation R, 20 apart
    const int offset = (n - 5221) % 20;
    return offset <= 9;
  }
  return false;
}

bool store_is_name_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// Parses "NUMBER VALUE" at the start of a .var line; false when the line is not one (LinuxCNC skips it).
bool store_parse_var_line(std::string_view line, int& number, double& value) {
  std::size_t p = 0;
  auto skip_blanks = [&] {
    while (p < line.size() && (line[p] == ' ' || line[p] == '\t' || line[p] == '\r')) ++p;
  };
  skip_blanks();
  const char* begin = line.data() + p;
  const char* end = line.data() + line.size();
  if (p < line.size() && line[p] == '+') ++begin;
  auto [after_number, ec] = std::from_chars(begin, end, number);
  if (ec != std::errc()) return false;
  p = static_cast<std::size_t>(after_number - line.data());
  skip_blanks();
  begin = line.data() + p;
  if (p < line.size() && line[p] == '+') ++begin;
  auto [after_value, ec2] = std::from_chars(begin, end, value);
  return ec2 == std::errc();
}

// The numbers listed in an existing .var file (empty when there is none).
std::vector<int> store_numbers_in_var_file(const std::string& path) {
  std::vector<int> numbers;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    int number = 0;
    double value = 0.0;
    if (store_parse_var_line(line, number, value)) numbers.push_back(number);
  }
  return numbers;
}

}  // namespace

ParameterStore::ParameterStore() : values_(static_cast<std::size_t>(kParameterCount), 0.0), levels_(1) {
  values_[kStoreDebugEnableParameter] = 1.0;
}

bool ParameterStore::is_read_only(int number) {
  return (number >= 5021 && number <= 5029) || (number >= 5400 && number <= 5413) ||
         (number >= 5420 && number <= 5428);
}

void ParameterStore::normalise_name(std::string_view name, std::string& out) {
  out.clear();
  for (char c : name) {
    if (store_is_name_blank(c)) continue;
    out.push_back((c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c);
  }
}

std::string_view ParameterStore::normalised(std::string_view name, std::string& scratch) {
  const bool clean = std::none_of(name.begin(), name.end(),
                                  [](char c) { return store_is_name_blank(c) || (c >= 'A' && c <= 'Z'); });
  if (clean) return name;
  normalise_name(name, scratch);
  return scratch;
}

const ParameterStore::Level& ParameterStore::level_for(std::string_view normalised_name) const {
  const bool global = !normalised_name.empty() && normalised_name[0] == '_';
  return levels_[global ? 0 : static_cast<std::size_t>(level_)];
}

ParameterStore::Level& ParameterStore::level_for(std::string_view normalised_name) {
  const bool global = !normalised_name.empty() && normalised_name[0] == '_';
  return levels_[global ? 0 : static_cast<std::size_t>(level_)];
}

std::optional<double> ParameterStore::named(std::string_view name) const {
  const std::string_view key = normalised(name, scratch_);
  const Level& level = level_for(key);
  const auto found = level.names.find(key);
  if (found == level.names.end() || found->second.generation != level.generation) return std::nullopt;
  return found->second.value;
}

void ParameterStore::set_named(std::string_view name, double value) {
  const std::string_view key = normalised(name, scratch_);
  Level& level = level_for(key);
  auto found = level.names.find(key);
  if (found == level.names.end()) found = level.names.emplace(std::string(key), Slot{}).first;
  found->second = Slot{value, level.generation};
}

void ParameterStore::declare_named(std::string_view name) {
  if (!named(name)) set_named(name, 0.0);
}

void ParameterStore::push_call(const double* arguments, int count) {
  Level& caller = levels_[static_cast<std::size_t>(level_)];
  std::copy(values_.begin() + 1, values_.begin() + 1 + kCallArgumentCount, caller.saved_arguments.begin());
  for (int i = 0; i < kCallArgumentCount; ++i)
    values_[static_cast<std::size_t>(i + 1)] = i < count ? arguments[i] : 0.0;
  ++level_;
  if (static_cast<std::size_t>(level_) == levels_.size()) levels_.emplace_back();
  ++levels_[static_cast<std::size_t>(level_)]
        .generation;  // a fresh call sees none of an earlier one's locals
}

void ParameterStore::pop_call() {
  if (level_ == 0) return;
  ++levels_[static_cast<std::size_t>(level_)].generation;
  --level_;
  const Level& caller = levels_[static_cast<std::size_t>(level_)];
  std::copy(caller.saved_arguments.begin(), caller.saved_arguments.end(), values_.begin() + 1);
}

Status ParameterStore::load_var_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    if (access(path.c_str(), F_OK) != 0) return ok_status();  // not there yet: LinuxCNC starts from zeros
    return make_error(ErrorCode::io, fmt::format("{}: unable to open parameter file", path));
  }
  std::vector<double> values(static_cast<std::size_t>(kParameterCount), 0.0);
  std::vector<int> numbers;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    int number = 0;
    double value = 0.0;
    if (!store_parse_var_line(line, number, value)) continue;
    if (number <= 0 || number >= kParameterCount)
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}:{}: parameter number out of range: {}", path, line_number, number));
    if (!numbers.empty() && number <= numbers.back())
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}:{}: parameter file out of order (#{} after #{})", path, line_number,
                                    number, numbers.back()));
    values[static_cast<std::size_t>(number)] = value;
    numbers.push_back(number);
  }
  values_ = std::move(values);
  values_[kStoreDebugEnableParameter] = 1.0;
  loaded_numbers_ = std::move(numbers);
  return ok_status();
}

Status ParameterStore::save_var_file(const std::string& path) const {
  std::set<int> numbers(loaded_numbers_.begin(), loaded_numbers_.end());
  for (int n : store_numbers_in_var_file(path)) {
    if (n <= 0 || n >= kParameterCount)
      return make_error(ErrorCode::bad_input, fmt::format("{}: parameter number out of range: {}", path, n));
    numbers.insert(n);
  }
  for (int n = 5161; n <= 5390; ++n)
    if (store_always_persisted(n)) numbers.insert(n);
  std::string text;
  for (int n : numbers) text += fmt::format("{}\t{:.6f}\n", n, values_[static_cast<std::size_t>(n)]);

  // The offsets must survive a power cut as LinuxCNC's do (it fsyncs too), hence sync() before the rename.
  StagedFile file;
  if (auto opened = file.open(path); !opened) return opened;
  if (auto wrote = file.write(text); !wrote) return wrote;
  if (auto synced = file.sync(); !synced) return synced;
  return file.commit();
}

}  // namespace pkm::program::ngc
