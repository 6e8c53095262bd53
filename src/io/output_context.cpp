#include "io/output_context.hpp"

#include <mutex>

namespace pkm {

namespace {

std::mutex& output_context_mutex() {
  static std::mutex mutex;
  return mutex;
}

OutputContext& output_context_storage() {
  static OutputContext context;
  return context;
}

}  // namespace

void set_output_context(OutputContext context) {
  const std::lock_guard lock(output_context_mutex());
  output_context_storage() = std::move(context);
}

OutputContext output_context() {
  const std::lock_guard lock(output_context_mutex());
  return output_context_storage();
}

}  // namespace pkm
