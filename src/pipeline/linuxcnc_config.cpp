#include "pipeline/linuxcnc_config.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/units.hpp"
#include "io/input_file.hpp"
#include "io/output_set.hpp"
#include "pipeline/linuxcnc_hal_files.hpp"
#include "pipeline/linuxcnc_launch.hpp"

namespace pkm {

std::string_view to_string(LinuxcncKinematics kinematics) {
  switch (kinematics) {
    case LinuxcncKinematics::genhexkins:
      return "genhexkins";
    case LinuxcncKinematics::trivkins:
      return "trivkins";
    case LinuxcncKinematics::pkmkins:
      break;
  }
  return "pkmkins";
}

namespace {

constexpr const char* kAxisLetters = "XYZABC";

struct JointSettings {
  double min = 0.0, max = 0.0, speed = 0.0, accel = 0.0;  // LinuxCNC units: mm or deg
};

Error limits_error(const Machine& machine, std::string_view key) {
  Error e =
      make_error(ErrorCode::bad_input,
                 fmt::format("{}: limits.{} is needed for LinuxCNC's joints (limits, speed, acceleration)",
                             machine.source, key));
  e.location.file = machine.source;
  e.location.key = fmt::format("limits.{}", key);
  return e;
}

// Carriages on a circle (the rotopod) turn endlessly: without a range in the machine file their joints get
// one of a thousand turns each way, which LinuxCNC's joint checks never reach.
constexpr double kEndlessJointRangeDeg = 360000.0;

Result<JointSettings> joint_settings(const Machine& machine) {
  const ActuatorLimits& l = machine.limits;
  const bool angles = machine.mechanism->actuators_are_angles();
  if (!l.min && !angles) return limits_error(machine, "actuator_min");
  if (!l.max && !angles) return limits_error(machine, "actuator_max");
  if (!l.speed) return limits_error(machine, "actuator_speed");
  if (!l.accel) return limits_error(machine, "actuator_accel");
  const double unit = angles ? deg_from_rad(1.0) : 1.0;
  return JointSettings{l.min ? *l.min * unit : -kEndlessJointRangeDeg,
                       l.max ? *l.max * unit : kEndlessJointRangeDeg, *l.speed * unit, *l.accel * unit};
}

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

struct JointSection {
  bool angular = false;
  JointSettings limits;
  double home = 0.0;
  std::optional<LinuxcncHomingSwitch> homing;  ///< none: homes at once, at `home`
};

// The textbook's homing for a joint with the limits `s`: the switch 1 % of the range below the lower software
// stop, the search at a quarter of the speed limit, the latch fifty times slower (v1 ≫ v2).
LinuxcncHomingSwitch homing_switch(const JointSettings& s) {
  const double search = 0.25 * s.speed;
  return {s.min - 0.01 * (s.max - s.min), search, search / 50.0};
}

// The machine's actuators as LinuxCNC joints, at their home positions.
std::vector<JointSection> actuator_joints(const Machine& machine, const JointSettings& s,
                                          const LinuxcncConfig& config) {
  std::vector<JointSection> joints;
  for (std::size_t j = 0; j < config.home_joints.size(); ++j) {
    joints.push_back({machine.mechanism->actuators_are_angles(), s, config.home_joints[j], std::nullopt});
    if (!config.homing_switches.empty()) joints.back().homing = config.homing_switches[j];
  }
  return joints;
}

// The controlled coordinates as joints of trivkins, and the limits of LinuxCNC's axes: the same program
// through the same motion controller with no kinematics is the baseline of the servo-thread time comparison.
std::vector<JointSection> coordinate_joints(const Machine& machine, const PoseVector& home,
                                            const JointSettings& actuators) {
  std::vector<JointSection> joints;
  const Mechanism& m = *machine.mechanism;
  const double stroke_mm =
      m.actuators_are_angles() ? 2.0 * m.platform_size_mm() : actuators.max - actuators.min;
  const double angular_accel = deg_from_rad(machine.motion.path_accel_mm_s2 / m.platform_size_mm());
  const AxisMask axes = m.controlled_axes();
  for (int i = 0; i < 6; ++i) {
    if (!axes.controlled[static_cast<std::size_t>(i)]) continue;
    const bool linear = i < 3;
    const double centre = linear ? home[i] : deg_from_rad(home[i]);
    const double reach = linear ? stroke_mm : 180.0;
    JointSettings limits{
        centre - reach, centre + reach,
        linear ? machine.motion.rapid_mm_min / 60.0 : machine.motion.angular_feed_deg_min / 60.0,
        linear ? machine.motion.path_accel_mm_s2 : angular_accel};
    joints.push_back({!linear, limits, centre, std::nullopt});
  }
  return joints;
}

// The whole platform's limits in LinuxCNC's axes (coordinate_joints). The joints carry the machine's real
// limits (LinuxCNC checks them on every joint command), so the axes only bound the planner: home ± the
// actuator stroke for positions and home ± 180° for angles.
std::string axis_sections(const Machine& machine, const PoseVector& home, const JointSettings& actuators) {
  const std::vector<JointSection> axes = coordinate_joints(machine, home, actuators);
  const AxisMask controlled = machine.mechanism->controlled_axes();
  std::string out;
  std::size_t k = 0;
  for (int i = 0; i < 6; ++i) {
    if (!controlled.controlled[static_cast<std::size_t>(i)]) continue;
    const JointSettings& l = axes[k++].limits;
    out +=
        fmt::format("[AXIS_{}]\nMIN_LIMIT = {}\nMAX_LIMIT = {}\nMAX_VELOCITY = {}\nMAX_ACCELERATION = {}\n\n",
                    kAxisLetters[i], number(l.min), number(l.max), number(l.speed), number(l.accel));
  }
  return out;
}

std::string homing_lines(const JointSection& s) {
  if (!s.homing) {
    // No home switches in a simulated machine: homing takes the joint's position as HOME_OFFSET (search and
    // latch speeds 0), and every joint homes at once, where the machine file's home pose puts it.
    return fmt::format("HOME = {0}\nHOME_OFFSET = {0}\nHOME_SEARCH_VEL = 0\nHOME_LATCH_VEL = 0\n",
                       number(s.home));
  }
  // Down to the lower boundary switch at v1, back off it at v2 until it releases: that edge is HOME_OFFSET
  // (the joint's coordinate there); then to HOME at the joint's speed limit.
  return fmt::format(
      "HOME = {}\nHOME_OFFSET = {}\nHOME_SEARCH_VEL = {}\nHOME_LATCH_VEL = {}\nHOME_USE_INDEX = NO\n",
      number(s.home), number(s.homing->switch_position), number(-s.homing->search_speed),
      number(s.homing->latch_speed));
}

std::string joint_sections(const std::vector<JointSection>& joints) {
  std::string out;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const JointSection& s = joints[j];
    out += fmt::format(
        "[JOINT_{}]\nTYPE = {}\nMIN_LIMIT = {}\nMAX_LIMIT = {}\nMAX_VELOCITY = {}\nMAX_ACCELERATION = {}\n{}"
        "HOME_SEQUENCE = 0\n\n",
        j, s.angular ? "ANGULAR" : "LINEAR", number(s.limits.min), number(s.limits.max),
        number(s.limits.speed), number(s.limits.accel), homing_lines(s));
  }
  return out;
}

std::string ini_text(const Machine& machine, const LinuxcncConfigOptions& options,
                     const std::string& kinematics, const LinuxcncConfig& config, const JointSettings& joints,
                     const PoseVector& home) {
  const Mechanism& m = *machine.mechanism;
  const AxisMask axes = m.controlled_axes();
  std::string coordinates, origin;
  for (int i = 0; i < 6; ++i) {
    if (!axes.controlled[static_cast<std::size_t>(i)]) continue;
    coordinates += fmt::format("{}{}", coordinates.empty() ? "" : " ", kAxisLetters[i]);
    if (i < 3) origin += fmt::format(" {}{}", kAxisLetters[i], number(machine.motion.program_origin_mm[i]));
  }
  // The world home: kinematics whose forward solution iterates (genhexkins) start their homed pose from it.
  std::string home_text;
  for (int i = 0; i < 6; ++i) {
    const double value = i < 3 ? home[i] : deg_from_rad(home[i]);
    home_text += fmt::format("{}{}", i ? " " : "", number(value + 0.0));  // + 0.0: no angle prints 0, not -0
  }
  const std::vector<JointSection> joint_list = options.kinematics == LinuxcncKinematics::trivkins
                                                   ? coordinate_joints(machine, home, joints)
                                                   : actuator_joints(machine, joints, config);
  // halui (LinuxCNC's HAL user interface, started before the HAL files) gives execute.hal the operator's feed
  // override and E-stop; pkmexec's override goes to 120 % (execution/machine_headroom.hpp), LinuxCNC's slider
  // too then.
  std::string hal_files =
      options.execute ? "HALUI = halui\nHALFILE = machine.hal\nHALFILE = execute.hal\nHALFILE = drives.hal\n"
                      : "HALFILE = machine.hal\nHALFILE = drives.hal\n";
  if (options.kinematics == LinuxcncKinematics::genhexkins) hal_files += "HALFILE = genhexkins.hal\n";
  return fmt::format(
      "# LinuxCNC configuration of {name}, written by `pkm linuxcnc config` from {source}.\n"
      "# Machine coordinates are pkm's base frame (the tool point, mm) and G-code's angles A B C in "
      "degrees,\n"
      "# R = Rz(C)*Ry(B)*Rx(A) whatever the machine file's own convention ({conv}), as pkm plan reads them;\n"
      "# G54 is the machine file's program origin (motion.program_origin_mm). Regenerate rather than edit: "
      "the\n"
      "# joints' limits and homes come from the machine file.\n"
      "# Without an X display: `pkm linuxcnc config --display linuxcncrsh` (LinuxCNC's text interface, port "
      "5007)\n"
      "# or --display /path/to/pkm/linuxcnc/headless_run.py (runs one program). As root, rtapi_app runs as "
      "another\n"
      "# user, who must be able to read this folder, with its socket in /tmp:\n"
      "#   {start}\n\n"
      "[EMC]\nVERSION = 1.1\nMACHINE = {name}\n\n"
      "[DISPLAY]\nDISPLAY = {display}\nPOSITION_OFFSET = RELATIVE\nPOSITION_FEEDBACK = COMMANDED\n"
      "MAX_FEED_OVERRIDE = {max_override}\n\n"
      "[RS274NGC]\nPARAMETER_FILE = pkm.var\nRS274NGC_STARTUP_CODE = G21 G90 G10 L2 P1{origin}\n\n"
      "[EMCMOT]\nEMCMOT = motmod\nCOMM_TIMEOUT = 1.0\nSERVO_PERIOD = {period}\n\n"
      "[TASK]\nTASK = milltask\nCYCLE_TIME = 0.010\n\n"
      "[HAL]\n{hal}\n"
      "[TRAJ]\nCOORDINATES = {coordinates}\nLINEAR_UNITS = mm\nANGULAR_UNITS = degree\nHOME = {home}\n"
      "DEFAULT_LINEAR_VELOCITY = {feed}\nMAX_LINEAR_VELOCITY = {rapid}\nMAX_LINEAR_ACCELERATION = {accel}\n"
      "DEFAULT_ANGULAR_VELOCITY = {angular}\nMAX_ANGULAR_VELOCITY = {angular}\n\n"
      "[EMCIO]\nEMCIO = io\nCYCLE_TIME = 0.100\nTOOL_TABLE = tool.tbl\n\n"
      "[KINS]\nKINEMATICS = {kinematics}\nJOINTS = {joints}\n\n"
      "{joint_sections}{axis_sections}",
      fmt::arg("name", machine.name.empty() ? std::string("pkm machine") : machine.name),
      fmt::arg("source", machine.source), fmt::arg("conv", to_string(m.convention())),
      fmt::arg("start", linuxcnc_start_command(config.directory, true)), fmt::arg("display", options.display),
      fmt::arg("max_override", options.execute ? "1.2" : "1.5"), fmt::arg("origin", origin),
      fmt::arg("period", config.servo_period_ns), fmt::arg("hal", hal_files),
      fmt::arg("coordinates", coordinates), fmt::arg("home", home_text),
      fmt::arg("feed", number(machine.motion.max_feed_mm_min / 60.0)),
      fmt::arg("rapid", number(machine.motion.rapid_mm_min / 60.0)),
      fmt::arg("accel", number(machine.motion.path_accel_mm_s2)),
      fmt::arg("angular", number(machine.motion.angular_feed_deg_min / 60.0)),
      fmt::arg("kinematics", kinematics), fmt::arg("joints", joint_list.size()),
      fmt::arg("joint_sections", joint_sections(joint_list)),
      fmt::arg("axis_sections", axis_sections(machine, home, joints)));
}

std::string hal_text(const Machine& machine) {
  return fmt::format(
      "# Motion of {}: the motion controller runs in the servo thread through the [KINS] kinematics; the "
      "drives\n"
      "# are in drives.hal.\n"
      "loadrt [KINS]KINEMATICS\n"
      "loadrt [EMCMOT]EMCMOT servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS\n"
      "addf motion-command-handler servo-thread\naddf motion-controller servo-thread\n\n"
      "net estop-loop iocontrol.0.user-enable-out => iocontrol.0.emc-enable-in\n"
      "net tool-prepare-loop iocontrol.0.tool-prepare => iocontrol.0.tool-prepared\n"
      "net tool-change-loop iocontrol.0.tool-change => iocontrol.0.tool-changed\n",
      machine.name.empty() ? std::string("the machine") : machine.name);
}

// genhexkins' joint coordinates: base joints in the base frame and platform joints in the frame of LinuxCNC's
// Cartesian position, which is pkm's tool point with the platform's axes. Read off the mechanism at home
// through the interface; genhexkins can describe only six distance actuators with the whole pose free. Its
// A B C are roll, pitch and yaw, R = Rz(C)·Ry(B)·Rx(A), as pkmkins takes them, whatever the machine file's
// convention: the platform joints are in the platform's own frame, so the convention does not enter.
Result<std::string> genhexkins_text(const Machine& machine) {
  const Mechanism& m = *machine.mechanism;
  StrutJointPoints joints;
  if (!m.has_distance_actuators() || m.actuator_count() != 6 || m.controlled_axes().count() != 6 ||
      m.strut_joints(m.home(), joints) != 6) {
    Error e =
        make_error(ErrorCode::bad_input,
                   fmt::format("{}: genhexkins describes only hexapods with six strut-length actuators; use "
                               "pkmkins for this machine",
                               machine.source));
    e.location.file = machine.source;
    e.location.key = "type";
    return e;
  }
  std::string out =
      "# LinuxCNC's genhexkins with this machine's joints (platform joints in the tool frame, mm).\n";
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d base = joints.base_mm[j];
    const Eigen::Vector3d platform =
        m.home().rotation.transpose() * (joints.platform_mm[j] - m.home().position_mm);
    for (int k = 0; k < 3; ++k)
      out += fmt::format("setp genhexkins.base.{}.{} {}\n", j, "xyz"[k], number(base[k]));
    for (int k = 0; k < 3; ++k)
      out += fmt::format("setp genhexkins.platform.{}.{} {}\n", j, "xyz"[k], number(platform[k]));
  }
  return out;
}

// LinuxCNC's A B C are G-code's (abc angles). A machine that controls only some of its angles (a 3-RPS
// tripod) controls them in its own convention, which are LinuxCNC's A and B only in abc; pkmkins refuses
// any other, so the configuration does too, before writing anything.
Status check_angles_are_gcode_angles(const Machine& machine) {
  const Mechanism& m = *machine.mechanism;
  const AxisMask axes = m.controlled_axes();
  int angles = 0;
  for (std::size_t i = 3; i < 6; ++i) angles += axes.controlled[i] ? 1 : 0;
  if (angles == 0 || angles == 3 || m.convention() == AngleConvention::abc) return ok_status();
  Error e =
      make_error(ErrorCode::bad_input,
                 fmt::format("{}: angles: {}: the machine controls only some of its angles, and they are "
                             "LinuxCNC's (and G-code's) A B C, R = Rz(C)·Ry(B)·Rx(A), only in the abc "
                             "convention: write the machine file with angles: abc",
                             machine.source, to_string(m.convention())));
  e.location.file = machine.source;
  e.location.key = "angles";
  return e;
}

// LinuxCNC run as root reads the configuration as another user (rtapi_app's RTAPI_UID, linuxcnc_launch.hpp):
// the folder and its files are made readable by every user, whatever the umask. A failure only matters then,
// and linuxcnc_start_problems names it, so it is not an error here.
void open_to_read(const std::string& directory, const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  using fs::perms;
  std::error_code ignored;
  fs::permissions(directory, perms::group_read | perms::group_exec | perms::others_read | perms::others_exec,
                  fs::perm_options::add, ignored);
  for (const std::string& name : files)
    fs::permissions(fs::path(directory) / name, perms::group_read | perms::others_read, fs::perm_options::add,
                    ignored);
}

// Homing on switches and pkm's executor need the machine's actuators as LinuxCNC's joints (not trivkins'
// coordinates); the switches need the joints' range too.
Status check_options(const Machine& machine, const LinuxcncConfigOptions& options) {
  const bool actuators_as_joints = options.kinematics != LinuxcncKinematics::trivkins;
  if (options.homing == LinuxcncHoming::switches &&
      (!actuators_as_joints || !machine.limits.min || !machine.limits.max)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: homing on switches needs the joints' range (limits.actuator_min and "
                                  "actuator_max) and actuators as joints (not trivkins)",
                                  machine.source));
  }
  if (options.execute && !actuators_as_joints) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}: pkm's executor moves the machine's actuators, which are not LinuxCNC's "
                    "joints with trivkins: use pkmkins (or genhexkins) with --execute",
                    machine.source));
  }
  return ok_status();
}

// What drives.hal needs: the drives' resolution, speed and period, and where homing puts each joint.
LinuxcncDrivesHal drives_hal(const Machine& machine, const LinuxcncConfigOptions& options,
                             const LinuxcncConfig& config, const JointSettings& settings) {
  const Mechanism& m = *machine.mechanism;
  LinuxcncDrivesHal d;
  d.joints =
      options.kinematics == LinuxcncKinematics::trivkins ? m.controlled_axes().count() : m.actuator_count();
  d.step = machine.drives.step.value_or(0.001);
  d.angles = m.actuators_are_angles();
  d.speed = settings.speed;
  d.period_s = config.servo_period_ns * 1e-9;
  d.kind = options.drives;
  d.execute = options.execute;
  d.homing_switches = config.homing_switches;
  d.home_joints = config.home_joints;
  return d;
}

}  // namespace

Result<LinuxcncConfig> write_linuxcnc_config(const Machine& machine, const LinuxcncConfigOptions& options) {
  const Mechanism& m = *machine.mechanism;
  if (auto angles = check_angles_are_gcode_angles(machine); !angles) return angles.error();
  auto settings = joint_settings(machine);
  if (!settings) return settings.error();
  LinuxcncConfig config;
  const auto home_actuators = m.inverse(m.home());
  if (!home_actuators) return home_actuators.error();
  if (auto in_range = check_actuator_range(machine, *home_actuators); !in_range) return in_range.error();
  const double unit = m.actuators_are_angles() ? deg_from_rad(1.0) : 1.0;
  for (int j = 0; j < m.actuator_count(); ++j) config.home_joints.push_back((*home_actuators)[j] * unit);
  const AxisMask axes = m.controlled_axes();
  for (int i = 0; i < 6; ++i)
    if (axes.controlled[static_cast<std::size_t>(i)]) config.coordinates += kAxisLetters[i];
  config.servo_period_ns = static_cast<int>(std::lround(machine.drives.period_ms.value_or(1.0) * 1e6));
  if (auto checked = check_options(machine, options); !checked) return checked.error();
  if (options.homing == LinuxcncHoming::switches)
    config.homing_switches.assign(config.home_joints.size(), homing_switch(*settings));

  std::error_code ec;
  const std::string directory =
      std::filesystem::absolute(options.out_directory, ec).lexically_normal().string();
  // loadrt splits its line at spaces, so the machine file's path in the module's argument cannot have one.
  if (directory.find_first_of(" \t\"'") != std::string::npos) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}: LinuxCNC's loadrt cannot pass a path with spaces or quotes to pkmkins; "
                    "choose another --out",
                    directory));
  }
  config.directory = directory;
  std::string kinematics = std::string(to_string(options.kinematics));
  std::string genhexkins;
  if (options.kinematics == LinuxcncKinematics::genhexkins) {
    auto text = genhexkins_text(machine);
    if (!text) return text.error();
    genhexkins = std::move(text.value());
  } else if (options.kinematics == LinuxcncKinematics::trivkins) {
    kinematics += " coordinates=" + config.coordinates;
  } else {
    kinematics += " machine=" + directory + "/machine.yaml";
  }
  auto machine_text = read_input_file(machine.source, "machine file");
  if (!machine_text) return machine_text.error();

  OutputSet outputs{"linuxcnc config"};
  if (auto made = outputs.use_directory(directory); !made) return made.error();
  // LinuxCNC keeps the interpreter's parameters in the file the INI names, beside the configuration: writing
  // the configuration again after a run must not take them for someone else's files.
  outputs.allow_files_of_others({"pkm.var", "pkm.var.bak"});
  // LinuxCNC's A B C are G-code's (abc), as pkmkins converts them: its home and axis limits are too.
  const PoseVector home = vector_from_pose(AngleConvention::abc, m.home());
  std::vector<std::pair<std::string, std::string>> files = {
      {"machine.ini", ini_text(machine, options, kinematics, config, *settings, home)},
      {"machine.hal", hal_text(machine)},
      {"drives.hal", linuxcnc_drives_hal(drives_hal(machine, options, config, *settings))},
      {"machine.yaml", *machine_text},
      {"tool.tbl", "T1 P1 D0 Z0 ;no tool length: programs run at pkm's tool point\n"}};
  if (!genhexkins.empty()) files.emplace_back("genhexkins.hal", genhexkins);
  if (options.execute) {
    files.emplace_back("execute.hal", linuxcnc_execute_hal(m.actuator_count(), directory + "/machine.yaml",
                                                           config.servo_period_ns));
  }
  for (const auto& [name, text] : files) {
    std::ofstream out(outputs.staged_path(name), std::ios::binary);
    out << text;
    if (!out.flush()) {
      return make_error(ErrorCode::io, fmt::format("cannot write {}/{}", directory, name));
    }
    config.files.push_back(name);
  }
  if (auto committed = outputs.commit(); !committed) return committed.error();
  open_to_read(directory, config.files);
  return config;
}

}  // namespace pkm
