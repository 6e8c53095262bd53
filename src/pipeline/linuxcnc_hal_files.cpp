#include "pipeline/linuxcnc_hal_files.hpp"

#include <fmt/format.h>

namespace pkm {

namespace {

std::string hal_number(double value) {
  return fmt::format("{:.17g}", value);
}

// A comma-separated list of instance names, PREFIX-0 … PREFIX-(n−1) (LinuxCNC's `names=`).
std::string instance_names(const std::string& prefix, int n) {
  std::string out;
  for (int j = 0; j < n; ++j) out += fmt::format("{}{}-{}", j ? "," : "", prefix, j);
  return out;
}

// Where real drives go, as comments with this machine's numbers: step/dir through a Mesa card (hostmot2),
// step/dir through the parallel port with LinuxCNC's software step generator, EtherCAT servo drives. With
// execute.hal the command signal already has its writer (the hand-over), and the drives' enable is
// pkm-drives-enable (LinuxCNC's machine on, or pkmexec moving them).
std::string drive_examples(const LinuxcncDrivesHal& d) {
  const double steps_per_unit = 1.0 / d.step;
  const std::string unit = d.angles ? "deg" : "mm";
  const std::string command = d.execute ? "jN-pos-cmd" : "jN-pos-cmd joint.N.motor-pos-cmd";
  const std::string enable = d.execute ? "pkm-drives-enable" : "jN-enable joint.N.amp-enable-out";
  return fmt::format(
      "# Real drives replace the simulation below, joint by joint (N = 0 … joints − 1; one step is "
      "1/{0:.10g} {1}):\n"
      "#\n"
      "# Step/dir through a Mesa card (LinuxCNC's hostmot2; read first and write last in the servo thread):\n"
      "#   loadrt hostmot2\n"
      "#   loadrt hm2_eth board_ip=10.10.10.10 config=\"num_encoders=0 num_stepgens=6\"\n"
      "#   addf hm2_7i76e.0.read servo-thread 1\n"
      "#   addf hm2_7i76e.0.write servo-thread -1\n"
      "#   setp hm2_7i76e.0.stepgen.0N.position-scale {0:.10g}\n"
      "#   net {2} => hm2_7i76e.0.stepgen.0N.position-cmd\n"
      "#   net jN-pos-fb hm2_7i76e.0.stepgen.0N.position-fb => joint.N.motor-pos-fb\n"
      "#   net {3} => hm2_7i76e.0.stepgen.0N.enable\n"
      "#\n"
      "# Step/dir through the parallel port (LinuxCNC's software stepgen; needs [EMCMOT]BASE_PERIOD, a fast "
      "thread):\n"
      "#   loadrt hal_parport cfg=\"0x378 out\"\n"
      "#   loadrt stepgen step_type=0,0,0,0,0,0\n"
      "#   addf parport.0.read base-thread 1\n"
      "#   addf stepgen.make-pulses base-thread\n"
      "#   addf parport.0.write base-thread -1\n"
      "#   addf stepgen.capture-position servo-thread 1\n"
      "#   addf stepgen.update-freq servo-thread -1\n"
      "#   setp stepgen.N.position-scale {0:.10g}\n"
      "#   net {2} => stepgen.N.position-cmd\n"
      "#   net jN-pos-fb stepgen.N.position-fb => joint.N.motor-pos-fb\n"
      "#   net jN-step stepgen.N.step => parport.0.pin-02-out   (and dir to the next pin)\n"
      "#\n"
      "# EtherCAT servo drives in cyclic synchronous position mode (linuxcnc-ethercat's lcec, where "
      "installed):\n"
      "#   loadusr -W lcec_conf ethercat.xml\n"
      "#   loadrt lcec\n"
      "#   addf lcec.read-all servo-thread 1\n"
      "#   addf lcec.write-all servo-thread -1\n"
      "#   net {2} => lcec.0.driveN.pos-cmd\n"
      "#   net jN-pos-fb lcec.0.driveN.pos-fb => joint.N.motor-pos-fb\n"
      "#   net {3} => lcec.0.driveN.enable\n"
      "#\n"
      "# Home switches go to joint.N.home-sw-in (with pkm linuxcnc config --homing switches).\n\n",
      steps_per_unit, unit, command, enable);
}

// A home switch per joint, LinuxCNC's sim_home_switch on the drive's position `position_signal`: the
// simulated strut starts at its home length when LinuxCNC's motor position is 0 (it knows nothing of where
// the strut is before homing), so the switch trips at the motor position (switch − home); a negative position
// makes sim_home_switch trip below it.
std::string home_switch_hal(const LinuxcncDrivesHal& d, const std::string& position_signal) {
  const std::size_t n = d.homing_switches.size();
  std::string out = fmt::format(
      "\n# The lower boundary switches (simulated: a real machine wires its switches to "
      "joint.N.home-sw-in).\n"
      "loadrt sim_home_switch count={}\n",
      n);
  for (std::size_t j = 0; j < n; ++j) {
    out += fmt::format(
        "addf sim-home-switch.{0} servo-thread\nsetp sim-home-switch.{0}.home-pos {1}\n"
        "setp sim-home-switch.{0}.hysteresis 0.000001\nnet j{0}-{2} => sim-home-switch.{0}.cur-pos\n"
        "net j{0}-home-sw sim-home-switch.{0}.home-sw => joint.{0}.home-sw-in\n",
        j, hal_number(d.homing_switches[j].switch_position - d.home_joints[j]), position_signal);
  }
  return out;
}

// Simulated step drives: each joint is where it is commanded, to the step.
std::string step_drives(const LinuxcncDrivesHal& d) {
  std::string out = "# The drives, simulated: every joint is where it is commanded.\n" + drive_examples(d);
  for (int j = 0; j < d.joints; ++j) {
    out += d.execute ? fmt::format("net j{0}-pos-cmd => joint.{0}.motor-pos-fb\n", j)
                     : fmt::format("net j{0}-pos-cmd joint.{0}.motor-pos-cmd => joint.{0}.motor-pos-fb\n", j);
  }
  return out;
}

// Simulated servo drives: LinuxCNC's pid closing a position loop per joint (velocity feed-forward FF1 = 1, a
// proportional gain of a tenth of the servo rate: an error decays in ten periods; the output limited to twice
// the drive's speed) on a motor that integrates the velocity it is given (LinuxCNC's integ).
std::string servo_drives(const LinuxcncDrivesHal& d) {
  std::string out =
      "# The drives, simulated servo drives: a position loop (LinuxCNC's pid, velocity feed-forward) per "
      "joint\n"
      "# on a motor that integrates its velocity command (integ). A real drive replaces both.\n" +
      drive_examples(d);
  out += fmt::format("loadrt pid names={}\nloadrt integ names={}\n", instance_names("pkm-servo", d.joints),
                     instance_names("pkm-motor", d.joints));
  const double p_gain = 0.1 / d.period_s;
  for (int j = 0; j < d.joints; ++j) {
    out += fmt::format(
        "addf pkm-servo-{0}.do-pid-calcs servo-thread\naddf pkm-motor-{0} servo-thread\n"
        "setp pkm-servo-{0}.Pgain {1}\nsetp pkm-servo-{0}.FF1 1\nsetp pkm-servo-{0}.maxoutput {2}\n"
        "net j{0}-pos-cmd{3} => pkm-servo-{0}.command\n"
        "net j{0}-pos-fb pkm-motor-{0}.out => pkm-servo-{0}.feedback joint.{0}.motor-pos-fb\n"
        "net j{0}-vel-cmd pkm-servo-{0}.output => pkm-motor-{0}.in\n"
        "net {4} => pkm-servo-{0}.enable\n",
        j, hal_number(p_gain), hal_number(2.0 * d.speed),
        d.execute ? "" : fmt::format(" joint.{}.motor-pos-cmd", j),
        d.execute ? std::string("pkm-drives-enable")
                  : fmt::format("j{0}-enable joint.{0}.amp-enable-out", j));
  }
  return out;
}

}  // namespace

std::string linuxcnc_drives_hal(const LinuxcncDrivesHal& drives) {
  const bool servo = drives.kind == LinuxcncDrives::servo;
  std::string out = servo ? servo_drives(drives) : step_drives(drives);
  if (!drives.homing_switches.empty()) out += home_switch_hal(drives, servo ? "pos-fb" : "pos-cmd");
  return out;
}

std::string linuxcnc_execute_hal(int joints, const std::string& machine_file, int servo_period_ns) {
  std::string out = fmt::format(
      "# pkm's executor pkmexec (docs/linuxcnc.md, \"Executing pkm's own motion\"): `pkm linuxcnc stream "
      "PROGRAM\n"
      "# --machine M | pkm_feed.py --machine-on` streams a planned program into it while LinuxCNC runs.\n"
      "#\n"
      "# The drives are LinuxCNC's until a program starts, then pkmexec's until it ends: pkmexec takes a "
      "program only\n"
      "# when LinuxCNC is on, homed, idle and at rest (pkm-handed-over); while it moves the drives "
      "LinuxCNC's "
      "motion\n"
      "# is disabled (its machine shows off, \"motion stopped by enable input\") and follows them, so that "
      "it "
      "takes\n"
      "# them back, where pkmexec left them, when its machine is turned on again (pkm_feed.py "
      "--machine-on).\n"
      "loadrt pkmexec machine={0} period_ns={1}\n"
      "loadrt sum2 names={2}\nloadrt mux2 names={3}\n"
      "loadrt not names=pkm-motion-off\nloadrt or2 names=pkm-drives-on,pkm-stop\n"
      "loadrt logic names=pkm-ready personality=0x104\n"
      "addf pkm-ready servo-thread\naddf pkmexec.update servo-thread\naddf pkm-motion-off servo-thread\n"
      "addf pkm-drives-on servo-thread\naddf pkm-stop servo-thread\n\n"
      "net pkm-motion-enabled motion.motion-enabled => pkm-ready.in-00 pkm-drives-on.in0\n"
      "net pkm-all-homed motion.is-all-homed => pkm-ready.in-01\n"
      "net pkm-in-position motion.in-position => pkm-ready.in-02\n"
      "net pkm-interpreter-idle halui.program.is-idle => pkm-ready.in-03\n"
      "net pkm-handed-over pkm-ready.and => pkmexec.enable\n"
      "net pkm-active pkmexec.active => pkm-motion-off.in pkm-drives-on.in1\n"
      "net pkm-motion-allowed pkm-motion-off.out => motion.enable\n"
      "net pkm-drives-enable pkm-drives-on.out\n\n"
      "# The operator: LinuxCNC's feed override (0 … 120 %), a feed-hold button (`halcmd sets pkm-feed-hold "
      "1`), "
      "an\n"
      "# abort (`sets pkm-abort 1`) and LinuxCNC's E-stop, which stop along the path within the drives' "
      "limits.\n"
      "net pkm-feed-override halui.feed-override.value => pkmexec.feed-override\n"
      "net pkm-feed-hold => pkmexec.feed-hold\n"
      "net pkm-estop halui.estop.is-activated => pkm-stop.in0\n"
      "net pkm-abort => pkm-stop.in1\n"
      "net pkm-stop-now pkm-stop.out => pkmexec.abort\n\n"
      "# Per joint: pkmexec's command in motor units (joint + LinuxCNC's motor offset from homing) or "
      "LinuxCNC's,\n"
      "# whichever has the drives, as jJ-pos-cmd; pkmexec follows LinuxCNC's joint position in between.\n",
      machine_file, servo_period_ns, instance_names("pkm-motor-cmd", joints),
      instance_names("pkm-drive-cmd", joints));
  for (int j = 0; j < joints; ++j) {
    out += fmt::format(
        "addf pkm-motor-cmd-{0} servo-thread\naddf pkm-drive-cmd-{0} servo-thread\n"
        "net j{0}-pkm-cmd pkmexec.{0}.pos-cmd => pkm-motor-cmd-{0}.in0\n"
        "net j{0}-motor-offset joint.{0}.motor-offset => pkm-motor-cmd-{0}.in1\n"
        "net j{0}-pkm-motor-cmd pkm-motor-cmd-{0}.out => pkm-drive-cmd-{0}.in1\n"
        "net j{0}-motion-cmd joint.{0}.motor-pos-cmd => pkm-drive-cmd-{0}.in0\n"
        "net pkm-active => pkm-drive-cmd-{0}.sel\n"
        "net j{0}-pos-cmd pkm-drive-cmd-{0}.out\n"
        "net j{0}-joint-pos joint.{0}.pos-fb => pkmexec.{0}.pos-fb\n",
        j);
  }
  return out;
}

}  // namespace pkm
