#pragma once
// The RS274/NGC block executor: gives each block the BlockReader yields its meaning, in LinuxCNC's order of
// execution within a block (feed mode, F, S, T, I/O, M6/M61, spindle, state, coolant, overrides, user
// M-codes, dwell, plane, units, cutter radius compensation, tool length, coordinate system, path control,
// distance modes, retract mode, G10/G28/G30/G92, motion, stop), and turns it into canonical moves and
// events. Moves go through cutter radius compensation in program coordinates, then into the work frame.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/gcode_block.hpp"
#include "program/ngc_canned_cycle.hpp"
#include "program/ngc_cutter_compensation.hpp"
#include "program/ngc_evaluated_block.hpp"
#include "program/ngc_machine_state.hpp"
#include "program/ngc_parameter_store.hpp"
#include "program/part_program.hpp"
#include "program/tool_table.hpp"

namespace pkm::program::ngc {

class Executor final : public PredefinedParameters, private CycleSink {
 public:
  Executor(const std::string& source, const InterpretOptions& options, std::optional<ToolTable> tools);
  Status run(std::string_view text, CanonicalProgram& program);
  std::optional<double> predefined(std::string_view name) const override;

 private:
  // CycleSink: what a canned cycle does becomes moves and events here.
  void rapid(const Eigen::Vector3d& to_mm) override;
  void feed(const Eigen::Vector3d& to_mm) override;
  void dwell(double seconds) override;
  void event(const std::string& what) override;

  gcode::LineRef where() const { return {*file_name_, line_}; }
  Status execute(const gcode::Block& b);
  Status check_words(const gcode::Block& b, int motion, bool moves) const;
  Status check_letter_users(const gcode::Block& b, int motion, bool moves) const;
  Status read_feed_and_speed(const gcode::Block& b);
  Status tools_and_spindle(const gcode::Block& b);
  void machine_functions(const gcode::Block& b);
  void save_or_restore_state(const gcode::Block& b);
  Status set_plane_and_compensation(const gcode::Block& b);
  Status set_tool_length(const gcode::Block& b);
  Status set_coordinate_system(const gcode::Block& b);
  Status set_path_control(const gcode::Block& b);
  Status non_modal(const gcode::Block& b);
  Status set_g10(const gcode::Block& b);
  Status set_g10_tool(const gcode::Block& b, int l);
  Status set_g10_offsets(const gcode::Block& b, int l);
  Status set_axis_offsets(const gcode::Block& b, int code);
  Status return_home(const gcode::Block& b, int code);
  void store_home(int code);
  Status motion(const gcode::Block& b, int motion);
  Status straight(const gcode::Block& b, int motion);
  Status arc(const gcode::Block& b, int motion, CanonicalMove& m) const;
  Status cycle(const gcode::Block& b, int motion);
  Status feed_for(const gcode::Block& b, int motion, CanonicalMove& m) const;
  Status stop(const gcode::Block& b);

  Status target_of(const gcode::Block& b, Eigen::Vector3d& end_mm, Eigen::Vector3d& abc_deg) const;
  Status polar_target(const gcode::Block& b, Eigen::Vector3d& end_mm) const;
  Eigen::Vector3d machine_target_of(const gcode::Block& b, Eigen::Vector3d& abc_deg) const;
  Eigen::Vector3d machine_mm(const Eigen::Vector3d& program_mm) const;
  Eigen::Vector3d program_from_machine_mm(const Eigen::Vector3d& machine_mm) const;
  CanonicalMove new_move(MoveKind kind) const;
  Status emit(const CanonicalMove& m);
  Status flush_compensation();
  Status append_compensated();
  void add_event(std::string what);
  void refresh_frame();
  void reframe();
  void write_position_parameters();
  double tool_diameter_of(int tool) const;

  const std::string& source_;
  const InterpretOptions& options_;
  std::optional<ToolTable> tools_;
  CanonicalProgram* program_ = nullptr;
  MoveOutput output_;
  MachineState state_;
  std::optional<MachineState> saved_state_;  ///< M70
  ParameterStore parameters_;
  CutterCompensation compensation_;
  CycleMemory cycle_memory_;
  std::uint64_t cycle_moves_ = 0;           ///< moves the canned cycles made so far (bounded by max_blocks)
  std::vector<CanonicalMove> compensated_;  ///< scratch: what compensation emits for one move
  const std::string* file_name_ = &source_;
  int line_ = 0;
  int motion_column_ = 1;  ///< of the block being executed, for errors about its moves
  SourceRef source_ref_;
  bool ended_ = false;
  bool no_table_noted_ = false;
  Status cycle_status_ = ok_status();  ///< the first failure while a cycle emits its moves
};

}  // namespace pkm::program::ngc
