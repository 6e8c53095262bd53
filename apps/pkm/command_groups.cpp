#include "command_groups.hpp"

#include <array>
#include <iostream>
#include <string>
#include <string_view>

#include "io/printable_text.hpp"

namespace pkm::cli {

namespace {

struct CommandGroup {
  const char* name;
  std::array<const char*, 10> commands;  // nullptr-terminated when shorter
  const char* example;
};

constexpr std::array<CommandGroup, 5> kCommandGroups{{
    {"Plan and run",
     {"plan", "interpret", "interpolate", "play", "servo", "simulate", "optimize", "report", nullptr},
     "pkm plan part.ngc --machine m.yaml --out run/ --report run/report.html"},
    {"Analyse",
     {"stiffness", "compliance", "modes", "modes-margin", "workspace", "strategies", "jacobian", "circle",
      "spif", nullptr},
     "pkm stiffness part.cl --machine m.yaml --load tangential=600 --out stiffness/"},
    {"Machine",
     {"check", "ik", "fk", "demo", "linuxcnc", nullptr},
     "pkm check m.yaml; pkm ik --machine m.yaml --pose -50,0,700,0,0,0"},
    {"Calibration",
     {"calibrate", nullptr},
     "pkm calibrate identify --machine m.yaml --measurements tracker.csv --out calibrated.yaml"},
    {"Tools", {"bench", nullptr}, "pkm bench kinematics --machine m.yaml"},
}};

const char* group_of(std::string_view command) {
  for (const CommandGroup& group : kCommandGroups)
    for (const char* name : group.commands)
      if (name != nullptr && command == name) return group.name;
  return "Tools";
}

std::string command_list(CLI::App& app) {
  std::string list;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    list += (list.empty() ? "" : ", ") + sub->get_name();
  return list;
}

}  // namespace

void group_commands(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    sub->group(group_of(sub->get_name()));
  std::string footer = "Examples:";
  for (const CommandGroup& group : kCommandGroups)
    footer += "\n  " + std::string(group.name) + ":\n    " + group.example;
  footer += "\n\npkm COMMAND --help describes a command; docs/cli.md all of them.\n";
  app.footer(footer);
}

std::optional<int> refuse_unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return std::nullopt;
  const std::string first = argv[1];
  if (first.empty() || first.front() == '-') return std::nullopt;
  if (!app.get_subcommands([&](CLI::App* sub) { return sub->check_name(first); }).empty())
    return std::nullopt;
  std::cerr << "pkm: error: unknown command '" << printable_text(first) << "'; the commands are "
            << command_list(app) << "\nRun with --help for more information.\n";
  return 2;
}

}  // namespace pkm::cli
