// pkm compliance --bode FILE: the tool's dynamic compliance over a log-spaced frequency range
// (src/stiffness/compliance_bode.hpp, docs/dynamic_compliance.md), with the natural frequencies and the
// damping assumed (pipeline/compliance_job.hpp computes and writes them; here the flags are read and the
// results printed).
#include <fmt/format.h>

#include <iostream>

#include "compliance_cli.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {
namespace {

Error compliance_bode_flag_error(const std::string& flag, const Error& error) {
  Error e = error;
  e.message = flag + ": " + e.message;
  return e;
}

Result<stiffness::DampingAssumption> compliance_damping(const ComplianceBodeArguments& arguments) {
  stiffness::DampingAssumption damping;
  damping.modal_ratio = arguments.damping_ratio;
  if (arguments.rayleigh_text.empty()) return damping;
  auto values = parse_number_list(arguments.rayleigh_text, "--rayleigh");
  if (!values) return values.error();
  if (values->size() != 2) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--rayleigh: give α,β (1/s, s), got {} numbers", values->size()));
  }
  damping.model = stiffness::DampingModel::rayleigh;
  damping.rayleigh_mass_per_s = (*values)[0];
  damping.rayleigh_stiffness_s = (*values)[1];
  if (Status s = stiffness::check_damping(damping); !s)
    return compliance_bode_flag_error("--rayleigh", s.error());
  return damping;
}

/// The largest magnitude of an entry over the sweep and where it is.
std::pair<double, double> compliance_bode_peak(const stiffness::BodeData& data, std::size_t entry) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < data.frequency_Hz.size(); ++k)
    if (data.magnitude_um_N[entry][k] > data.magnitude_um_N[entry][best]) best = k;
  return {data.frequency_Hz[best], data.magnitude_um_N[entry][best]};
}

std::vector<double> compliance_bode_vector(const dynamics::CoordinateVector& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

Result<stiffness::BodeRequest> compliance_bode_request(const ComplianceBodeArguments& arguments) {
  if (!(arguments.f_max_Hz > arguments.f_min_Hz)) {
    return make_error(ErrorCode::bad_input, fmt::format("--f-max-hz {:g} must be above --f-min-hz {:g}",
                                                        arguments.f_max_Hz, arguments.f_min_Hz));
  }
  auto damping = compliance_damping(arguments);
  if (!damping) return damping.error();
  stiffness::BodeRequest request;
  request.f_min_Hz = arguments.f_min_Hz;
  request.f_max_Hz = arguments.f_max_Hz;
  request.points = arguments.points;
  request.options.damping = *damping;
  return request;
}

nlohmann::json compliance_bode_json(const stiffness::BodeData& data,
                                    const ComplianceBodeArguments& arguments) {
  nlohmann::json entries = nlohmann::json::array();
  for (std::size_t e = 0; e < data.entries.size(); ++e) {
    const auto [f, peak] = compliance_bode_peak(data, e);
    const Eigen::Vector3d& d = data.entries[e].displacement_direction;
    entries.push_back({{"name", data.entries[e].name},
                       {"direction", {d.x(), d.y(), d.z()}},
                       {"lowest_frequency_magnitude_um_N", data.magnitude_um_N[e].front()},
                       {"peak_frequency_Hz", f},
                       {"peak_magnitude_um_N", peak}});
  }
  return {{"file", arguments.path},
          {"f_min_Hz", arguments.f_min_Hz},
          {"f_max_Hz", arguments.f_max_Hz},
          {"points", arguments.points},
          {"damping", stiffness::describe(data.damping)},
          {"damping_model", data.damping.model == stiffness::DampingModel::modal ? "modal" : "rayleigh"},
          {"damping_ratio_per_mode", compliance_bode_vector(data.damping_ratio)},
          {"natural_frequencies_Hz", compliance_bode_vector(data.natural_frequency_Hz)},
          {"entries", entries},
          {"columns", "frequency_Hz, then <entry>_magnitude_um_N and <entry>_phase_deg per entry"}};
}

void print_compliance_bode(const stiffness::BodeData& data, const ComplianceBodeArguments& arguments) {
  std::cout << fmt::format(
      "  dynamic compliance (the dynamics: section's masses and springs, drives clamped; "
      "{}):\n",
      stiffness::describe(data.damping));
  std::cout << "    natural frequencies (Hz):";
  for (int i = 0; i < data.natural_frequency_Hz.size(); ++i)
    std::cout << fmt::format(" {:.3f}", data.natural_frequency_Hz[i]);
  std::cout << '\n';
  for (std::size_t e = 0; e < data.entries.size(); ++e) {
    const auto [f, peak] = compliance_bode_peak(data, e);
    std::cout << fmt::format("    {:<10} {:10.5f} µm/N at {:g} Hz, peak {:10.5f} µm/N at {:.3f} Hz\n",
                             data.entries[e].name, data.magnitude_um_N[e].front(), data.frequency_Hz.front(),
                             peak, f);
  }
  std::cout << fmt::format("    Bode data ({} frequencies, {:g}…{:g} Hz): {}\n", data.frequency_Hz.size(),
                           arguments.f_min_Hz, arguments.f_max_Hz, arguments.path);
}

}  // namespace pkm::cli
