#include "pipeline/strategy_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>

#include "report/csv_table.hpp"
#include "report/report_html.hpp"

namespace pkm::pipeline {
namespace {

constexpr double kStrategyUmPerMm = 1000.0;
// Two rms values this close are one value written twice (different sums of the same squares).
constexpr double kRmsTieMm = 1e-12;

// Blue (negative: towards the work) – white – red (positive: away from the work), t in [−1, 1].
std::string strategy_error_colour(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, -1.0, 1.0);
  const double r0 = t < 0 ? 33 : 178, g0 = t < 0 ? 102 : 24, b0 = t < 0 ? 172 : 43;
  const double w = std::abs(t);
  auto mix = [w](double c) { return static_cast<int>(std::lround(255.0 + (c - 255.0) * w)); };
  return fmt::format("#{:02x}{:02x}{:02x}", mix(r0), mix(g0), mix(b0));
}

// One panel: the map's points from above, scaled to fit the box with x and y at the same scale.
void svg_map_panel(std::string& out, const StrategyScore& score, const std::vector<ErrorMapPoint>& map,
                   double left, double top, double width, double height, double scale_mm) {
  auto add = std::back_inserter(out);
  fmt::format_to(add, "<rect x='{}' y='{}' width='{}' height='{}' fill='none' stroke='#999'/>\n", left, top,
                 width, height);
  fmt::format_to(add, "<text x='{}' y='{}' font-size='13' font-weight='bold'>{}. {}</text>\n", left + 6,
                 top + 16, score.rank, report::html_escape(score.name));
  fmt::format_to(add, "<text x='{}' y='{}' font-size='11'>rms {:.4f} µm, max {:.4f} µm</text>\n", left + 6,
                 top + 30, score.rms_normal_mm * kStrategyUmPerMm, score.max_normal_mm * kStrategyUmPerMm);
  if (map.empty()) return;
  double x0 = map.front().x_mm, x1 = x0, y0 = map.front().y_mm, y1 = y0;
  for (const ErrorMapPoint& p : map) {
    x0 = std::min(x0, p.x_mm), x1 = std::max(x1, p.x_mm);
    y0 = std::min(y0, p.y_mm), y1 = std::max(y1, p.y_mm);
  }
  const double box_top = top + 38, box_width = width - 16, box_height = height - 46;
  const double span = std::max({x1 - x0, (y1 - y0) * box_width / box_height, 1e-9});
  const double mm = box_width / span;
  const double cx = left + 8 + box_width / 2, cy = box_top + box_height / 2;
  for (const ErrorMapPoint& p : map) {
    fmt::format_to(add, "<circle cx='{:.1f}' cy='{:.1f}' r='1.6' fill='{}'/>\n",
                   cx + (p.x_mm - (x0 + x1) / 2) * mm, cy - (p.y_mm - (y0 + y1) / 2) * mm,
                   strategy_error_colour(p.normal_mm / scale_mm));
  }
}

void svg_legend(std::string& out, double left, double top, double scale_mm) {
  auto add = std::back_inserter(out);
  constexpr int kSteps = 21;
  for (int i = 0; i < kSteps; ++i) {
    const double t = -1.0 + 2.0 * i / (kSteps - 1);
    fmt::format_to(add, "<rect x='{}' y='{}' width='12' height='10' fill='{}' stroke='none'/>\n",
                   left + 12 * i, top, strategy_error_colour(t));
  }
  fmt::format_to(
      add,
      "<text x='{}' y='{}' font-size='11'>normal error (along the tool axis; + away from the work): "
      "−{:.4f} … +{:.4f} µm</text>\n",
      left + 12 * kSteps + 8, top + 9, scale_mm * kStrategyUmPerMm, scale_mm * kStrategyUmPerMm);
}

void svg_bar_chart(std::string& out, const std::vector<StrategyScore>& scores, double left, double top,
                   double width, double height) {
  auto add = std::back_inserter(out);
  double largest = 0.0;
  for (const StrategyScore& s : scores) largest = std::max({largest, s.max_normal_mm, s.rms_normal_mm});
  if (largest <= 0.0) largest = 1.0;  // no load: empty bars on a unit axis
  const double label_width = 120, plot_width = width - label_width - 140;  // room for "1.2345 (line 12345)"
  const double row = height / static_cast<double>(std::max<std::size_t>(1, scores.size()));
  fmt::format_to(add,
                 "<text x='{}' y='{}' font-size='13' font-weight='bold'>normal error per strategy, µm "
                 "(dark: rms, light: max with its line), best first</text>\n<text x='{}' y='{}' "
                 "font-size='11'>ranked by the {}</text>\n",
                 left, top - 22, left, top - 8, report::html_escape(kStrategyCriterion));
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const StrategyScore& s = scores[i];
    const double y = top + row * static_cast<double>(i);
    const double bar = std::max(4.0, row / 2 - 3);
    fmt::format_to(add, "<text x='{}' y='{}' font-size='12'>{}. {}</text>\n", left, y + bar + 2, s.rank,
                   report::html_escape(s.name));
    const double x = left + label_width;
    const double rms_width = plot_width * s.rms_normal_mm / largest,
                 max_width = plot_width * s.max_normal_mm / largest;
    fmt::format_to(add, "<rect x='{}' y='{:.1f}' width='{:.1f}' height='{:.1f}' fill='#3b6ea5'/>\n", x, y,
                   rms_width, bar);
    fmt::format_to(add, "<text x='{:.1f}' y='{:.1f}' font-size='11'>{:.4f}</text>\n", x + rms_width + 4,
                   y + bar - 2, s.rms_normal_mm * kStrategyUmPerMm);
    fmt::format_to(add, "<rect x='{}' y='{:.1f}' width='{:.1f}' height='{:.1f}' fill='#a9c4e2'/>\n", x,
                   y + bar + 2, max_width, bar);
    fmt::format_to(add, "<text x='{:.1f}' y='{:.1f}' font-size='11'>{:.4f} (line {})</text>\n",
                   x + max_width + 4, y + 2 * bar, s.max_normal_mm * kStrategyUmPerMm, s.max_normal_line);
  }
}

}  // namespace

void FedSegments::add(int line, double s_start, double s_end) {
  ranges_[line].emplace_back(s_start, s_end);
}

bool FedSegments::contains(int line, double s) const {
  constexpr double kWrittenSMm = 6e-7;  // s is written with six decimals
  const auto it = ranges_.find(line);
  if (it == ranges_.end()) return false;
  for (const auto& [from, to] : it->second)
    if (s >= from - kWrittenSMm && s <= to + kWrittenSMm) return true;
  return false;
}

void rank_strategies(std::vector<StrategyScore>& scores) {
  std::stable_sort(scores.begin(), scores.end(), [](const StrategyScore& a, const StrategyScore& b) {
    if (std::abs(a.rms_normal_mm - b.rms_normal_mm) > kRmsTieMm) return a.rms_normal_mm < b.rms_normal_mm;
    return a.max_normal_mm < b.max_normal_mm;
  });
  for (std::size_t i = 0; i < scores.size(); ++i) scores[i].rank = static_cast<int>(i) + 1;
}

std::string strategies_csv(const std::vector<StrategyScore>& scores) {
  std::string out = "strategy,points,path_length_mm,time_s,max_normal_um,max_line,rms_normal_um,rank\n";
  for (const StrategyScore& s : scores) {
    fmt::format_to(std::back_inserter(out), "{},{},{:.3f},{:.3f},{:.6f},{},{:.6f},{}\n", s.name, s.points,
                   s.path_length_mm, s.cutting_time_s, s.max_normal_mm * kStrategyUmPerMm, s.max_normal_line,
                   s.rms_normal_mm * kStrategyUmPerMm, s.rank);
  }
  return out;
}

Result<SurfaceErrorMap> surface_error_map(const std::string& run_directory, const FedSegments& fed,
                                          std::size_t max_sample) {
  const std::filesystem::path dir(run_directory);
  report::CsvReader path_csv, deflection_csv;
  if (Status opened = path_csv.open((dir / "path.csv").string()); !opened) return opened.error();
  if (Status opened = deflection_csv.open((dir / "deflection.csv").string()); !opened) return opened.error();
  int column[7];
  const std::pair<report::CsvReader*, std::string_view> wanted[7] = {{&path_csv, "line"},
                                                                     {&path_csv, "x_program_mm"},
                                                                     {&path_csv, "y_program_mm"},
                                                                     {&path_csv, "z_program_mm"},
                                                                     {&path_csv, "s"},
                                                                     {&deflection_csv, "line"},
                                                                     {&deflection_csv, "normal_mm"}};
  for (int k = 0; k < 7; ++k) {
    auto index = wanted[k].first->require(wanted[k].second);
    if (!index) return index.error();
    column[k] = *index;
  }
  const auto rows = report::count_csv_rows(path_csv.path());
  if (!rows) return rows.error();
  // Every k-th cutting tick for the plot; the cutting share is not known yet, so k is from all ticks.
  const long every = std::max<long>(
      1, static_cast<long>(std::ceil(static_cast<double>(*rows) / std::max<std::size_t>(1, max_sample))));
  SurfaceErrorMap map;
  map.csv = "time_s,line,x_mm,y_mm,z_mm,normal_um\n";
  std::vector<double> p, d;
  long tick = 0;
  while (true) {
    auto more = report::next_in_step(path_csv, p, deflection_csv, d);
    if (!more) return more.error();
    if (!*more) break;
    const int line = static_cast<int>(p[column[0]]);
    if (line != static_cast<int>(d[column[5]]) || p[0] != d[0]) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}:{}: not the tick of {} line {}", deflection_csv.path(),
                                    deflection_csv.line(), path_csv.path(), path_csv.line()));
    }
    ++tick;
    if (!fed.contains(line, p[column[4]])) continue;
    const ErrorMapPoint point{p[column[1]], p[column[2]], p[column[3]], d[column[6]]};
    fmt::format_to(std::back_inserter(map.csv), "{:.6f},{},{:.6f},{:.6f},{:.6f},{:.5e}\n", p[0], line,
                   point.x_mm, point.y_mm, point.z_mm, point.normal_mm * kStrategyUmPerMm);
    ++map.rows;
    if (tick % every == 0 && map.sample.size() < max_sample) map.sample.push_back(point);
  }
  return map;
}

std::string strategies_svg(const std::vector<StrategyScore>& scores,
                           const std::vector<std::vector<ErrorMapPoint>>& maps) {
  constexpr double kPanelWidth = 300, kPanelHeight = 250, kMargin = 12;
  constexpr int kColumns = 3;
  const int panels = static_cast<int>(scores.size());
  const int panel_rows = (panels + kColumns - 1) / kColumns;
  const double width = kMargin * 2 + kColumns * kPanelWidth + (kColumns - 1) * kMargin;
  const double legend_top = kMargin + 24 + panel_rows * (kPanelHeight + kMargin);
  const double chart_top = legend_top + 50, chart_height = 34.0 * std::max(1, panels);
  const double height = chart_top + chart_height + kMargin;
  double scale_mm = 0.0;
  for (const auto& map : maps)
    for (const ErrorMapPoint& p : map) scale_mm = std::max(scale_mm, std::abs(p.normal_mm));
  for (const StrategyScore& s : scores) scale_mm = std::max(scale_mm, s.max_normal_mm);
  if (scale_mm <= 0.0) scale_mm = 1e-3;

  std::string out;
  auto add = std::back_inserter(out);
  fmt::format_to(add,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='{0}' height='{1}' viewBox='0 0 {0} {1}' "
                 "font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n",
                 width, height);
  fmt::format_to(
      add,
      "<text x='{}' y='{}' font-size='15' font-weight='bold'>Machining strategies: the surface error "
      "from the tool's deflection under the cutting load (seen from above)</text>\n",
      kMargin, kMargin + 12);
  for (int i = 0; i < panels; ++i) {
    const double left = kMargin + (i % kColumns) * (kPanelWidth + kMargin);
    const double top = kMargin + 24 + (i / kColumns) * (kPanelHeight + kMargin);
    static const std::vector<ErrorMapPoint> kNoPoints;
    svg_map_panel(out, scores[i], i < static_cast<int>(maps.size()) ? maps[i] : kNoPoints, left, top,
                  kPanelWidth, kPanelHeight, scale_mm);
  }
  svg_legend(out, kMargin, legend_top, scale_mm);
  svg_bar_chart(out, scores, kMargin, chart_top, width - 2 * kMargin, chart_height);
  out += "</svg>\n";
  return out;
}

}  // namespace pkm::pipeline
