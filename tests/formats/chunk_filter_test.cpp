// The chunk filter of the HDF5 tables (formats/hdf5_chunk_filter.hpp, byte_shuffle.hpp): the shuffle is
// HDF5's byte-plane transposition at every length, and a deflated chunk, whatever mix of run-made and other
// planes it has, is one zlib stream that zlib itself (HDF5's inflater) reads back to the shuffled bytes.
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "formats/byte_shuffle.hpp"
#include "formats/hdf5_chunk_filter.hpp"

namespace pkm::formats {
namespace {

std::vector<std::uint8_t> shuffled_by_definition(const std::vector<std::uint8_t>& elements) {
  const std::size_t count = elements.size() / 8;
  std::vector<std::uint8_t> planes(elements.size());
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t b = 0; b < 8; ++b) planes[b * count + i] = elements[i * 8 + b];
  return planes;
}

TEST(ByteShuffle, IsHdf5sPlaneTranspositionAtEveryLengthAndUndoesItself) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::size_t> counts;
  for (std::size_t c = 0; c <= 70; ++c) counts.push_back(c);  // around the 16-element blocks
  counts.insert(counts.end(), {255, 256, 257, 4095, 16384});
  for (const std::size_t count : counts) {
    std::vector<std::uint8_t> elements(count * 8);
    for (auto& b : elements) b = static_cast<std::uint8_t>(byte(rng));
    std::vector<std::uint8_t> planes(elements.size());
    shuffle_bytes8(elements.data(), count, planes.data());
    EXPECT_EQ(planes, shuffled_by_definition(elements)) << count << " elements";
    // Back, whole and for the first rows only (a table's last chunk).
    for (const std::size_t rows : {count, count / 2, count > 0 ? count - 1 : 0}) {
      std::vector<std::uint8_t> back(rows * 8, 0xAB);
      unshuffle_bytes8(planes.data(), count, rows, back.data());
      EXPECT_TRUE(std::equal(back.begin(), back.end(), elements.begin())) << count << " elements, " << rows;
    }
  }
}

/// A chunk of `count` 8-byte elements whose byte planes are, each at random: one byte repeated, runs of
/// random lengths, or random bytes.
std::vector<std::uint8_t> mixed_chunk(std::mt19937_64& rng, std::size_t count) {
  std::uniform_int_distribution<int> kind(0, 2), byte(0, 255), run(1, 400);
  std::vector<std::uint8_t> planes(count * 8);
  for (std::size_t b = 0; b < 8; ++b) {
    const int k = kind(rng);
    std::uint8_t value = static_cast<std::uint8_t>(byte(rng));
    int left = run(rng);
    for (std::size_t i = 0; i < count; ++i) {
      if (k == 2) value = static_cast<std::uint8_t>(byte(rng));
      if (k == 1 && --left == 0) value = static_cast<std::uint8_t>(byte(rng)), left = run(rng);
      planes[b * count + i] = value;
    }
  }
  std::vector<std::uint8_t> elements(planes.size());
  unshuffle_bytes8(planes.data(), count, count, elements.data());
  return elements;
}

TEST(ChunkDeflater, EveryMixOfPlanesIsOneZlibStreamThatZlibReadsBack) {
  std::mt19937_64 rng(12);
  ChunkDeflater deflater(1);
  ChunkInflater inflater;
  ChunkBytes stored;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t count = trial < 100 ? 16384 : static_cast<std::size_t>(1 + trial * 37 % 3000);
    const std::vector<std::uint8_t> elements = mixed_chunk(rng, count);
    deflater.shuffle_deflate(elements.data(), count, 8, stored);
    // zlib's own inflater, as HDF5's deflate filter runs it, checksum included.
    std::vector<std::uint8_t> inflated(elements.size());
    uLongf inflated_size = inflated.size();
    ASSERT_EQ(uncompress(inflated.data(), &inflated_size, stored.data.get(), stored.size), Z_OK) << trial;
    ASSERT_EQ(inflated_size, elements.size());
    EXPECT_EQ(inflated, shuffled_by_definition(elements)) << trial;
    // The reader's way back gives the elements (as doubles' bits).
    std::vector<double> values(count);
    ASSERT_TRUE(inflater.inflate(stored, count, false, count, values.data())) << trial;
    EXPECT_EQ(std::memcmp(values.data(), elements.data(), elements.size()), 0) << trial;
  }
}

TEST(ChunkDeflater, APlaneOfOneByteCostsAFewBytes) {
  // Values in one binade on a coarse quantum: the low planes are zero, the top ones constant.
  std::vector<double> values(16384);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 512.0 + static_cast<double>(i % 7) / 1024.0;
  ChunkDeflater deflater(1);
  ChunkBytes stored;
  deflater.shuffle_deflate(values.data(), values.size(), 8, stored);
  EXPECT_LT(stored.size, values.size() * 8 / 100);
  std::vector<double> back(values.size());
  uLongf size = back.size() * 8;
  std::vector<std::uint8_t> planes(size);
  ASSERT_EQ(uncompress(planes.data(), &size, stored.data.get(), stored.size), Z_OK);
  unshuffle_bytes8(planes.data(), values.size(), values.size(), reinterpret_cast<std::uint8_t*>(back.data()));
  EXPECT_EQ(back, values);
}

}  // namespace
}  // namespace pkm::formats
