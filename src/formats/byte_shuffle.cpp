#include "formats/byte_shuffle.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace pkm::formats {

namespace {

constexpr std::size_t kElementBytes = 8;

#if defined(__SSE2__)
constexpr std::size_t kBlockElements = 16;  // 128 bytes: eight 16-byte registers

/// One round: registers k and k + 4 interleaved byte by byte into 2k and 2k + 1. Over the block's 7-bit
/// byte index (register 3 bits, position 4 bits) it rotates the index left by one bit.
inline void interleave_round(__m128i (&v)[8]) {
  __m128i out[8];
  for (int k = 0; k < 4; ++k) {
    out[2 * k] = _mm_unpacklo_epi8(v[k], v[k + 4]);
    out[2 * k + 1] = _mm_unpackhi_epi8(v[k], v[k + 4]);
  }
  for (int k = 0; k < 8; ++k) v[k] = out[k];
}
#endif

}  // namespace

void shuffle_bytes8(const std::uint8_t* elements, std::size_t count, std::uint8_t* planes) {
  std::size_t i = 0;
#if defined(__SSE2__)
  // Index (element 4 bits, byte 3 bits) → (byte 3 bits, element 4 bits): a rotation by four.
  for (; i + kBlockElements <= count; i += kBlockElements) {
    __m128i v[8];
    for (int k = 0; k < 8; ++k)
      v[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(elements + i * kElementBytes + 16 * k));
    for (int round = 0; round < 4; ++round) interleave_round(v);
    for (int b = 0; b < 8; ++b) _mm_storeu_si128(reinterpret_cast<__m128i*>(planes + b * count + i), v[b]);
  }
#endif
  for (; i < count; ++i)
    for (std::size_t b = 0; b < kElementBytes; ++b) planes[b * count + i] = elements[i * kElementBytes + b];
}

void unshuffle_bytes8(const std::uint8_t* planes, std::size_t plane_bytes, std::size_t rows,
                      std::uint8_t* elements) {
  std::size_t i = 0;
#if defined(__SSE2__)
  // (byte, element) → (element, byte): three more rotations complete the seven.
  for (; i + kBlockElements <= rows; i += kBlockElements) {
    __m128i v[8];
    for (int b = 0; b < 8; ++b)
      v[b] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(planes + b * plane_bytes + i));
    for (int round = 0; round < 3; ++round) interleave_round(v);
    for (int k = 0; k < 8; ++k)
      _mm_storeu_si128(reinterpret_cast<__m128i*>(elements + i * kElementBytes + 16 * k), v[k]);
  }
#endif
  for (; i < rows; ++i)
    for (std::size_t b = 0; b < kElementBytes; ++b)
      elements[i * kElementBytes + b] = planes[b * plane_bytes + i];
}

}  // namespace pkm::formats
