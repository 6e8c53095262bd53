#include "formats/hdf5_chunk_filter.hpp"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "formats/byte_shuffle.hpp"

namespace pkm::formats {

void ChunkBytes::reserve(std::size_t bytes) {
  if (bytes <= capacity) return;
  data = std::make_unique_for_overwrite<std::uint8_t[]>(bytes);
  capacity = bytes;
}

namespace {

/// Whether a plane of `count` bytes is made of long runs of one byte (on average 32 or more): zlib's
/// run-length strategy then encodes it as well as libdeflate, in a fraction of the time. Counted a block at a
/// time, stopping as soon as the runs are too many.
bool made_of_runs(const std::uint8_t* plane, std::size_t count) {
  // Blocks of at most 255 bytes, counted in a byte: the compiler then compares and adds 32 bytes at a time.
  constexpr std::size_t kMeanRun = 32, kBlock = 255;
  const std::size_t most_changes = count / kMeanRun;
  std::size_t changes = 0;
  for (std::size_t start = 0; start + 1 < count; start += kBlock) {
    const std::size_t end = std::min(count - 1, start + kBlock);
    std::uint8_t block_changes = 0;
    for (std::size_t i = start; i < end; ++i) block_changes += plane[i] != plane[i + 1];
    changes += block_changes;
    if (changes > most_changes) return false;
  }
  return true;
}

/// How many planes of `count` bytes at the start of `planes` are made of runs.
std::size_t leading_run_planes(const std::uint8_t* planes, std::size_t count, std::size_t plane_count) {
  std::size_t runs = 0;
  while (runs < plane_count && made_of_runs(planes + runs * count, count)) ++runs;
  return runs;
}

// RFC 1950: deflate with a 32 KiB window, no dictionary; (0x78 · 256 + 0x01) is a multiple of 31.
constexpr std::uint8_t kZlibHeader[2] = {0x78, 0x01};

}  // namespace

ChunkDeflater::ChunkDeflater(int level) : compressor_(libdeflate_alloc_compressor(level)) {
  if (compressor_ == nullptr) throw std::runtime_error("libdeflate could not set up a compressor");
  runs_ = std::make_unique<z_stream>();
  // Negative window bits: raw deflate, no zlib header or checksum (those are written here, once per chunk).
  constexpr int kRawDeflate = -15;
  constexpr int kMemoryLevel = 8;
  if (deflateInit2(runs_.get(), 1, Z_DEFLATED, kRawDeflate, kMemoryLevel, Z_RLE) != Z_OK) {
    libdeflate_free_compressor(compressor_);
    throw std::runtime_error("zlib could not set up a compressor");
  }
}

ChunkDeflater::~ChunkDeflater() {
  deflateEnd(runs_.get());
  libdeflate_free_compressor(compressor_);
}

std::size_t ChunkDeflater::deflate_runs(std::size_t planes, std::size_t count, bool last, ChunkBytes& out,
                                        std::size_t at) {
  // A plane at a time from a fresh state: a plane fits zlib's window, which would otherwise slide (a copy of
  // the window and a pass over its hash chains) every 32 KiB. Raw deflate blocks flushed to a byte boundary
  // follow each other as one stream; a run never needs a distance into the plane before.
  std::size_t written = 0;
  for (std::size_t p = 0; p < planes; ++p) {
    deflateReset(runs_.get());
    runs_->next_in = shuffled_.data.get() + p * count;
    runs_->avail_in = static_cast<uInt>(count);
    runs_->next_out = out.data.get() + at + written;
    runs_->avail_out = static_cast<uInt>(out.capacity - at - written);
    const bool ends_stream = last && p + 1 == planes;
    const int result = deflate(runs_.get(), ends_stream ? Z_FINISH : Z_SYNC_FLUSH);
    // With room to spare (the reserve below) one call consumes everything; a full output would mean more to
    // come.
    if (result == Z_STREAM_ERROR || runs_->avail_in != 0 || runs_->avail_out == 0 ||
        (ends_stream && result != Z_STREAM_END))
      throw std::runtime_error("zlib could not deflate a chunk");
    written = out.capacity - at - runs_->avail_out;
  }
  return written;
}

void ChunkDeflater::shuffle_deflate(const void* elements, std::size_t count, std::size_t element_bytes,
                                    ChunkBytes& out) {
  const auto* in = static_cast<const std::uint8_t*>(elements);
  const std::size_t total = count * element_bytes;
  shuffled_.reserve(total);
  if (element_bytes == 8) {
    shuffle_bytes8(in, count, shuffled_.data.get());
  } else {
    for (std::size_t b = 0; b < element_bytes; ++b) {
      std::uint8_t* plane = shuffled_.data.get() + b * count;
      for (std::size_t i = 0; i < count; ++i) plane[i] = in[i * element_bytes + b];
    }
  }
  const std::size_t run_planes = leading_run_planes(shuffled_.data.get(), count, element_bytes);
  const std::size_t runs = run_planes * count;
  const std::size_t rest = total - runs;
  constexpr std::size_t kSyncFlushBytes = 16;  // the empty stored block a sync flush ends with, and spare
  constexpr std::size_t kChecksumBytes = 4;
  out.reserve(sizeof kZlibHeader +
              run_planes * (deflateBound(runs_.get(), static_cast<uLong>(count)) + kSyncFlushBytes) +
              libdeflate_deflate_compress_bound(compressor_, rest) + kChecksumBytes);
  std::memcpy(out.data.get(), kZlibHeader, sizeof kZlibHeader);
  out.size = sizeof kZlibHeader;
  if (runs > 0) out.size += deflate_runs(run_planes, count, rest == 0, out, out.size);
  if (rest > 0 || runs == 0) {
    // libdeflate writes the final blocks (an empty one for an empty chunk), two to three times faster than
    // zlib at this level; they start at the byte boundary the runs' flush left.
    const std::size_t deflated = libdeflate_deflate_compress(
        compressor_, shuffled_.data.get() + runs, rest, out.data.get() + out.size, out.capacity - out.size);
    if (deflated == 0) throw std::runtime_error("libdeflate could not deflate a chunk");  // the bound fits
    out.size += deflated;
  }
  const std::uint32_t adler = libdeflate_adler32(1, shuffled_.data.get(), total);  // RFC 1950: big-endian
  for (int shift = 24; shift >= 0; shift -= 8)
    out.data[out.size++] = static_cast<std::uint8_t>(adler >> shift);
}

ChunkInflater::ChunkInflater() : decompressor_(libdeflate_alloc_decompressor()) {
  if (decompressor_ == nullptr) throw std::runtime_error("libdeflate could not set up a decompressor");
}

ChunkInflater::~ChunkInflater() {
  libdeflate_free_decompressor(decompressor_);
}

bool ChunkInflater::inflate(const ChunkBytes& stored, std::size_t chunk_rows, bool integers, std::size_t rows,
                            double* out) {
  constexpr std::size_t kBytes = 8;
  const std::size_t total = chunk_rows * kBytes;
  shuffled_.reserve(total);
  std::size_t inflated = 0;
  if (libdeflate_zlib_decompress(decompressor_, stored.data.get(), stored.size, shuffled_.data.get(), total,
                                 &inflated) != LIBDEFLATE_SUCCESS ||
      inflated != total)
    return false;
  unshuffle_bytes8(shuffled_.data.get(), chunk_rows, rows, reinterpret_cast<std::uint8_t*>(out));
  if (integers) {
    for (std::size_t i = 0; i < rows; ++i) {  // the integers' bits, in place, as doubles
      std::int64_t value;
      std::memcpy(&value, &out[i], kBytes);
      out[i] = static_cast<double>(value);
    }
  }
  return true;
}

}  // namespace pkm::formats
