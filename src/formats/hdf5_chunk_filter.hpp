#pragma once
// The bytes HDF5 stores for one chunk of a column written through the shuffle and deflate filters
// (hdf5_table.cpp), made here rather than by the library: the chunk can then be compressed on another thread
// while the next one fills, and written with H5Dwrite_chunk. The same pipeline HDF5 runs, in its order: the
// shuffle (byte k of every element together, so the zero low bytes of quantised values form long runs),
// then deflate in the zlib format, which HDF5's deflate filter inflates (libdeflate, Debian's libdeflate-dev,
// the same format zlib's compress2 writes, faster). Readers undo both as for any chunk the library wrote.
//
// The planes made of long runs of one byte (the low bytes of values rounded to fewer significant bits, the
// exponent of a column that stays within one binade, a program line held for a hundred ticks) cost
// libdeflate as much time as any other bytes, while zlib's run-length strategy encodes them in a few
// microseconds. A deflate stream is a sequence of blocks, so the leading such planes are deflated by zlib and
// flushed to a byte boundary (a sync flush), and libdeflate deflates the rest as the stream's final blocks:
// one zlib stream, read by any inflater.
#include <cstddef>
#include <cstdint>
#include <memory>

struct libdeflate_compressor;
struct libdeflate_decompressor;
struct z_stream_s;

namespace pkm::formats {

/// Bytes that keep their storage from one chunk to the next (no clearing, no reallocation once large
/// enough): a run writes millions of chunks.
struct ChunkBytes {
  std::unique_ptr<std::uint8_t[]> data;
  std::size_t capacity = 0;
  std::size_t size = 0;
  void reserve(std::size_t bytes);
};

/// A compressor and its shuffle buffer, made once and used for every chunk of a table (on one thread).
class ChunkDeflater {
 public:
  explicit ChunkDeflater(int level);
  ~ChunkDeflater();
  ChunkDeflater(const ChunkDeflater&) = delete;
  ChunkDeflater& operator=(const ChunkDeflater&) = delete;
  /// Shuffles `count` little-endian elements of `element_bytes` bytes each, then deflates them into `out`.
  void shuffle_deflate(const void* elements, std::size_t count, std::size_t element_bytes, ChunkBytes& out);

 private:
  /// Deflates the first `planes` planes of `count` bytes of the shuffled chunk (made of runs) with zlib's
  /// run-length strategy into `out` from `at`: the bytes written. The stream ends there when `last`, else
  /// at a byte boundary.
  std::size_t deflate_runs(std::size_t planes, std::size_t count, bool last, ChunkBytes& out, std::size_t at);

  libdeflate_compressor* compressor_ = nullptr;
  std::unique_ptr<z_stream_s> runs_;  ///< zlib's raw deflate, run-length strategy
  ChunkBytes shuffled_;
};

/// The way back, for a reader of such chunks (hdf5_table_reader.cpp): inflates a chunk HDF5 stored through
/// the shuffle and deflate filters and undoes the shuffle, faster than HDF5's own pipeline (zlib).
class ChunkInflater {
 public:
  ChunkInflater();
  ~ChunkInflater();
  ChunkInflater(const ChunkInflater&) = delete;
  ChunkInflater& operator=(const ChunkInflater&) = delete;
  /// The first `rows` of a chunk of `chunk_rows` 8-byte elements (doubles, or 64-bit integers when
  /// `integers`) as doubles into `out`; false when the bytes are not such a chunk.
  bool inflate(const ChunkBytes& stored, std::size_t chunk_rows, bool integers, std::size_t rows,
               double* out);

 private:
  libdeflate_decompressor* decompressor_ = nullptr;
  ChunkBytes shuffled_;
};

}  // namespace pkm::formats
