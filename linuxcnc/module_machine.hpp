#pragma once
// The machine file a LinuxCNC module of pkm's is given (`loadrt pkmkins machine=PATH`, `loadrt pkmexec
// machine=PATH`), read once when the module loads, and its messages copied into the module's C buffer.
#include <cstddef>
#include <optional>
#include <string>

#include "machine/machine.hpp"

namespace pkm::linuxcnc {

/// Copies `message` into the C buffer `error` of `size` bytes (cut to fit, always terminated).
void copy_message(const std::string& message, char* error, std::size_t size);

/// The machine, or nothing with the reader's message (file, line, column, key) in `error`.
std::optional<Machine> load_module_machine(const char* machine_file, char* error, std::size_t size);

}  // namespace pkm::linuxcnc
