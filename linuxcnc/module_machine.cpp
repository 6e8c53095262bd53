#include "module_machine.hpp"

#include <cstdio>

#include "io/machine_file.hpp"

namespace pkm::linuxcnc {

void copy_message(const std::string& message, char* error, std::size_t size) {
  if (error == nullptr || size == 0) return;
  std::snprintf(error, size, "%s", message.c_str());
}

std::optional<Machine> load_module_machine(const char* machine_file, char* error, std::size_t size) {
  if (machine_file == nullptr || machine_file[0] == '\0') {
    copy_message("no machine file given (module parameter machine=PATH)", error, size);
    return std::nullopt;
  }
  auto loaded = load_machine_file(machine_file);
  if (!loaded) {
    copy_message(loaded.error().message, error, size);
    return std::nullopt;
  }
  return std::move(loaded.value());
}

}  // namespace pkm::linuxcnc
