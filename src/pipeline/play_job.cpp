#include "pipeline/play_job.hpp"

#include <filesystem>
#include <system_error>

#include "formats/step_line_sink.hpp"

namespace pkm::pipeline {

Result<PlayJobResult> run_play_job(const PlayJob& job) {
  std::error_code error;
  const std::string path = std::filesystem::is_directory(job.input, error)
                               ? interpolation::step_stream_path(job.input)
                               : job.input;
  interpolation::StepStreamReader reader;
  if (Status opened = reader.open(path); !opened) return opened.error();
  formats::StepLineSink sink;
  if (Status opened = sink.open(job.to, reader.header().actuators); !opened) return opened.error();
  auto played = interpolation::play(reader, sink, job.settings);
  if (!played) return played.error();
  return PlayJobResult{path, reader.header(), reader.period_count(), *played};
}

}  // namespace pkm::pipeline
