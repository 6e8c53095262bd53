#include "formats/hdf5_chunk_filter.hpp"

#include <libdeflate.h>

#include <memory>
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
  // libdeflate writes the same zlib stream HDF5's deflate filter inflates, two to three times faster than
  // zlib at this level. A compressor per call: chunks are deflated on threads of their own.
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(level), &libdeflate_free_compressor);
  if (!compressor) throw std::runtime_error("libdeflate could not set up a compressor");
  std::vector<std::uint8_t> out(libdeflate_zlib_compress_bound(compressor.get(), total));
  const std::size_t size =
      libdeflate_zlib_compress(compressor.get(), shuffled.data(), total, out.data(), out.size());
  if (size == 0) throw std::runtime_error("libdeflate could not deflate a chunk");  // the bound always fits
  out.resize(size);
  return out;
}

}  // namespace pkm::formats
