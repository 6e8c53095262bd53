#pragma once
// The bytes HDF5 stores for one chunk of a column written through the shuffle and deflate filters
// (hdf5_table.cpp), made here rather than by the library: the chunk can then be compressed on another thread
// while the next one fills, and written with H5Dwrite_chunk. The same pipeline HDF5 runs, in its order: the
// shuffle (byte k of every element together, so the zero low bytes of quantised values form long runs),
// then deflate in the zlib format, which HDF5's deflate filter inflates (libdeflate, Debian's libdeflate-dev,
// the same format zlib's compress2 writes, faster). Readers undo both as for any chunk the library wrote.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pkm::formats {

/// Shuffles `count` little-endian elements of `element_bytes` bytes each, then deflates them at `level`.
std::vector<std::uint8_t> shuffle_deflate(const void* elements, std::size_t count, std::size_t element_bytes,
                                          int level);

}  // namespace pkm::formats
