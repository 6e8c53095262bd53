#include "redundancy/block_subdivision.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pkm::redundancy {
namespace {

constexpr double kNotAdmissible = std::numeric_limits<double>::infinity();

// Into how many equal steps a part of this length is sampled.
int sub_steps(double part_mm, double step_mm) {
  return std::max(1, static_cast<int>(std::ceil(part_mm / step_mm * (1.0 - 1e-9))));
}

// Appends the sampled points of part i (from 1) of move m cut into n parts of s steps each: move m cut into
// n·s equal steps, so that the part's end is exactly the end of part i (i·s / (n·s) rounds as i / n).
void append_part(const ProgramCurves& curves, int m, int n, int i, int s, std::vector<PathPoint>& points) {
  for (int j = 1; j <= s; ++j) {
    const double f = static_cast<double>((i - 1) * s + j) / static_cast<double>(n * s);
    points.push_back(curves.point(m, f, points.back().position_mm));
  }
}

// The load at a part's start, held along the part (§3.6 step 3b); the direction of travel is the first
// step's.
statics::Wrench part_load(const statics::LoadModel& loads, const PathPoint& start, const PathPoint& first,
                          const Eigen::Vector3d& tool_axis_platform) {
  statics::LoadPoint point;
  point.tangent = first.tangent;
  point.tool_axis = start.axis_rotation * tool_axis_platform;
  point.line = first.line;
  point.cutting = first.cutting;
  return loads.wrench_at(point);
}

// One part of a cut block: its sampled points ([0] its start) and the load held along it.
struct Part {
  std::vector<PathPoint> points;
  statics::Wrench load;
};

// A block's criterion from its parts': summed for step laws, the largest for pointwise ones.
double combine(bool pointwise, double total, double part) {
  return pointwise ? std::max(total, part) : total + part;
}

// The criterion along a part with the free coordinates linear from `from_values` (node `start`, at the
// part's start) to `to_values`; `scratch` ends with the end node at index `end`.
double part_cost(const LawEvaluator& law, const Part& part, const Node& start, const FreeValues& from_values,
                 const FreeValues& to_values, bool check_branch, Node (&scratch)[2], int& end) {
  const bool pointwise = is_pointwise(law.options().law);
  const int steps = static_cast<int>(part.points.size()) - 1;
  const Node* from = &start;
  double total = 0.0;
  for (int j = 1; j <= steps; ++j) {
    const double w = static_cast<double>(j) / steps;
    Node& node = scratch[j % 2];
    const FreeValues at = j == steps ? to_values : FreeValues(from_values + w * (to_values - from_values));
    if (!law.evaluate(part.points[j], part.load, at, node, check_branch)) return kNotAdmissible;
    total = combine(pointwise, total, law.step_cost(*from, node));
    from = &node;
  }
  end = steps % 2;
  return total;
}

// The greedy step of §3.6 (3c): the values at a part's end for the part alone, from its start.
class PartObjective final : public StepObjective {
 public:
  PartObjective(const LawEvaluator& law, const Part& part, const Node& start, const FreeValues& start_values)
      : law_(law), part_(part), start_(start), start_values_(start_values) {}

  double cost(const FreeValues& values, bool check_branch) override {
    return part_cost(law_, part_, start_, start_values_, values, check_branch, nodes_, end_);
  }
  /// The node at the part's end of the last admissible evaluation.
  const Node& end_node() const { return nodes_[end_]; }

 private:
  const LawEvaluator& law_;
  const Part& part_;
  const Node& start_;
  FreeValues start_values_;
  Node nodes_[2];
  int end_ = 0;
};

// Where a block starts: its point, node and values.
struct BlockStart {
  PathPoint point;
  Node node;
  FreeValues values = FreeValues::Zero();
};

// One way of cutting a block: its parts, the values at their ends, the criterion, and the end node.
struct Partition {
  int parts = 0;
  std::vector<Part> cut;
  std::vector<FreeValues> values;
  double criterion = kNotAdmissible;
  Node end;
};

struct Context {
  const ProgramCurves& curves;
  const LawEvaluator& law;
  const statics::LoadModel& loads;
  double step_mm;
  Eigen::Vector3d tool_axis_platform;
  StepMinimiser& minimiser;
};

// Move m cut into n parts from `start`, each sampled at most the step apart.
std::vector<Part> cut_parts(const Context& c, int m, int n, const PathPoint& start) {
  const int s = sub_steps(c.curves.curves[m]->translation_mm / n, c.step_mm);
  std::vector<Part> parts(n);
  const PathPoint* from = &start;
  for (int i = 1; i <= n; ++i) {
    Part& part = parts[i - 1];
    part.points.assign(1, *from);
    append_part(c.curves, m, n, i, s, part.points);
    part.load = part_load(c.loads, part.points[0], part.points[1], c.tool_axis_platform);
    from = &part.points.back();
  }
  return parts;
}

// Move m cut into n parts from `start`: at every part's end the values the law chooses from its start
// (§3.6 3c); the block's criterion is the parts' combined (3d).
Partition cut_block(const Context& c, int m, int n, const BlockStart& start) {
  Partition out;
  out.parts = n;
  out.cut = cut_parts(c, m, n, start.point);
  const bool pointwise = is_pointwise(c.law.options().law);
  Node from = start.node;
  FreeValues values = start.values;
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    PartObjective objective(c.law, out.cut[i], from, values);
    values = c.minimiser.minimise(objective, values);
    const double cost = objective.cost(values, true);
    if (!std::isfinite(cost)) return out;
    total = combine(pointwise, total, cost);
    out.values.push_back(values);
    // The next part's start node carries that part's load.
    if (i + 1 == n) {
      out.end = objective.end_node();
    } else if (!c.law.evaluate(out.cut[i + 1].points[0], out.cut[i + 1].load, values, from, true)) {
      return out;
    }
  }
  out.criterion = total;
  return out;
}

// §3.6 step 3: N from the fewest parts up, while a finer cut still pays (3g); the best cut found.
Result<Partition> best_partition(const Context& c, int m, const BlockStart& start,
                                 const SubdivisionSettings& settings) {
  const double length_mm = c.curves.curves[m]->translation_mm;
  const int first = c.curves.fewest_parts(m);
  Partition best = cut_block(c, m, first, start);
  // The criterion the finer cuts must beat by the improvement share, and how many in a row have not.
  double reference = best.criterion;
  int misses = 0;
  for (int n = first + 1; n <= settings.max_parts && length_mm / n >= settings.min_part_mm; ++n) {
    Partition finer = cut_block(c, m, n, start);
    const double criterion = finer.criterion;
    if (criterion < best.criterion) best = std::move(finer);
    // An inadmissible cut (no values for some part) says nothing of the next: go on until one is admissible.
    if (!std::isfinite(reference)) {
      reference = criterion;
      continue;
    }
    if (reference - criterion > settings.improvement * std::abs(reference)) {
      reference = criterion;
      misses = 0;
    } else if (++misses >= settings.patience) {
      break;
    }
  }
  if (!std::isfinite(best.criterion)) {
    const PathPoint& end = c.curves.point(m, 1.0, start.point.position_mm);
    return make_error(
        ErrorCode::unreachable,
        fmt::format(
            "{}:{}: no admissible {} within the bounds along the block to ({:.3f}, {:.3f}, {:.3f}) mm "
            "for any cut into {} to {} parts: every candidate is out of reach, over a limit or "
            "across a singular position",
            c.curves.program->source, end.line, c.law.free().name(0), end.position_mm.x(),
            end.position_mm.y(), end.position_mm.z(), first, std::max(first, best.parts)));
  }
  return best;
}

// The start values: held, or for a pointwise law chosen like any other point (the leading rapid goes there).
Result<BlockStart> program_start(const Context& c) {
  BlockStart start;
  start.point = c.curves.start.points[0];
  start.values = c.law.free().start();
  const statics::Wrench load = part_load(c.loads, start.point, start.point, c.tool_axis_platform);
  if (is_pointwise(c.law.options().law)) {
    const Part alone{{start.point, start.point}, load};
    Node unused;
    c.law.evaluate(start.point, load, start.values, unused, false);
    PartObjective objective(c.law, alone, unused, start.values);
    start.values = c.minimiser.minimise(objective, start.values);
  }
  if (!c.law.evaluate(start.point, load, start.values, start.node, false)) {
    return make_error(ErrorCode::unreachable,
                      fmt::format("{}:{}: the start pose is out of reach or over a limit",
                                  c.curves.program->source, start.point.line));
  }
  return start;
}

}  // namespace

Result<SubdividedProgram> subdivide_blocks(const ProgramCurves& curves, const LawEvaluator& law,
                                           const statics::LoadModel& loads, double step_mm,
                                           const SubdivisionSettings& settings,
                                           const GreedySettings& greedy) {
  StepMinimiser minimiser(law.free(), greedy);
  const Eigen::Vector3d tool_axis_platform =
      curves.start.frame.reference_rotation.conjugate() * Eigen::Vector3d::UnitZ();
  const Context context{curves, law, loads, step_mm, tool_axis_platform, minimiser};
  auto start = program_start(context);
  if (!start) return start.error();
  SubdividedProgram out;
  out.nodes = curves.start;
  out.node_values.push_back(start->values);
  BlockStart block = std::move(*start);
  for (int m = curves.start.first_move; m < static_cast<int>(curves.curves.size()); ++m) {
    if (!curves.curves[m]) continue;
    auto best = best_partition(context, m, block, settings);
    if (!best) return best.error();
    out.nodes.parts[m] = best->parts;
    out.largest_parts = std::max(out.largest_parts, best->parts);
    for (const Part& part : best->cut) out.nodes.points.push_back(part.points.back());
    out.node_values.insert(out.node_values.end(), best->values.begin(), best->values.end());
    block.point = best->cut.back().points.back();
    block.node = best->end;
    block.values = best->values.back();
  }
  sample_between_nodes(curves, out.nodes, out.node_values, step_mm, out.motion, out.motion_values);
  return out;
}

void sample_between_nodes(const ProgramCurves& curves, const ProgramPoints& nodes,
                          const std::vector<FreeValues>& node_values, double step_mm, ProgramPoints& motion,
                          std::vector<FreeValues>& motion_values) {
  motion = curves.start;
  motion_values.assign(1, node_values[0]);
  std::size_t k = 1;
  for (int m = nodes.first_move; m < static_cast<int>(nodes.parts.size()); ++m) {
    const int n = nodes.parts[m];
    if (n == 0) continue;
    const int s = sub_steps(curves.curves[m]->translation_mm / n, step_mm);
    for (int i = 1; i <= n; ++i, ++k) {
      append_part(curves, m, n, i, s, motion.points);
      for (int j = 1; j <= s; ++j) {
        const double w = static_cast<double>(j) / s;
        motion_values.push_back(j == s ? node_values[k]
                                       : node_values[k - 1] + w * (node_values[k] - node_values[k - 1]));
      }
    }
    motion.parts[m] = n * s;
  }
}

}  // namespace pkm::redundancy
