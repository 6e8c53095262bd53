#pragma once
// One output file of a run written in chunks: rows gather in a buffer that goes to a StagedFile a megabyte at
// a time, so that a run of millions of rows neither holds its whole text nor pays a system call per row.
// Nothing appears at the path until commit().
#include <fmt/format.h>

#include <string>
#include <string_view>

#include "io/atomic_file.hpp"

namespace pkm {

struct BufferedStagedFile {
  static constexpr std::size_t kChunk = std::size_t{1} << 20;
  StagedFile file;
  fmt::memory_buffer buffer;

  Status open(const std::string& path) {
    buffer.reserve(kChunk);
    return file.open(path);
  }
  Status flush() {
    const Status written = file.write(std::string_view(buffer.data(), buffer.size()));
    buffer.clear();
    return written;
  }
  Status flush_if_large() { return buffer.size() > kChunk ? flush() : ok_status(); }
  Status commit() {
    if (auto flushed = flush(); !flushed) return flushed;
    return file.commit();
  }
};

}  // namespace pkm
