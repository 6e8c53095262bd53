#include "io/output_cleanup.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>

namespace pkm {

namespace {

constexpr int kCleanupSlots = 64;
constexpr std::size_t kCleanupPathBytes = 4096;
constexpr int kCleanupTreeDepth = 8;  // staging folders hold files and one level of subfolders

struct CleanupSlot {
  std::atomic<int> state{0};  // 0 free, 1 being written, 2 active
  CleanupKind kind = CleanupKind::file;
  char path[kCleanupPathBytes] = {};
};

std::array<CleanupSlot, kCleanupSlots>& cleanup_slots() {
  static std::array<CleanupSlot, kCleanupSlots> slots;
  return slots;
}

// The kernel's record of getdents64: ino64 d_ino, off64 d_off, unsigned short d_reclen, unsigned char d_type,
// then the name (NUL-terminated).
constexpr std::size_t kDirentReclenOffset = 16;
constexpr std::size_t kDirentNameOffset = 19;

// Removes everything below the open folder `folder` (then closes it): getdents64 and unlinkat only.
void cleanup_remove_below(int folder, int depth) {
  alignas(8) char buffer[2048];
  // Names removed while reading may hide others: read the folder again while a pass removed something (a
  // pass that removes nothing ends it, also when something cannot be removed).
  for (bool removed = true; removed;) {
    removed = false;
    ::lseek(folder, 0, SEEK_SET);
    for (long got; (got = ::syscall(SYS_getdents64, folder, buffer, sizeof buffer)) > 0;) {
      for (long at = 0; at < got;) {
        unsigned short record_length = 0;
        std::memcpy(&record_length, buffer + at + kDirentReclenOffset, sizeof record_length);
        const char* name = buffer + at + kDirentNameOffset;
        at += record_length;
        if (std::strcmp(name, ".") == 0 || std::strcmp(name, "..") == 0) continue;
        if (::unlinkat(folder, name, 0) == 0) {
          removed = true;
          continue;
        }
        if (depth < kCleanupTreeDepth) {
          const int inner = ::openat(folder, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (inner >= 0) cleanup_remove_below(inner, depth + 1);
        }
        if (::unlinkat(folder, name, AT_REMOVEDIR) == 0) removed = true;
      }
    }
  }
  ::close(folder);
}

void cleanup_remove(const CleanupSlot& slot) {
  switch (slot.kind) {
    case CleanupKind::file:
      ::unlink(slot.path);
      break;
    case CleanupKind::tree: {
      const int folder = ::open(slot.path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (folder >= 0) cleanup_remove_below(folder, 0);
      ::rmdir(slot.path);
      break;
    }
    case CleanupKind::empty_directory:
      ::rmdir(slot.path);
      break;
  }
}

// While a SignalBlock lives (a commit, a temporary being made and registered) the handler only records the
// signal (it may run in another thread, which does not block it); the commit raises it again when done.
std::atomic<int> g_held{0};  // SignalBlocks alive (they nest)
std::atomic<int> g_deferred_signal{0};

extern "C" void output_cleanup_on_signal(int signal_number) {
  if (g_held.load() > 0) {
    g_deferred_signal.store(signal_number);
    return;
  }
  auto& slots = cleanup_slots();
  // Files and trees first, then the folders a set created, innermost (registered last) first.
  for (auto& slot : slots)
    if (slot.state.load() == 2 && slot.kind != CleanupKind::empty_directory) cleanup_remove(slot);
  for (auto it = slots.rbegin(); it != slots.rend(); ++it)
    if (it->state.load() == 2 && it->kind == CleanupKind::empty_directory) cleanup_remove(*it);
  ::_exit(128 + signal_number);
}

}  // namespace

void install_output_cleanup_handlers() {
  struct sigaction action {};
  action.sa_handler = output_cleanup_on_signal;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  for (const int signal_number : {SIGINT, SIGTERM}) ::sigaction(signal_number, &action, nullptr);
}

int register_cleanup(const std::string& path, CleanupKind kind) {
  if (path.size() >= kCleanupPathBytes) return -1;
  auto& slots = cleanup_slots();
  for (int i = 0; i < kCleanupSlots; ++i) {
    int expected = 0;
    if (!slots[i].state.compare_exchange_strong(expected, 1)) continue;
    slots[i].kind = kind;
    std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
    slots[i].state.store(2);  // published whole: the handler never reads a half-written path
    return i;
  }
  return -1;
}

void unregister_cleanup(int slot) {
  if (slot >= 0 && slot < kCleanupSlots) cleanup_slots()[slot].state.store(0);
}

SignalBlock::SignalBlock() {
  static_assert(sizeof(sigset_t) <= sizeof(saved_));
  sigset_t block;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  ::pthread_sigmask(SIG_BLOCK, &block, reinterpret_cast<sigset_t*>(saved_));
  g_held.fetch_add(1);
}

SignalBlock::~SignalBlock() {
  const bool outermost = g_held.fetch_sub(1) == 1;
  ::pthread_sigmask(SIG_SETMASK, reinterpret_cast<const sigset_t*>(saved_), nullptr);
  if (!outermost) return;
  if (const int deferred = g_deferred_signal.exchange(0); deferred != 0) ::raise(deferred);
}

}  // namespace pkm
