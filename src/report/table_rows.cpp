#include "report/table_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "formats/hdf5_table_reader.hpp"
#include "report/csv_table.hpp"

namespace pkm::report {

namespace {

namespace fs = std::filesystem;

constexpr const char* kTicksH5 = "ticks.h5";

// DIR/<table>.csv, a line at a time.
class CsvRows final : public TableRows {
 public:
  Status open(const std::string& path) {
    name_ = path;
    return csv_.open(path);
  }
  const std::vector<std::string>& columns() const override { return csv_.columns(); }
  Result<bool> next(std::vector<double>& row) override {
    const bool more = csv_.next(row);
    if (csv_.error()) return *csv_.error();
    return more;
  }
  std::string where(long ahead) const override {
    return fmt::format("{}:{}", csv_.path(), csv_.line() + ahead);
  }
  Result<long> count_rows() const override { return count_csv_rows(csv_.path()); }
  const std::string& name() const override { return name_; }

 private:
  CsvReader csv_;
  std::string name_;
};

// The group <table> of DIR/ticks.h5, a block of rows at a time.
class Hdf5Rows final : public TableRows {
 public:
  Hdf5Rows(formats::Hdf5TableReader reader, std::string path, std::string table)
      : reader_(std::move(reader)),
        path_(std::move(path)),
        table_(std::move(table)),
        name_(fmt::format("{} ({})", path_, table_)) {}
  const std::vector<std::string>& columns() const override { return reader_.columns(); }
  Result<bool> next(std::vector<double>& row) override { return reader_.next(row); }
  std::string where(long ahead) const override {
    const long row = reader_.rows_read() + ahead;
    return row > 0 ? fmt::format("{}: {} row {}", path_, table_, row) : name_;
  }
  Result<long> count_rows() const override { return reader_.rows(); }
  const std::string& name() const override { return name_; }

 private:
  formats::Hdf5TableReader reader_;
  std::string path_, table_, name_;
};

}  // namespace

int TableRows::column(std::string_view name) const {
  const std::vector<std::string>& names = columns();
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

Result<int> TableRows::require(std::string_view name) const {
  const int index = column(name);
  if (index < 0) return make_error(ErrorCode::bad_input, fmt::format("{}: no column '{}'", where(0), name));
  return index;
}

double tick_time_s(double stored_s) {
  return std::round(stored_s * 1e6) / 1e6;
}

formats::TickTables tick_tables_in(const std::string& directory) {
  std::error_code ignored;
  return fs::exists(fs::path(directory) / kTicksH5, ignored) ? formats::TickTables::hdf5
                                                             : formats::TickTables::csv;
}

bool has_tick_tables(const std::string& directory) {
  const fs::path dir(directory);
  std::error_code ignored;
  return fs::exists(dir / kTicksH5, ignored) ||
         (fs::exists(dir / "actuators.csv", ignored) && fs::exists(dir / "path.csv", ignored));
}

Result<std::unique_ptr<TableRows>> open_tick_table(const std::string& directory, formats::TickTables tables,
                                                   const std::string& table, long block_rows) {
  const fs::path dir(directory);
  if (tables == formats::TickTables::csv) {
    auto rows = std::make_unique<CsvRows>();
    if (Status opened = rows->open((dir / (table + ".csv")).string()); !opened) return opened.error();
    return std::unique_ptr<TableRows>(std::move(rows));
  }
  const std::string path = (dir / kTicksH5).string();
  auto reader = formats::Hdf5TableReader::open(path, table, block_rows);
  if (!reader) return reader.error();
  return std::unique_ptr<TableRows>(std::make_unique<Hdf5Rows>(std::move(*reader), path, table));
}

Result<bool> next_in_step(TableRows& a, std::vector<double>& row_a, TableRows& b,
                          std::vector<double>& row_b) {
  auto more_a = a.next(row_a);
  if (!more_a) return more_a.error();
  auto more_b = b.next(row_b);
  if (!more_b) return more_b.error();
  if (*more_a != *more_b) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{} and {} have different numbers of rows (from {})", a.name(), b.name(),
                                  *more_a ? b.where(1) : a.where(1)));
  }
  return *more_a;
}

}  // namespace pkm::report
