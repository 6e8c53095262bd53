#include "io/content_hash.hpp"

#include <fmt/format.h>

#include <array>
#include <fstream>

namespace pkm {

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash) {
  constexpr std::uint64_t kPrime = 0x100000001b3ULL;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= kPrime;
  }
  return hash;
}

Result<std::string> file_content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io, fmt::format("{}: cannot read for its content hash", path));
  std::array<char, 1 << 16> buffer{};
  std::uint64_t hash = fnv1a64({});
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hash = fnv1a64(std::string_view(buffer.data(), static_cast<std::size_t>(in.gcount())), hash);
  }
  if (in.bad()) return make_error(ErrorCode::io, fmt::format("{}: read error for its content hash", path));
  return fmt::format("{:016x}", hash);
}

}  // namespace pkm
