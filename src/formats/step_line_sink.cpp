#include "formats/step_line_sink.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "interpolation/drive_output/steps_csv.hpp"

namespace pkm::formats {

StepLineSink::~StepLineSink() {
  if (descriptor_ > STDERR_FILENO) ::close(descriptor_);
}

Status StepLineSink::open(const std::string& target, int actuators) {
  target_ = target;
  actuators_ = actuators;
  if (target.empty()) return ok_status();
  if (target == "-") {
    descriptor_ = STDOUT_FILENO;
  } else {
    struct stat status {};
    const bool exists = ::stat(target.c_str(), &status) == 0;
    if (exists && S_ISDIR(status.st_mode)) return failure(EISDIR);
    if (exists && (S_ISFIFO(status.st_mode) || S_ISCHR(status.st_mode))) {
      descriptor_ = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
      if (descriptor_ < 0) return failure(errno);
    } else {
      staged_ = true;
      if (auto opened = file_.open(target); !opened) return opened;
    }
  }
  return put(interpolation::steps_csv_header(actuators));
}

Status StepLineSink::write(const interpolation::StepPeriod& period) {
  if (target_.empty()) return ok_status();
  interpolation::StepRowBuffer row;
  return put(interpolation::format_step_row(period, actuators_, row));
}

Status StepLineSink::finish() {
  return staged_ ? file_.commit() : ok_status();
}

Error StepLineSink::failure(int error_number) const {
  return make_error(ErrorCode::io,
                    fmt::format("cannot write {}: {}", target_,
                                std::error_code(error_number, std::generic_category()).message()));
}

Status StepLineSink::put(std::string_view text) {
  if (staged_) return file_.write(text);
  while (!text.empty()) {
    const ssize_t written = ::write(descriptor_, text.data(), text.size());
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) return failure(errno);
    text.remove_prefix(static_cast<std::size_t>(written));
  }
  return ok_status();
}

}  // namespace pkm::formats
