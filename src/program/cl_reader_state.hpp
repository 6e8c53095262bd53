#pragma once
// The APT CL data reader's state and its statement handlers (read_cl_data in part_program.hpp is the entry).
// One class, its handlers spread over files by concept:
//   cl_reader.cpp            dispatch, values, events, the output stage (transform, compensation)
//   cl_reader_motion.cpp     GOTO (also multi-point), FROM, GOHOME, RAPID, CIRCLE, DELAY
//   cl_reader_settings.cpp   FEDRAT, SPINDL, UNITS, TLAXIS, MULTAX, OPSKIP, END, comments and annotations
//   cl_reader_transform.cpp  MSYS, CSYS, TRNTYP, ROTABL: the frame the CL points are written in
//   cl_reader_cycle.cpp      CYCLE/… expanded into moves and dwells (the G-code canned cycles)
//   cl_reader_cutcom.cpp     CUTCOM/LEFT|RIGHT through the G-code interpreter's cutter compensation
//   cl_reader_nurbs.cpp      NX NURBS records evaluated into line moves within the tolerance
// Conventions that depend on the CAM system (arc direction above all) come from the dialect
// (program_format.hpp); see docs/cl-data.md.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/cl_arc.hpp"
#include "program/cl_lexer.hpp"
#include "program/part_program.hpp"
#include "program/program_format.hpp"

namespace pkm::program {

struct ClCycleState;   // cl_reader_cycle.cpp
struct ClCutcomState;  // cl_reader_cutcom.cpp
struct ClNurbsState;   // cl_reader_nurbs.cpp

/// 'WORD' compared case-blind with an upper-case word.
bool cl_equals_upper(std::string_view text, std::string_view upper_word);
/// Starts with a letter: a modifier word (MMPM, CLW), not a number.
bool cl_starts_like_word(std::string_view text);

class ClReader {
 public:
  ClReader(const std::string& source, const InterpretOptions& options, ProgramFormat dialect, int line_count);
  ~ClReader();
  ClReader(const ClReader&) = delete;
  ClReader& operator=(const ClReader&) = delete;

  bool ended() const { return ended_; }
  Status apply(const ClStatement& s);
  Result<CanonicalProgram> finish(int line_count);

  // --- values (cl_reader.cpp) ---
  Error error_at(ClPosition at, std::string_view message) const;
  Status number(const ClArg& arg, double& out) const;
  Status numbers(const ClStatement& s, std::size_t first, std::size_t count, double* out) const;
  /// Three numbers from args[first], normalised; zero length is an error.
  Status unit_vector(const ClStatement& s, std::size_t first, Eigen::Vector3d& out) const;
  Status no_values(const ClStatement& s) const;
  Status not_after_circle(const ClStatement& s) const;
  void record_event(const ClStatement& s);
  void add_note(std::string note);
  void note_arc_directions();

  // --- the output stage (cl_reader.cpp) ---
  /// A move at the current tool axis, in the CL frame (before transform and compensation).
  CanonicalMove move_to(const ClStatement& s, MoveKind kind, const Eigen::Vector3d& end_mm) const;
  Status set_feed(const ClStatement& s, CanonicalMove& move) const;
  /// Sends a move of the CL frame on: through cutter compensation when it is on, then the transform.
  Status emit(const CanonicalMove& move, ClPosition at);
  /// Emits whatever compensation still holds (before a dwell, a cycle, the end).
  Status flush_compensation(ClPosition at);

 private:
  // Motion (cl_reader_motion.cpp).
  Status go_to(const ClStatement& s);
  Status go_to_point(const ClStatement& s, const Eigen::Vector3d& end_mm);
  Status from(const ClStatement& s);
  Status gohome(const ClStatement& s);
  Status rapid(const ClStatement& s);
  Status circle(const ClStatement& s);
  Status delay(const ClStatement& s);
  void remember_direction(const CanonicalMove& move, const Eigen::Vector3d& start_mm);
  void check_arc_direction(const ClStatement& s, CanonicalMove& arc);
  /// GOTO/FROM values: one or more points (x,y,z or x,y,z,i,j,k), in mm of the CL frame.
  struct ClPoint {
    Eigen::Vector3d p_mm;
    std::optional<Eigen::Vector3d> axis;
  };
  Status points(const ClStatement& s, std::vector<ClPoint>& out) const;

  // Settings (cl_reader_settings.cpp).
  Status fedrat(const ClStatement& s);
  Status tlaxis(const ClStatement& s);
  Status units(const ClStatement& s);
  Status multax(const ClStatement& s);
  Status end(const ClStatement& s);
  Status spindl(const ClStatement& s);
  Status opskip(const ClStatement& s);
  Status cutter(const ClStatement& s);
  Status annotation(const ClStatement& s);

  // Frames (cl_reader_transform.cpp).
  Status msys(const ClStatement& s);
  Status csys(const ClStatement& s);
  Status trntyp(const ClStatement& s);
  Status rotabl(const ClStatement& s);
  void update_transform();  ///< transform_ from frame_ and table_rotation_

  // Cycles, compensation, NURBS (their own files).
  Status cycle(const ClStatement& s);
  Status cycle_point(const ClStatement& s, const ClPoint& point);
  bool cycle_active() const;
  Status cutcom(const ClStatement& s);
  bool cutcom_active() const;
  Status compensated(const CanonicalMove& move, ClPosition at, std::vector<CanonicalMove>& out);
  Status nurbs(const ClStatement& s);
  /// True while a NURBS record collects its knots and control points: the statement is part of it.
  bool nurbs_collecting() const;
  Status nurbs_continue(const ClStatement& s, bool& consumed);
  Status nurbs_finish(ClPosition at);

  void output(CanonicalMove move);

 public:
  // State the handlers share (public to the handler files only through this header).
  const std::string& source_;
  const bool block_delete_;
  const bool apply_transforms_;
  const ProgramFormat dialect_;
  CanonicalProgram program_;
  MoveOutput output_;
  double scale_ = 1.0;                                  ///< mm per program length unit (UNITS)
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();  ///< tool tip, CL frame, mm
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ();     ///< tool axis, CL frame
  std::optional<double> feed_;                          ///< mm/min, or mm/rev when feed_per_rev_
  bool feed_per_rev_ = false;
  double spindle_rpm_ = 0.0;
  bool spindle_rpm_known_ = false;
  bool spindle_clockwise_ = true;
  bool spindle_on_ = false;
  bool rapid_next_ = false;
  std::optional<ClCircle> circle_;
  ClPosition circle_at_;
  std::optional<bool> multax_;     ///< MULTAX/ON (true), OFF (false), not said
  double cutter_diameter_mm_ = 0;  ///< CUTTER/d, TLDATA/MILL,d (0: not known)
  /// CL frame → output frame (MSYS, CSYS, TRNTYP, ROTABL); identity when --no-transform.
  Eigen::Isometry3d transform_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Vector3d> home_mm_;                ///< FROM before any motion: where GOHOME goes
  Eigen::Vector3d initial_mm_ = Eigen::Vector3d::Zero();  ///< the start (CL frame) when there is no FROM
  /// ROTABL: the rotary table's turn so far (the CL points are written on the turned part).
  Eigen::Matrix3d table_rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Isometry3d frame_ = Eigen::Isometry3d::Identity();  ///< MSYS/CSYS, before the table's turn
  std::optional<Eigen::Vector3d> last_direction_;  ///< unit, CL frame: where the last cutting move went
  Eigen::Vector3d emitted_end_mm_ = Eigen::Vector3d::Zero();  ///< CL frame: where the last emitted move ends
  std::vector<int> reversed_arc_lines_;  ///< arcs that start against the move before them
  int longer_arcs_ = 0;                  ///< SolidWorks arcs taken the long way round (tangent continuity)
  bool skipping_ = false;
  bool ended_ = false;
  std::unique_ptr<ClCycleState> cycle_;
  std::unique_ptr<ClCutcomState> cutcom_;
  std::unique_ptr<ClNurbsState> nurbs_;
  std::vector<CanonicalMove> scratch_;  ///< compensation output, reused
};

}  // namespace pkm::program
