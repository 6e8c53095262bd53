#include "pipeline/program_stream.hpp"

#include <algorithm>
#include <filesystem>

namespace pkm::pipeline {

namespace {

/// Moves handed over at once, and batches the reader may be ahead: the lock is taken once per batch.
constexpr std::size_t kBatchMoves = 512;
constexpr std::size_t kMaxBatchesAhead = 8;
constexpr std::size_t kMaxPlacesPerLine = 8;

}  // namespace

void SubroutineLines::add(const program::CanonicalMove& move) {
  if (move.source_file == 0 && move.source_line == move.line) return;
  if (move.line <= 0 || move.source_line <= 0) return;
  std::vector<std::pair<int, int>>& here = places_[move.line];
  if (here.size() >= kMaxPlacesPerLine) return;
  const std::pair<int, int> place{move.source_file, move.source_line};
  if (std::find(here.begin(), here.end(), place) == here.end()) here.push_back(place);
}

nlohmann::json SubroutineLines::json(const std::vector<std::string>& files) const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [line, list] : places_) {
    std::vector<std::string> named;
    for (const auto& [file, source_line] : list) {
      const std::size_t index = static_cast<std::size_t>(file);
      const std::string name =
          index < files.size() ? std::filesystem::path(files[index]).filename().string() : std::string("?");
      std::string place = name + ":" + std::to_string(source_line);
      // Two files of the same name are one place to the reader of the report.
      if (std::find(named.begin(), named.end(), place) == named.end()) named.push_back(std::move(place));
    }
    out[std::to_string(line)] = std::move(named);
  }
  return out;
}

ProgramStream::ProgramStream(const Machine& machine, std::string program_path, ProgramOptions options,
                             SubroutineLines* places, program::CanonicalProgram* header)
    : machine_(machine),
      path_(std::move(program_path)),
      options_(std::move(options)),
      places_(places),
      header_(header) {
  auto mapped = MappedText::open(path_, "part program");
  if (!mapped) {
    open_error_ = mapped.error();
    return;
  }
  text_ = std::move(*mapped);
  line_count_ = text_->line_count();
  filling_.reserve(kBatchMoves);
  reader_ = std::thread([this] { read(); });
}

ProgramStream::~ProgramStream() {
  stop();
}

void ProgramStream::stop() {
  {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  changed_.notify_all();
  if (reader_.joinable()) reader_.join();
}

Status ProgramStream::take(const program::CanonicalMove& move) {
  filling_.push_back(move);
  if (filling_.size() < kBatchMoves) return ok_status();
  text_->keep_around(text_->offset_near_line(move.line));
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return cancelled_ || full_.size() < kMaxBatchesAhead; });
  if (cancelled_) return Error{ErrorCode::bad_input, "the planner stopped reading the program"};
  full_.push_back(std::move(filling_));
  filling_ = {};
  filling_.reserve(kBatchMoves);
  lock.unlock();
  changed_.notify_all();
  return ok_status();
}

void ProgramStream::read() {
  auto program = program::read_part_program(
      text_->text(), path_,
      interpret_options_for(machine_, options_,
                            [this](const program::CanonicalMove& move) { return take(move); }));
  std::lock_guard lock(mutex_);
  if (program) {
    if (header_ != nullptr) *header_ = std::move(*program);
    if (!filling_.empty()) full_.push_back(std::move(filling_));
  } else {
    error_ = program.error();
  }
  done_ = true;
  changed_.notify_all();
}

Result<const program::CanonicalMove*> ProgramStream::next() {
  if (open_error_) return *open_error_;
  if (taken_ < taking_.size()) {
    const program::CanonicalMove* move = &taking_[taken_++];
    if (places_ != nullptr) places_->add(*move);
    return move;
  }
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return done_ || !full_.empty(); });
  if (full_.empty()) {
    if (error_) return *error_;
    if (reader_.joinable()) {
      lock.unlock();
      reader_.join();
    }
    return static_cast<const program::CanonicalMove*>(nullptr);
  }
  taking_ = std::move(full_.front());
  full_.pop_front();
  taken_ = 0;
  lock.unlock();
  changed_.notify_all();
  return next();
}

Result<program::CanonicalProgram> ProgramStream::whole() const {
  return load_program_for(machine_, path_, options_);
}

Result<StreamedProgramPlan> start_streamed_program_plan(const Machine& machine,
                                                        const std::string& program_path,
                                                        const ProgramOptions& program_options,
                                                        const planning::PlanOptions& options) {
  StreamedProgramPlan started;
  started.program = std::make_unique<program::CanonicalProgram>();
  started.program->source = program_path;
  const planning::ProgramStart start = planning::program_start(machine);
  started.program->start_mm = start.start_mm;
  started.program->start_abc_deg = start.start_abc_deg;
  started.places = std::make_unique<SubroutineLines>();
  started.header = std::make_unique<program::CanonicalProgram>();
  const planning::MoveSourceFactory read = [&]() -> Result<std::unique_ptr<planning::MoveSource>> {
    return std::unique_ptr<planning::MoveSource>(std::make_unique<ProgramStream>(
        machine, program_path, program_options, started.places.get(), started.header.get()));
  };
  auto streamed = planning::start_streamed_plan(machine, *started.program, read, options);
  if (!streamed) return streamed.error();
  started.plan = std::move(*streamed);
  return started;
}

}  // namespace pkm::pipeline
