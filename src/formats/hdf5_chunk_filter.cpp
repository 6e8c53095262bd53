#include "formats/hdf5_chunk_filter.hpp"

#include <zlib.h>

#include <stdexcept>

namespace pkm::formats {

std::vector<std::uint8_t> shuffle_deflate(const void* elements, std::size_t count, std::size_t element_bytes,
                                          int level) {
  const auto* in = static_cast<const std::uint8_t*>(elements);
  const std::size_t total = count * element_bytes;
  std::vector<std::uint8_t> shuffled(total);
  for (std::size_t b = 0; b < element_bytes; ++b) {
    std::uint8_t* plane = shuffled.data() + b * count;
    for (std::size_t i = 0; i < count; ++i) plane[i] = in[i * element_bytes + b];
  }
  uLongf size = compressBound(static_cast<uLong>(total));
  std::vector<std::uint8_t> out(size);
  if (compress2(out.data(), &size, shuffled.data(), static_cast<uLong>(total), level) != Z_OK)
    throw std::runtime_error("zlib could not deflate a chunk");  // only out of memory: compressBound fits
  out.resize(size);
  return out;
}

}  // namespace pkm::formats
