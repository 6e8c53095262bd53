#include "interpolation/methods/estimating_candidates.hpp"

#include <fmt/format.h>

namespace pkm::interpolation {

std::int64_t candidate_count(CandidateSet set, int actuators, int struts_per_tact) {
  if (actuators < 1 || actuators > kMaxActuators) return 0;
  std::int64_t power2 = 1;
  std::int64_t power3 = 1;
  for (int j = 0; j < actuators; ++j) {
    power2 *= 2;
    power3 *= 3;
  }
  switch (set) {
    case CandidateSet::all_six:
      return power2;
    case CandidateSet::one_to_all:
      return power3 - 1;
    case CandidateSet::exactly_k: {
      const int k = struts_per_tact;
      if (k < 1 || k > actuators) return 0;
      std::int64_t choose = 1;  // C(n, k), exact at every step: C(n, i+1) = C(n, i)·(n − i)/(i + 1)
      std::int64_t signs = 1;
      for (int i = 0; i < k; ++i) {
        choose = choose * (actuators - i) / (i + 1);
        signs *= 2;
      }
      return choose * signs;
    }
  }
  return 0;
}

Result<std::vector<StepDirections>> candidate_directions(CandidateSet set, int actuators,
                                                         int struts_per_tact) {
  if (actuators < 1 || actuators > kMaxActuators) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("estimating-function interpolation needs 1…{} actuators, the mechanism has {}",
                    kMaxActuators, actuators));
  }
  if (set == CandidateSet::exactly_k && (struts_per_tact < 1 || struts_per_tact > actuators)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("struts_per_tact = {} is outside 1…{} (the mechanism's actuators)",
                                  struts_per_tact, actuators));
  }
  // Enumerate all 3^n digit strings (digit 0 → −1, 1 → idle, 2 → +1) and keep those the set asks for.
  std::int64_t total = 1;
  for (int j = 0; j < actuators; ++j) total *= 3;
  std::vector<StepDirections> out;
  out.reserve(static_cast<std::size_t>(candidate_count(set, actuators, struts_per_tact)));
  for (std::int64_t code = 0; code < total; ++code) {
    StepDirections d{};
    int moving = 0;
    std::int64_t rest = code;
    for (int j = 0; j < actuators; ++j) {
      d[j] = static_cast<std::int8_t>(rest % 3 - 1);
      rest /= 3;
      moving += d[j] != 0 ? 1 : 0;
    }
    const bool wanted = set == CandidateSet::all_six     ? moving == actuators
                        : set == CandidateSet::exactly_k ? moving == struts_per_tact
                                                         : moving > 0;
    if (wanted) out.push_back(d);
  }
  return out;
}

}  // namespace pkm::interpolation
