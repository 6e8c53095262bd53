#include "formats/contour_trace.hpp"

#include <fmt/format.h>

#include <iterator>

namespace pkm::formats {

namespace {
constexpr std::size_t kContourTraceChunk = std::size_t{1} << 20;
}

Status ContourTraceWriter::open(const std::string& path) {
  if (Status opened = file_.open(path); !opened) return opened;
  buffer_.reserve(kContourTraceChunk + 256);
  buffer_ = "period,time_s,line,max_error_mm,x_mm,y_mm,z_mm,path_x_mm,path_y_mm,path_z_mm\n";
  open_ = true;
  return ok_status();
}

Status ContourTraceWriter::add(const interpolation::StepPeriod& period,
                               const interpolation::PeriodContour& contour, const Eigen::Vector3d& path_mm) {
  if (!open_) return make_error(ErrorCode::io, "contour trace written before it was opened");
  auto out = std::back_inserter(buffer_);
  fmt::format_to(out, "{},{:.6f},{},{:.4e},", period.index, period.time_s, period.line, contour.max_error_mm);
  // An FK failure at the period's end leaves the tool point empty rather than inventing one.
  if (contour.solved) {
    fmt::format_to(out, "{:.6f},{:.6f},{:.6f},", contour.tool_mm.x(), contour.tool_mm.y(),
                   contour.tool_mm.z());
  } else {
    buffer_ += ",,,";
  }
  fmt::format_to(out, "{:.6f},{:.6f},{:.6f}\n", path_mm.x(), path_mm.y(), path_mm.z());
  return buffer_.size() > kContourTraceChunk ? flush() : ok_status();
}

Status ContourTraceWriter::flush() {
  const Status written = file_.write(buffer_);
  buffer_.clear();
  return written;
}

Status ContourTraceWriter::finish() {
  if (!open_) return make_error(ErrorCode::io, "contour trace finished before it was opened");
  if (Status flushed = flush(); !flushed) return flushed;
  open_ = false;
  return file_.commit();
}

}  // namespace pkm::formats
