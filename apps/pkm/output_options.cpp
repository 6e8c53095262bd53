#include "output_options.hpp"

#include <array>
#include <string>
#include <string_view>

#include "io/output_context.hpp"

namespace pkm::cli {

namespace {

// The commands whose --out is a folder holding one output set.
constexpr std::array<std::string_view, 11> kFolderWriters{"plan",
                                                          "interpolate",
                                                          "stiffness",
                                                          "servo",
                                                          "simulate",
                                                          "workspace",
                                                          "strategies",
                                                          "calibrate plan",
                                                          "calibrate simulate",
                                                          "calibrate identify",
                                                          "linuxcnc config"};

void add_force_flags(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    add_force_flags(*sub);
    for (const std::string_view writer : kFolderWriters) {
      if (full_command_name(*sub) == writer)
        sub->add_flag("--force")->description(
            "replace the output set of another command in the --out folder, whole");
    }
  }
}

std::string first_result(const CLI::App& sub, const std::string& option) {
  const CLI::Option* found = sub.get_option_no_throw(option);
  if (found == nullptr || found->count() == 0) return {};
  return found->results().front();
}

void set_context_from(const CLI::App& app) {
  const CLI::App* leaf = &app;
  while (!leaf->get_subcommands().empty()) leaf = leaf->get_subcommands().front();
  OutputContext context;
  context.command = full_command_name(*leaf);
  const CLI::Option* force = leaf->get_option_no_throw("--force");
  context.force = force != nullptr && force->count() > 0;
  if (std::string machine = first_result(*leaf, "--machine"); !machine.empty())
    context.inputs.emplace_back("machine", machine);
  if (std::string program = first_result(*leaf, "program"); !program.empty())
    context.inputs.emplace_back("program", program);
  set_output_context(std::move(context));
}

}  // namespace

std::string full_command_name(const CLI::App& sub) {
  std::string name = sub.get_name();
  for (const CLI::App* parent = sub.get_parent(); parent != nullptr && parent->get_parent() != nullptr;
       parent = parent->get_parent())
    name = parent->get_name() + " " + name;
  return name;
}

void add_output_options(CLI::App& app) {
  add_force_flags(app);
  app.parse_complete_callback([&app] { set_context_from(app); });
}

}  // namespace pkm::cli
