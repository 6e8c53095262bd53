#include "kinematics/stewart_all_modes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <mutex>
#include <random>
#include <thread>

namespace pkm {
namespace {

Complex monodromy_random_complex(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const double re = normal(rng);
  return {re, normal(rng)};
}

Eigen::Vector3cd monodromy_random_vector(std::mt19937_64& rng) {
  return {monodromy_random_complex(rng), monodromy_random_complex(rng), monodromy_random_complex(rng)};
}

StewartParameters monodromy_random_parameters(std::mt19937_64& rng) {
  std::array<Eigen::Vector3cd, 6> base, platform;
  std::array<Complex, 6> length_squared;
  for (int j = 0; j < 6; ++j) {
    base[j] = monodromy_random_vector(rng);
    platform[j] = monodromy_random_vector(rng);
    length_squared[j] = monodromy_random_complex(rng);
  }
  return StewartParameters::from_joints(base, platform, length_squared);
}

bool same_study_point(const StudyPoint& a, const StudyPoint& b) {
  return (a - b).norm() <= 1e-8 * (1.0 + a.norm());
}

bool known_study_point(const std::vector<StudyPoint>& roots, const StudyPoint& x) {
  return std::any_of(roots.begin(), roots.end(), [&](const StudyPoint& r) { return same_study_point(r, x); });
}

/// x with the common complex factor removed: divided by its largest rotation coordinate. The Study
/// coordinates are projective (each path's end is scaled by the complex chart), so this is what compares two
/// endpoints; a real pose has a real representative, and the conjugate of this form is the form of the
/// conjugate solution.
StudyPoint without_common_factor(const StudyPoint& x) {
  int k = 0;
  x.head<4>().cwiseAbs().maxCoeff(&k);
  return x / x[k];
}

// Follows x along from → via_1 → via_2 → from; false when a leg does not end at a regular finite solution.
bool monodromy_loop(const StewartSystem& system, const StewartParameters& from,
                    const StewartParameters& via_1, const StewartParameters& via_2, StudyPoint& x) {
  for (const auto& [a, b] : {std::pair{&from, &via_1}, std::pair{&via_1, &via_2}, std::pair{&via_2, &from}}) {
    const TrackedPath path = track_stewart_path(system, *a, *b, x);
    if (path.end != PathEnd::finite || path.pivot_ratio < 1e-10) return false;
    x = path.x;
  }
  return true;
}

// The target is real, so the conjugate of a solution is one too. Once the distinct regular endpoints and
// their conjugates number the start system's 40 (the generic root count), every solution is known, and each
// path not yet followed ends at one of the complex ones no followed path reached: it is not followed (about a
// tenth of the paths on general geometries). A path that jumped onto another's solution cannot fake this: the
// solution it lost is then counted only through its conjugate, and a lost real one keeps the count below 40.
class KnownSolutions {
 public:
  KnownSolutions(std::size_t all, double real_tolerance) : all_(all), real_tolerance_(real_tolerance) {
    known_.reserve(all);
  }
  /// Counts a path's end; true once every solution is known.
  bool add(const TrackedPath& end) {
    if (end.end != PathEnd::finite || !(end.pivot_ratio > 1e-8)) return false;
    // Compared at the accuracy of the endpoints (that of telling a real one): two distinct solutions closer
    // than that only keep the count below 40, which costs the saving, never a solution.
    const StudyPoint x = without_common_factor(end.x);
    const double tolerance = real_tolerance_ * x.norm();
    const auto is_known = [&](const StudyPoint& y) {
      return std::any_of(known_.begin(), known_.end(),
                         [&](const StudyPoint& k) { return (k - y).norm() <= tolerance; });
    };
    if (!is_known(x)) {
      known_.push_back(x);
      if (x.imag().norm() > tolerance && !is_known(x.conjugate())) known_.push_back(x.conjugate());
    }
    return known_.size() >= all_;
  }

 private:
  std::size_t all_;
  double real_tolerance_;
  std::vector<StudyPoint> known_;
};

// The start system's paths to `target`, handed out in index order to `options.threads` threads (the paths
// are independent; one thread: this one alone) until every solution is known. Every path handed out is
// followed to its end, so the paths followed are always the first ones: ends[k] is the path from root k.
// With more threads a few more paths may be followed than with one (those in flight when the last solution
// turns up); the solutions found are the same.
std::vector<TrackedPath> follow_start_paths(const StewartSystem& system, const StewartStartSystem& start,
                                            const StewartParameters& target,
                                            const StewartAllModesOptions& options, int& steps) {
  const int count = static_cast<int>(start.roots.size());
  std::vector<TrackedPath> ends(start.roots.size());
  KnownSolutions known(start.roots.size(), options.real_tolerance);
  std::mutex known_mutex;
  std::atomic<int> next{0};
  std::atomic<bool> all_known{false};
  const auto follow = [&] {
    while (!all_known.load(std::memory_order_relaxed)) {
      const int k = next.fetch_add(1);
      if (k >= count) return;
      ends[k] = track_stewart_path(system, start.parameters, target, start.roots[k], options.tracking);
      if (!options.stop_when_all_known) continue;
      const std::lock_guard<std::mutex> lock(known_mutex);
      if (known.add(ends[k])) all_known.store(true, std::memory_order_relaxed);
    }
  };
  const int hardware = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  const int threads = std::clamp(options.threads > 0 ? options.threads : hardware, 1, count);
  std::vector<std::thread> helpers;
  helpers.reserve(threads - 1);
  for (int i = 1; i < threads; ++i) helpers.emplace_back(follow);
  follow();
  for (std::thread& helper : helpers) helper.join();
  ends.resize(std::min(next.load(), count));
  for (const TrackedPath& end : ends) steps += end.steps;
  return ends;
}

}  // namespace

StudyPoint study_point_of(const Pose& pose) {
  const Eigen::Quaterniond e(pose.rotation);
  const Eigen::Quaterniond p(0.0, pose.position_mm.x(), pose.position_mm.y(), pose.position_mm.z());
  const Eigen::Quaterniond g = p * e;
  StudyPoint x;
  x << e.w(), e.x(), e.y(), e.z(), 0.5 * g.w(), 0.5 * g.x(), 0.5 * g.y(), 0.5 * g.z();
  return x;
}

StewartStartSystem stewart_start_by_monodromy(std::uint64_t seed, int expected, int max_loops,
                                              int quiet_loops) {
  std::mt19937_64 rng(seed);
  StewartStartSystem start;
  for (int i = 0; i < 4; ++i) start.chart[i] = monodromy_random_complex(rng);
  const StewartSystem system(start.chart);
  // One random complex solution on the chart and the Study quadric, and the lengths that make it one.
  Eigen::Vector4cd e, g;
  for (int i = 0; i < 4; ++i) {
    e[i] = monodromy_random_complex(rng);
    g[i] = monodromy_random_complex(rng);
  }
  e /= (start.chart.array() * e.array()).sum();
  g -= ((e.array() * g.array()).sum() / (e.array() * e.array()).sum()) * e;
  StudyPoint x0;
  x0 << e, g;
  start.parameters = monodromy_random_parameters(rng);
  start.parameters.length_squared = system.lengths_through(start.parameters, x0);
  start.roots.push_back(x0);

  int quiet = 0;
  for (int loop = 0; loop < max_loops; ++loop) {
    const StewartParameters via_1 = monodromy_random_parameters(rng);
    const StewartParameters via_2 = monodromy_random_parameters(rng);
    const std::size_t before = start.roots.size();
    for (std::size_t r = 0; r < before; ++r) {
      StudyPoint x = start.roots[r];
      if (monodromy_loop(system, start.parameters, via_1, via_2, x) && !known_study_point(start.roots, x)) {
        start.roots.push_back(x);
      }
    }
    quiet = start.roots.size() == before ? quiet + 1 : 0;
    if (static_cast<int>(start.roots.size()) >= expected && quiet >= quiet_loops) break;
  }
  return start;
}

StewartAllModes stewart_all_modes(const std::array<Eigen::Vector3d, 6>& base_mm,
                                  const std::array<Eigen::Vector3d, 6>& platform_mm,
                                  const std::array<double, 6>& lengths_mm,
                                  const StewartAllModesOptions& options) {
  const StewartStartSystem& start = stewart_start_system();
  const StewartSystem system(start.chart);

  // Scale to the start instance's size: joints about their centroids, lengths by the largest of all.
  Eigen::Vector3d base_centre = Eigen::Vector3d::Zero(), platform_centre = Eigen::Vector3d::Zero();
  for (int j = 0; j < 6; ++j) {
    base_centre += base_mm[j] / 6.0;
    platform_centre += platform_mm[j] / 6.0;
  }
  double size_mm = 0.0;
  for (int j = 0; j < 6; ++j) {
    size_mm = std::max({size_mm, (base_mm[j] - base_centre).norm(), (platform_mm[j] - platform_centre).norm(),
                        lengths_mm[j]});
  }
  std::array<Eigen::Vector3cd, 6> base, platform;
  std::array<Complex, 6> length_squared;
  for (int j = 0; j < 6; ++j) {
    base[j] = ((base_mm[j] - base_centre) / size_mm).cast<Complex>();
    platform[j] = ((platform_mm[j] - platform_centre) / size_mm).cast<Complex>();
    const double l = lengths_mm[j] / size_mm;
    length_squared[j] = l * l;
  }
  const StewartParameters target = StewartParameters::from_joints(base, platform, length_squared);

  StewartAllModes result;
  std::vector<TrackedPath> ends = follow_start_paths(system, start, target, options, result.steps);
  const int not_followed = static_cast<int>(start.roots.size() - ends.size());
  result.finite += not_followed;
  result.complex += not_followed;
  result.skipped = not_followed;
  // Two regular paths cannot end at the same regular solution: one of them jumped. Follow both again with
  // small steps.
  PathTrackOptions careful = options.tracking;
  careful.initial_step = 0.005;
  careful.max_step = 0.01;
  for (std::size_t a = 0; a < ends.size(); ++a) {
    for (std::size_t b = a + 1; b < ends.size(); ++b) {
      const bool regular = ends[a].end == PathEnd::finite && ends[b].end == PathEnd::finite &&
                           ends[a].pivot_ratio > 1e-8 && ends[b].pivot_ratio > 1e-8;
      if (regular && same_study_point(ends[a].x, ends[b].x)) {
        for (std::size_t k : {a, b}) {
          ends[k] = track_stewart_path(system, start.parameters, target, start.roots[k], careful);
          result.steps += ends[k].steps;
          ++result.retracked;
        }
      }
    }
  }

  std::vector<StudyPoint> seen;
  for (const TrackedPath& end : ends) {
    if (end.end == PathEnd::at_infinity) {
      ++result.at_infinity;
      continue;
    }
    if (end.end == PathEnd::failed) {
      ++result.failed;
      continue;
    }
    ++result.finite;
    if (end.pivot_ratio < 1e-8) ++result.singular;
    const StudyPoint x = without_common_factor(end.x);
    const double imaginary = x.imag().norm() / x.norm();
    if (imaginary > options.real_tolerance) {
      ++result.complex;
      continue;
    }
    if (known_study_point(seen, x)) continue;
    seen.push_back(x);
    const Eigen::Matrix<double, 8, 1> real = x.real();
    const double norm = real.head<4>().norm();
    const Eigen::Quaterniond e(real[0] / norm, real[1] / norm, real[2] / norm, real[3] / norm);
    const Eigen::Quaterniond g(real[4] / norm, real[5] / norm, real[6] / norm, real[7] / norm);
    const Eigen::Vector3d position = 2.0 * (g * e.conjugate()).vec();
    StewartModeCandidate mode;
    mode.pose.rotation = e.toRotationMatrix();
    // Back to the caller's frames: p = size·p' + c_A − R·c_b.
    mode.pose.position_mm = size_mm * position + base_centre - mode.pose.rotation * platform_centre;
    mode.imaginary = imaginary;
    mode.pivot_ratio = end.pivot_ratio;
    result.real.push_back(mode);
  }
  return result;
}

}  // namespace pkm
