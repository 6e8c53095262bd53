#include "io/output_file.hpp"

#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/output_manifest.hpp"
#include "io/output_set.hpp"

namespace pkm {

Status write_output_file(const std::string& path, std::string_view text) {
  namespace fs = std::filesystem;
  const fs::path file(path);
  const std::string folder = file.has_parent_path() ? file.parent_path().string() : std::string(".");
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) return write_file_atomically(path, text);
  auto manifest = read_output_manifest(folder);
  if (!manifest) return manifest.error();
  if (!*manifest) return write_file_atomically(path, text);
  OutputSet set;
  if (Status joined = set.join_directory(folder, {(*manifest)->command}); !joined) return joined;
  if (Status written = write_file_atomically(set.staged_path(file.filename().string()), text); !written)
    return written;
  return set.commit();
}

}  // namespace pkm
