// The HDF5 tables (formats/hdf5_table.hpp): what is appended reads back, across chunk boundaries, each column
// rounded to its quantum, exact or whole as it says, with its unit; errors name the file.
#include "formats/hdf5_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

namespace pkm::formats {
namespace {

std::string scratch_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "pkm-hdf5-test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

TEST(Hdf5Table, SignificantBitsKeepTheCsvDigitsAndZeroTheRest) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 10);
  for (const int digits : {4, 5}) {
    const int bits = significant_bits_for_digits(digits);
    // Half a unit of the digits' last place, relative, at its smallest (a mantissa of 9.99…).
    EXPECT_LT(std::ldexp(1.0, -bits), 0.5 * std::pow(10.0, -digits));
    for (int k = 0; k < 10000; ++k) {
      const double v = std::ldexp(mantissa(rng), exponent(rng));
      const double r = round_to_significant_bits(v, bits);
      EXPECT_LE(std::abs(r - v), std::ldexp(std::abs(v), -bits)) << v;
      int e = 0;
      const double m = std::frexp(r, &e);
      EXPECT_EQ(std::ldexp(m, bits), std::nearbyint(std::ldexp(m, bits))) << r << ": more bits than " << bits;
    }
  }
  EXPECT_TRUE(std::isnan(round_to_significant_bits(std::nan(""), 15)));
  EXPECT_EQ(round_to_significant_bits(0.0, 15), 0.0);
}

/// The definition: the mantissa scaled to `bits` bits, rounded half to even, scaled back.
double rounded_by_definition(double value, int bits) {
  if (!std::isfinite(value) || value == 0.0) return value;
  int exponent = 0;
  const double mantissa = std::frexp(value, &exponent);
  return std::ldexp(std::nearbyint(std::ldexp(mantissa, bits)), exponent - bits);
}

TEST(Hdf5Table, SignificantBitsRoundAsTheDefinitionIncludingTiesCarriesAndSubnormals) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> mantissa(0.5, 1.0);
  std::uniform_int_distribution<int> exponent(-1074, 1023), bits_of(1, 52), sign(0, 1), low(0, 1 << 20);
  for (int k = 0; k < 200000; ++k) {
    const int bits = bits_of(rng);
    double v = std::ldexp(mantissa(rng), exponent(rng));
    if (k % 4 == 1) {  // exactly half way between two kept values: ties go to even
      const double kept = std::floor(std::ldexp(mantissa(rng), bits));
      v = std::ldexp((kept + 0.5) / std::ldexp(1.0, bits), exponent(rng) % 900);
    } else if (k % 4 == 2) {  // all kept bits ones and more below: the carry reaches the exponent
      v = std::ldexp(1.0 - std::ldexp(1.0 + low(rng) * 1e-7, -bits - 1), exponent(rng) % 900);
    }
    if (sign(rng) == 1) v = -v;
    const double expected = rounded_by_definition(v, bits);
    EXPECT_EQ(round_to_significant_bits(v, bits), expected) << v << " to " << bits << " bits";
  }
  EXPECT_EQ(round_to_significant_bits(1.5, 1), 2.0);    // a tie, to even
  EXPECT_EQ(round_to_significant_bits(-2.5, 2), -2.0);  // 10.1b: a tie, to even
  EXPECT_EQ(round_to_significant_bits(std::numeric_limits<double>::denorm_min(), 3),
            std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(round_to_significant_bits(0.1, 53), 0.1);
}

TEST(Hdf5Table, RowsReadBackRoundedToTheirQuantumAcrossChunks) {
  const std::string path = scratch_file("rows.h5");
  const std::vector<Hdf5Column> columns{{"time_s", "s", quantum_bits_for_decimals(6), false},
                                        {"line", "", 0, true},
                                        {"x_mm", "mm", 20, false},
                                        {"error_mm", "mm", 0, false}};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-800.0, 800.0);
  std::vector<std::array<double, 4>> rows;
  for (int r = 0; r < 1000; ++r)
    rows.push_back({r * 1e-3, static_cast<double>(r / 7), u(rng), u(rng) * 1e-9});
  {
    auto file = Hdf5File::create(path);
    ASSERT_TRUE(file.ok()) << file.error().message;
    auto table = file->table("t", columns, 64);  // 1000 rows: 15 whole chunks and a part
    ASSERT_TRUE(table.ok()) << table.error().message;
    for (const auto& row : rows) ASSERT_TRUE(table->append(row.data()).ok());
    EXPECT_EQ(table->rows(), 1000);
    ASSERT_TRUE(table->finish().ok());
    ASSERT_TRUE(file->close().ok());
  }
  for (std::size_t c = 0; c < columns.size(); ++c) {
    auto read = read_hdf5_column(path, "t", columns[c].name);
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->unit, columns[c].unit);
    ASSERT_EQ(read->values.size(), rows.size());
    const double half_quantum = columns[c].quantum_bits > 0 ? std::ldexp(0.5, -columns[c].quantum_bits) : 0.0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (half_quantum > 0.0) {
        EXPECT_LE(std::abs(read->values[r] - rows[r][c]), half_quantum) << columns[c].name << " row " << r;
        // On the grid: a multiple of the quantum, so its low mantissa bits are zeros.
        const double steps = std::ldexp(read->values[r], columns[c].quantum_bits);
        EXPECT_EQ(steps, std::round(steps)) << columns[c].name << " row " << r;
      } else {
        EXPECT_EQ(read->values[r], rows[r][c]) << columns[c].name << " row " << r;
      }
    }
  }
  // The CSV's 6 decimals keep 5e-7; the quantum of 6 decimals keeps less.
  EXPECT_LE(std::ldexp(0.5, -quantum_bits_for_decimals(6)), 5e-7);
  EXPECT_GE(std::ldexp(1.0, -quantum_bits_for_decimals(6)), 0.5e-6);
}

TEST(Hdf5Table, ErrorsNameTheFileAndTheColumn) {
  auto missing = read_hdf5_column(scratch_file("none.h5"), "t", "x");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("none.h5"), std::string::npos) << missing.error().message;
  const std::string path = scratch_file("one.h5");
  {
    auto file = Hdf5File::create(path);
    ASSERT_TRUE(file.ok());
    auto table = file->table("t", {{"a", "mm", 0, false}});
    ASSERT_TRUE(table.ok());
    ASSERT_TRUE(table->finish().ok());
    ASSERT_TRUE(file->close().ok());
  }
  auto wrong = read_hdf5_column(path, "t", "b");
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.error().message.find("t/b"), std::string::npos) << wrong.error().message;
  auto empty = read_hdf5_column(path, "t", "a");
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->values.empty());
  auto bad = Hdf5File::create(scratch_file("no-such-folder/x.h5"));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("x.h5"), std::string::npos);
}

}  // namespace
}  // namespace pkm::formats
