#pragma once
// Candidate moves of one tact of the estimating-function method (Smirnov 2019, Table 5): every actuator
// steps by −1, 0 or +1 drive step, and a candidate set fixes which of these combinations are examined.
//   all_six     every actuator moves: 2^n candidates (64 for a hexapod), Smirnov's final recommendation
//               (§5.2.1, step 1): the 728-candidate search never needed fewer tacts (Table 5/6);
//   exactly_k   exactly k actuators move: C(n, k)·2^k (12/60/160/240/192/64 for n = 6);
//   one_to_all  any non-empty subset moves: 3^n − 1 (728 for n = 6).
#include <array>
#include <cstdint>
#include <vector>

#include "core/result.hpp"
#include "machine/mechanism.hpp"

namespace pkm::interpolation {

enum class CandidateSet { all_six, exactly_k, one_to_all };

/// Step direction of every actuator in one candidate: −1, 0 or +1.
using StepDirections = std::array<std::int8_t, kMaxActuators>;

/// Number of candidates per tact: 2^n, C(n, k)·2^k or 3^n − 1; 0 for k outside 1…n.
std::int64_t candidate_count(CandidateSet set, int actuators, int struts_per_tact);

/// The candidates themselves, in a fixed order (built once, before the first tact). Errors for n outside
/// 1…kMaxActuators or k outside 1…n.
Result<std::vector<StepDirections>> candidate_directions(CandidateSet set, int actuators,
                                                         int struts_per_tact);

}  // namespace pkm::interpolation
