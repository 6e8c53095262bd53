#include "io/mapped_text.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <system_error>

#include "io/input_file.hpp"

namespace pkm {

namespace {

constexpr int kIndexEvery = 1024;  ///< lines between two entries of the line index
/// What stays mapped around the reader: behind, for a short jump back (a loop body), and ahead.
constexpr std::size_t kKeepBehindBytes = std::size_t{1} << 20;
constexpr std::size_t kKeepAheadBytes = std::size_t{1} << 20;
/// Indexing the lines gives back what it has read every so many bytes.
constexpr std::size_t kIndexReleaseBytes = std::size_t{4} << 20;

std::size_t page_size() {
  static const std::size_t size = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  return size;
}

}  // namespace

Result<std::unique_ptr<MappedText>> MappedText::open(const std::string& path, std::string_view what) {
  if (Status checked = check_input_file(path, what, InputReading::streamed); !checked) return checked.error();
  std::unique_ptr<MappedText> mapped(new MappedText());
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) {
    return make_error(ErrorCode::io, fmt::format("{}: cannot read {}: {}", path, what,
                                                 std::error_code(errno, std::generic_category()).message()));
  }
  const off_t size = ::lseek(descriptor, 0, SEEK_END);
  if (size > 0) {
    void* at = ::mmap(nullptr, static_cast<std::size_t>(size), PROT_READ, MAP_PRIVATE, descriptor, 0);
    if (at != MAP_FAILED) {
      mapped->mapping_ = at;
      mapped->mapped_bytes_ = static_cast<std::size_t>(size);
      ::madvise(at, mapped->mapped_bytes_, MADV_SEQUENTIAL);
    }
  }
  ::close(descriptor);
  if (size > 0 && mapped->mapping_ == nullptr) {
    return make_error(ErrorCode::io,
                      fmt::format("{}: cannot read {}: cannot map it into memory", path, what));
  }
  mapped->text_ = std::string_view(static_cast<const char*>(mapped->mapping_), mapped->mapped_bytes_);
  static constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (mapped->text_.substr(0, kByteOrderMark.size()) == kByteOrderMark)
    mapped->text_.remove_prefix(kByteOrderMark.size());
  if (!mapped->index_lines()) {  // lone carriage returns: read whole and normalised instead
    auto whole = read_text_input(path, what);
    if (!whole) return whole.error();
    mapped->whole_ = std::move(*whole);
    mapped->text_ = mapped->whole_;
    mapped->index_lines();
  }
  return mapped;
}

MappedText::~MappedText() {
  if (mapping_ != nullptr) ::munmap(mapping_, mapped_bytes_);
}

bool MappedText::index_lines() {
  line_offsets_.assign(1, 0);
  long lines = 1;
  bool lone_carriage_return = false;
  // In pieces, each given back once scanned: the whole file is never resident at once.
  for (std::size_t begin = 0; begin < text_.size(); begin += kIndexReleaseBytes) {
    const std::string_view piece = text_.substr(begin, kIndexReleaseBytes);
    for (std::size_t at = piece.find('\n'); at != std::string_view::npos; at = piece.find('\n', at + 1)) {
      const std::size_t next = begin + at + 1;
      if (next >= text_.size()) break;
      if (lines % kIndexEvery == 0) line_offsets_.push_back(next);
      ++lines;
    }
    for (std::size_t at = piece.find('\r'); at != std::string_view::npos; at = piece.find('\r', at + 1)) {
      if (begin + at + 1 == text_.size() || text_[begin + at + 1] != '\n') lone_carriage_return = true;
    }
    keep_around(begin);
  }
  line_count_ = static_cast<int>(std::min<long>(lines, std::numeric_limits<int>::max()));
  keep_around(0);
  return !lone_carriage_return || !whole_.empty();
}

std::size_t MappedText::offset_near_line(int line) const {
  if (line <= 1 || line_offsets_.empty()) return 0;
  const std::size_t entry =
      std::min(static_cast<std::size_t>(line - 1) / kIndexEvery, line_offsets_.size() - 1);
  return line_offsets_[entry];
}

void MappedText::keep_around(std::size_t offset) {
  if (mapping_ == nullptr || !whole_.empty()) return;
  const std::size_t page = page_size();
  const std::size_t skipped = static_cast<std::size_t>(text_.data() - static_cast<const char*>(mapping_));
  const std::size_t at = std::min(offset + skipped, mapped_bytes_);
  const std::size_t behind = at > kKeepBehindBytes ? (at - kKeepBehindBytes) / page * page : 0;
  char* base = static_cast<char*>(mapping_);
  if (behind > 0) ::madvise(base, behind, MADV_DONTNEED);
  const std::size_t ahead = std::min(mapped_bytes_, (at + kKeepAheadBytes + page - 1) / page * page);
  if (ahead < mapped_bytes_) ::madvise(base + ahead, mapped_bytes_ - ahead, MADV_DONTNEED);
}

}  // namespace pkm
