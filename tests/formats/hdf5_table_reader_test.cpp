// Reading an HDF5 table back a block of rows at a time (formats/hdf5_table_reader.hpp) and through the
// report's row source (report/table_rows.hpp): every row as written, in the columns' written order, across
// whole blocks and a partial last one, whatever the block and chunk sizes; the CSV form gives the same rows;
// errors name the file and the table.
#include "formats/hdf5_table_reader.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>

#include "formats/hdf5_table.hpp"
#include "report/table_rows.hpp"

namespace pkm::formats {
namespace {

namespace fs = std::filesystem;

fs::path scratch_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "pkm-hdf5-reader-test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Twelve columns, so that a name order (q10 before q2) differs from the written one; the line an integer.
std::vector<Hdf5Column> wide_columns() {
  std::vector<Hdf5Column> columns{{"time_s", "s", 0, false}, {"line", "", 0, true}};
  for (int j = 1; j <= 10; ++j) columns.push_back({"q" + std::to_string(j) + "_mm", "mm", 0, false});
  return columns;
}

// Row r: its time, its line, then r + j / 16 (exact in binary, so the round trip is exact).
std::vector<double> row_values(long r, std::size_t width) {
  std::vector<double> row{static_cast<double>(r) * 1e-3, static_cast<double>(r / 3)};
  for (std::size_t j = 2; j < width; ++j)
    row.push_back(static_cast<double>(r) + static_cast<double>(j) / 16.0);
  return row;
}

void write_table(const std::string& path, long rows, long chunk_rows) {
  auto file = Hdf5File::create(path);
  ASSERT_TRUE(file.ok()) << file.error().message;
  const std::vector<Hdf5Column> columns = wide_columns();
  auto table = file->table("path", columns, chunk_rows);
  ASSERT_TRUE(table.ok()) << table.error().message;
  for (long r = 0; r < rows; ++r) ASSERT_TRUE(table->append(row_values(r, columns.size()).data()).ok());
  ASSERT_TRUE(table->finish().ok());
  ASSERT_TRUE(file->close().ok());
}

TEST(Hdf5TableReader, EveryRowComesBackAcrossWholeBlocksAndAPartialLastOne) {
  const std::string path = (scratch_directory("blocks") / "ticks.h5").string();
  const long rows = 1000;
  write_table(path, rows, 64);
  const std::vector<Hdf5Column> columns = wide_columns();
  // Blocks of 1, of 7 (142 whole blocks and one of 6 rows), of the file's chunk, and of more than the table.
  for (const long block : {1L, 7L, 64L, 5000L}) {
    auto reader = Hdf5TableReader::open(path, "path", block);
    ASSERT_TRUE(reader.ok()) << reader.error().message;
    ASSERT_EQ(reader->columns().size(), columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      EXPECT_EQ(reader->columns()[c], columns[c].name) << "the written order, column " << c;
      EXPECT_EQ(reader->units()[c], columns[c].unit) << columns[c].name;
    }
    EXPECT_EQ(reader->rows(), rows);
    std::vector<double> row;
    long read = 0;
    for (;;) {
      auto more = reader->next(row);
      ASSERT_TRUE(more.ok()) << more.error().message;
      if (!*more) break;
      ASSERT_EQ(row, row_values(read, columns.size())) << "row " << read << " in blocks of " << block;
      ++read;
      EXPECT_EQ(reader->rows_read(), read);
    }
    EXPECT_EQ(read, rows) << "blocks of " << block;
    auto after = reader->next(row);  // the end stays the end
    ASSERT_TRUE(after.ok());
    EXPECT_FALSE(*after);
  }
}

TEST(Hdf5TableReader, TheRowSourceGivesTheCsvFormsRows) {
  const fs::path dir = scratch_directory("forms");
  write_table((dir / "ticks.h5").string(), 50, 16);
  const std::vector<Hdf5Column> columns = wide_columns();
  {
    std::ofstream csv(dir / "path.csv");
    csv << std::setprecision(17) << csv_header(columns);  // every double as it is
    for (long r = 0; r < 50; ++r) {
      const std::vector<double> values = row_values(r, columns.size());
      for (std::size_t c = 0; c < values.size(); ++c) csv << (c > 0 ? "," : "") << values[c];
      csv << '\n';
    }
  }
  EXPECT_EQ(report::tick_tables_in(dir.string()), TickTables::hdf5);
  auto from_h5 = report::open_tick_table(dir.string(), TickTables::hdf5, "path", 16);
  ASSERT_TRUE(from_h5.ok()) << from_h5.error().message;
  auto from_csv = report::open_tick_table(dir.string(), TickTables::csv, "path");
  ASSERT_TRUE(from_csv.ok()) << from_csv.error().message;
  EXPECT_EQ((*from_h5)->columns(), (*from_csv)->columns());
  EXPECT_EQ((*from_h5)->require("q10_mm").value(), 11);
  EXPECT_EQ(*(*from_h5)->count_rows(), 50);
  EXPECT_EQ(*(*from_csv)->count_rows(), 50);
  std::vector<double> a, b;
  long rows = 0;
  for (;;) {
    auto more = report::next_in_step(**from_h5, a, **from_csv, b);
    ASSERT_TRUE(more.ok()) << more.error().message;
    if (!*more) break;
    EXPECT_EQ(a, b) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 50);
  EXPECT_NE((*from_h5)->where().find("ticks.h5: path row 50"), std::string::npos) << (*from_h5)->where();
}

TEST(Hdf5TableReader, ErrorsNameTheFileAndTheTable) {
  const fs::path dir = scratch_directory("errors");
  auto missing = Hdf5TableReader::open((dir / "none.h5").string(), "path");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("none.h5"), std::string::npos) << missing.error().message;
  write_table((dir / "ticks.h5").string(), 3, 16);
  auto other = Hdf5TableReader::open((dir / "ticks.h5").string(), "forces");
  ASSERT_FALSE(other.ok());
  EXPECT_NE(other.error().message.find("ticks.h5: no table forces"), std::string::npos)
      << other.error().message;
  auto rows = report::open_tick_table(dir.string(), TickTables::hdf5, "path");
  ASSERT_TRUE(rows.ok());
  auto absent = (*rows)->require("x_program_mm");
  ASSERT_FALSE(absent.ok());
  EXPECT_NE(absent.error().message.find("ticks.h5 (path): no column 'x_program_mm'"), std::string::npos)
      << absent.error().message;
  // Not an HDF5 file at all.
  std::ofstream(dir / "text.h5") << "time_s\n0\n";
  auto text = Hdf5TableReader::open((dir / "text.h5").string(), "path");
  ASSERT_FALSE(text.ok());
  EXPECT_NE(text.error().message.find("text.h5"), std::string::npos) << text.error().message;
}

// A table another program wrote: columns chunked differently, one of them deflated without the shuffle, one
// not filtered at all. Such columns are read through HDF5's own pipeline, not as raw chunks.
void write_foreign_table(const std::string& path, long rows) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group = H5Gcreate2(file, "path", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {static_cast<hsize_t>(rows)};
  const int chunks[3] = {10, 64, 0};  // 0: contiguous
  const char* names[3] = {"a", "b", "c"};
  for (int c = 0; c < 3; ++c) {
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
    if (chunks[c] > 0) {
      const hsize_t chunk[1] = {static_cast<hsize_t>(chunks[c])};
      H5Pset_chunk(properties, 1, chunk);
      if (c == 1) H5Pset_shuffle(properties);
      H5Pset_deflate(properties, 4);
    }
    const hid_t dataset =
        H5Dcreate2(group, names[c], H5T_IEEE_F64LE, space, H5P_DEFAULT, properties, H5P_DEFAULT);
    std::vector<double> values(static_cast<std::size_t>(rows));
    for (long r = 0; r < rows; ++r) values[static_cast<std::size_t>(r)] = r * 0.5 + c;
    H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(dataset);
    H5Pclose(properties);
    H5Sclose(space);
  }
  H5Gclose(group);
  H5Fclose(file);
}

TEST(Hdf5TableReader, ATableAnotherProgramWroteReadsThroughHdf5sOwnFilters) {
  const std::string path = (scratch_directory("foreign") / "ticks.h5").string();
  write_foreign_table(path, 333);
  auto reader = Hdf5TableReader::open(path, "path", 50);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  std::vector<std::vector<double>> expected;
  for (long r = 0; r < 333; ++r) expected.push_back({r * 0.5, r * 0.5 + 1, r * 0.5 + 2});
  std::vector<std::vector<double>> rows;
  std::vector<double> row;
  for (Result<bool> more = reader->next(row); more.ok() && *more; more = reader->next(row))
    rows.push_back(row);
  EXPECT_EQ(rows, expected);
}

// Random rows across many chunks, read ahead a chunk at a time, come back as written; a chunk whose stored
// bytes are damaged is an error naming the file, the table and the rows, not rows of garbage.
TEST(Hdf5TableReader, ChunksReadAheadComeBackAsWrittenAndADamagedOneIsAnError) {
  const std::string path = (scratch_directory("damaged") / "ticks.h5").string();
  const std::vector<Hdf5Column> columns = wide_columns();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  const long rows = 5000, chunk_rows = 256;
  std::vector<std::vector<double>> written;
  {
    auto file = Hdf5File::create(path);
    ASSERT_TRUE(file.ok());
    auto table = file->table("path", columns, chunk_rows);
    ASSERT_TRUE(table.ok());
    for (long r = 0; r < rows; ++r) {
      std::vector<double> row = row_values(r, columns.size());
      for (std::size_t c = 2; c < row.size(); ++c) row[c] = value(rng);  // kept exactly: quantum 0
      written.push_back(row);
      ASSERT_TRUE(table->append(row.data()).ok());
    }
    ASSERT_TRUE(table->finish().ok());
    ASSERT_TRUE(file->close().ok());
  }
  auto reader = Hdf5TableReader::open(path, "path");
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  std::vector<double> row;
  for (long r = 0; r < rows; ++r) {
    auto more = reader->next(row);
    ASSERT_TRUE(more.ok() && *more) << "row " << r;
    ASSERT_EQ(row, written[static_cast<std::size_t>(r)]) << "row " << r;
  }
  // Damage the stored bytes of the third chunk of q5_mm.
  haddr_t address = 0;
  hsize_t size = 0;
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t dataset = H5Dopen2(file, "path/q5_mm", H5P_DEFAULT);
    const hsize_t offset[1] = {2 * chunk_rows};
    unsigned mask = 0;
    ASSERT_GE(H5Dget_chunk_info_by_coord(dataset, offset, &mask, &address, &size), 0);
    H5Dclose(dataset);
    H5Fclose(file);
  }
  {
    std::fstream bytes(path, std::ios::in | std::ios::out | std::ios::binary);
    bytes.seekp(static_cast<std::streamoff>(address + size / 2));
    const std::string noise(8, '\x5a');
    bytes.write(noise.data(), static_cast<std::streamsize>(noise.size()));
  }
  auto damaged = Hdf5TableReader::open(path, "path");
  ASSERT_TRUE(damaged.ok()) << damaged.error().message;
  std::string message;
  for (long r = 0; r < rows && message.empty(); ++r) {
    auto more = damaged->next(row);
    if (!more.ok())
      message = more.error().message;
    else
      ASSERT_LT(r, 2 * chunk_rows) << "rows of the damaged chunk came back";
  }
  EXPECT_NE(message.find("ticks.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("table path"), std::string::npos) << message;
  EXPECT_NE(message.find("rows from 513"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm::formats
