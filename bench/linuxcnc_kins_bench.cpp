// The two LinuxCNC kinematics modules of a hexapod side by side, through their own entry points: pkm's
// pkmkins.so (machine=examples/machines/hexapod_genhexkins.yaml) and LinuxCNC's genhexkins.so with the same
// geometry on its pins. Both are loaded as rtapi_app loads them (dlopen); the few HAL/RTAPI functions they
// import are provided by this executable (exported from it, so the modules resolve them).
//
// The path is a servo-rate one: 1 kHz samples of a smooth 5-axis motion around home, 20 s. Before any timing,
// the inverse kinematics of both modules must agree along it to 1e-6 mm and their forward kinematics must
// return its poses (pkmkins to 1e-8, genhexkins to 1e-6), or the program stops with an error.
//
// Beside the modules, pkm's hot IK through its Mechanism interface in this process, from the same EmcPose:
// degrees → radians and Mechanism::actuator_values_at (the angles' sines and cosines included) on the
// machine file's mechanism, what pkmkins' kinematicsInverse does inside without the module's joint
// bookkeeping. It must agree with genhexkins to 1e-6 mm along the path too.
//
// Then three measurements:
//   - a table printed first: every call timed on its own (steady_clock) over the whole path 5 times, the
//   modules
//     alternating per pass, with the mean, p99.9 and worst case of inverse, forward and of both together, the
//     work of one servo period (LinuxCNC's motion controller calls inverse for the command and forward for
//     the feedback every period in coordinated mode); a servo thread has to budget for the tail, not the
//     mean;
//   - the hot IK side by side: genhexkins' kinematicsInverse and Mechanism::actuator_values_at over the whole
//     path in blocks, alternating, each block timed as a whole (no clock reading per call), with the ratio;
//   - Google Benchmarks, one call per iteration, cycling along the path (BM_Inverse/pkm_actuator_values is
//     the interface's).
#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/pose.hpp"
#include "core/units.hpp"
#include "io/machine_file.hpp"
#include "machine/mechanism.hpp"

#ifndef PKM_KINS_MODULE
#error \
    "PKM_KINS_MODULE (the path of the built pkmkins.so) is set by linuxcnc/CMakeLists.txt where pkmkins is built"
#endif

// ---------------------------------------------------------------------------------------------------------------
// The HAL/RTAPI functions the modules import (declared as in /usr/include/linuxcnc/hal.h and rtapi.h; those
// headers are C for LinuxCNC's own build flags, so the prototypes are repeated here). hal_pin_dir_t and
// msg_level_t are C enums, passed as int.
extern "C" {
int hal_init(const char* name);
int hal_exit(int comp_id);
int hal_ready(int comp_id);
void* hal_malloc(long int size);
int hal_pin_bit_new(const char* name, int dir, volatile bool** data_ptr_addr, int comp_id);
int hal_pin_s32_new(const char* name, int dir, volatile std::int32_t** data_ptr_addr, int comp_id);
int hal_pin_bit_newf(int dir, volatile bool** data_ptr_addr, int comp_id, const char* fmt, ...)
    __attribute__((format(printf, 4, 5)));
int hal_pin_u32_newf(int dir, volatile std::uint32_t** data_ptr_addr, int comp_id, const char* fmt, ...)
    __attribute__((format(printf, 4, 5)));
int hal_pin_float_newf(int dir, volatile double** data_ptr_addr, int comp_id, const char* fmt, ...)
    __attribute__((format(printf, 4, 5)));
void rtapi_print(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
void rtapi_print_msg(int level, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
}

namespace {

// A pin's storage, big enough for every HAL pin type; pins live until the process ends, as in HAL's shared
// memory, so the modules' pointers to them never dangle.
union PinStorage {
  bool bit;
  std::int32_t s32;
  std::uint32_t u32;
  double real;
};

// Every pin the modules create, by name: how the benchmark sets genhexkins' geometry and reads the modules'
// iteration counters, as halcmd would.
std::map<std::string, std::unique_ptr<PinStorage>>& pins() {
  static std::map<std::string, std::unique_ptr<PinStorage>> registry;
  return registry;
}

PinStorage* new_pin(const std::string& name) {
  auto [it, inserted] = pins().try_emplace(name, std::make_unique<PinStorage>());
  if (!inserted) {
    std::fprintf(stderr, "HAL: pin %s exists already\n", name.c_str());
    return nullptr;
  }
  return it->second.get();
}

std::string format_name(const char* fmt, va_list args) {
  char name[128];  // HAL_NAME_LEN is 47
  std::vsnprintf(name, sizeof name, fmt, args);
  return name;
}

// Hands a new pin's storage of one type to the module, as HAL's *_new functions do; -1 when there is none.
template <class T>
int place_pin(PinStorage* storage, volatile T** data_ptr_addr, T PinStorage::*member) {
  if (storage == nullptr) return -1;
  *data_ptr_addr = &(storage->*member);
  return 0;
}

PinStorage& pin(const std::string& name) {
  const auto it = pins().find(name);
  if (it == pins().end()) throw std::runtime_error("no HAL pin " + name);
  return *it->second;
}

// LinuxCNC's RTAPI_MSG_WARN: the modules' warnings and errors are shown, their load-time information is not.
constexpr int kMsgWarn = 2;

}  // namespace

extern "C" {

int hal_init(const char*) {
  static int next_id = 1;
  return next_id++;
}
int hal_exit(int) {
  return 0;
}
int hal_ready(int) {
  return 0;
}
void* hal_malloc(long int size) {
  return std::calloc(1, static_cast<std::size_t>(size));
}

int hal_pin_bit_new(const char* name, int, volatile bool** data_ptr_addr, int) {
  return place_pin(new_pin(name), data_ptr_addr, &PinStorage::bit);
}

int hal_pin_s32_new(const char* name, int, volatile std::int32_t** data_ptr_addr, int) {
  return place_pin(new_pin(name), data_ptr_addr, &PinStorage::s32);
}

int hal_pin_bit_newf(int, volatile bool** data_ptr_addr, int, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  const std::string name = format_name(fmt, args);
  va_end(args);
  return place_pin(new_pin(name), data_ptr_addr, &PinStorage::bit);
}

int hal_pin_u32_newf(int, volatile std::uint32_t** data_ptr_addr, int, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  const std::string name = format_name(fmt, args);
  va_end(args);
  return place_pin(new_pin(name), data_ptr_addr, &PinStorage::u32);
}

int hal_pin_float_newf(int, volatile double** data_ptr_addr, int, const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  const std::string name = format_name(fmt, args);
  va_end(args);
  return place_pin(new_pin(name), data_ptr_addr, &PinStorage::real);
}

void rtapi_print(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  std::vfprintf(stderr, fmt, args);
  va_end(args);
}

void rtapi_print_msg(int level, const char* fmt, ...) {
  if (level > kMsgWarn) return;
  va_list args;
  va_start(args, fmt);
  std::vfprintf(stderr, fmt, args);
  va_end(args);
}

}  // extern "C"

namespace {

// LinuxCNC's EmcPose (emcpos.h) and the kinematics entry points (kinematics.h), whose flags are unsigned
// long.
struct EmcPose {
  struct {
    double x, y, z;
  } tran;
  double a, b, c, u, v, w;
};
using KinsFlags = unsigned long;
using InverseFn = int (*)(const EmcPose*, double*, const KinsFlags*, KinsFlags*);
using ForwardFn = int (*)(const double*, EmcPose*, const KinsFlags*, KinsFlags*);
using HomeFn = int (*)(EmcPose*, double*, KinsFlags*, KinsFlags*);

constexpr int kJoints = 6;
using Joints = std::array<double, kJoints>;

constexpr const char* kGenhexkinsModule = "/usr/lib/linuxcnc/modules/genhexkins.so";
constexpr const char* kMachineFile = "examples/machines/hexapod_genhexkins.yaml";

// A loaded module, and the state LinuxCNC's motion controller keeps for it.
struct KinsModule {
  const char* name = "";
  void* handle = nullptr;
  InverseFn inverse = nullptr;
  ForwardFn forward = nullptr;
  // The last forward solution, passed to the next forward call as LinuxCNC passes the previous feedback pose:
  // genhexkins iterates from it; pkmkins ignores it and keeps its own warm start.
  EmcPose feedback{};
  // The module's place on the path (see PathCursor): its forward warm start belongs to that place.
  std::size_t at = 0;
  bool backwards = false;
  // Each sample's joints from the module's own inverse kinematics: the input of its forward calls.
  std::vector<Joints> joints;
  const char* iterations_pin = "";
};

void* symbol(void* handle, const char* module, const char* name) {
  void* s = dlsym(handle, name);
  if (s == nullptr) throw std::runtime_error(std::string(module) + ": no symbol " + name);
  return s;
}

void* open_module(const std::string& path) {
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (h == nullptr) throw std::runtime_error("dlopen " + path + ": " + dlerror());
  return h;
}

void bind_kinematics(KinsModule& m) {
  m.inverse = reinterpret_cast<InverseFn>(symbol(m.handle, m.name, "kinematicsInverse"));
  m.forward = reinterpret_cast<ForwardFn>(symbol(m.handle, m.name, "kinematicsForward"));
}

void run_app_main(const KinsModule& m) {
  const auto app_main = reinterpret_cast<int (*)()>(symbol(m.handle, m.name, "rtapi_app_main"));
  if (app_main() != 0) throw std::runtime_error(std::string(m.name) + ": rtapi_app_main failed");
}

std::filesystem::path machine_file() {
  return std::filesystem::path(PKM_SOURCE_DIR) / kMachineFile;
}

// `loadrt pkmkins machine=...`: rtapi_app sets the module parameter through the address the module publishes
// (RTAPI_MP_STRING: void* rtapi_info_address_machine = &machine) before calling rtapi_app_main.
KinsModule load_pkmkins() {
  static const std::string machine = machine_file().string();  // the module keeps the pointer
  KinsModule m;
  m.name = "pkmkins";
  m.iterations_pin = "pkmkins.fk-iterations";
  m.handle = open_module(PKM_KINS_MODULE);
  auto** parameter = *static_cast<char***>(symbol(m.handle, m.name, "rtapi_info_address_machine"));
  *parameter = const_cast<char*>(machine.c_str());
  run_app_main(m);
  bind_kinematics(m);
  return m;
}

// `loadrt genhexkins` and then, as a configuration's HAL file does, `setp genhexkins.base.N.x ...`: the
// machine file's joints (mm). Its pins are read at every call, so setting them after rtapi_app_main is
// enough.
KinsModule load_genhexkins() {
  if (!std::filesystem::exists(kGenhexkinsModule)) {
    throw std::runtime_error(std::string(kGenhexkinsModule) +
                             " not found: LinuxCNC's genhexkins is needed (Debian: linuxcnc-uspace)");
  }
  KinsModule m;
  m.name = "genhexkins";
  // Its kinematicsForward solves twice: switchkins solves again from the answer for the vismach GUI's pins
  // (gui_kinstype 0), in one iteration, and last-iterations is that second solve's; max-iterations is the
  // most of any solve.
  m.iterations_pin = "genhexkins.max-iterations";
  m.handle = open_module(kGenhexkinsModule);
  run_app_main(m);
  bind_kinematics(m);
  const YAML::Node file = YAML::LoadFile(machine_file().string());
  for (const char* part : {"base", "platform"}) {
    const YAML::Node points = file[std::string(part) + "_joints"];
    if (!points || points.size() != kJoints) throw std::runtime_error(std::string("machine file: ") + part);
    for (int i = 0; i < kJoints; ++i) {
      for (int k = 0; k < 3; ++k) {
        const std::string name = "genhexkins." + std::string(part) + "." + std::to_string(i) + "." + "xyz"[k];
        pin(name).real = points[i][k].as<double>();
      }
    }
  }
  return m;
}

// The machine file's mechanism in this process, for its hot IK through the interface.
std::unique_ptr<pkm::Machine> load_interface_machine() {
  auto loaded = pkm::load_machine_file(machine_file().string());
  if (!loaded) throw std::runtime_error("machine file: " + loaded.error().message);
  return std::make_unique<pkm::Machine>(std::move(loaded.value()));
}

// An EmcPose's joints through Mechanism::actuator_values_at: the six coordinates (angles in degrees,
// LinuxCNC's A, B, C: the abc convention, as pkmkins reads them) to the joints, the rotation included.
inline bool interface_inverse(const pkm::Mechanism& mechanism, const EmcPose& world, double* joints) {
  const pkm::PoseVector v =
      (pkm::PoseVector() << world.tran.x, world.tran.y, world.tran.z, pkm::rad_from_deg(world.a),
       pkm::rad_from_deg(world.b), pkm::rad_from_deg(world.c))
          .finished();
  return mechanism.actuator_values_at(pkm::AngleConvention::abc, v, joints);
}

void unload(KinsModule& m) {
  if (m.handle == nullptr) return;
  reinterpret_cast<void (*)()>(symbol(m.handle, m.name, "rtapi_app_exit"))();
  dlclose(m.handle);
  m.handle = nullptr;
}

// ---------------------------------------------------------------------------------------------------------------
// The path: 1 kHz samples, 20 s, of a smooth motion of X, Y, Z, A, B, C around home (0, 0, 508) mm, level.
constexpr double kPeriodS = 1e-3;
constexpr std::size_t kSamples = 20'000;

std::vector<EmcPose> servo_path() {
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  std::vector<EmcPose> path(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double t = static_cast<double>(i) * kPeriodS;
    EmcPose& p = path[i];
    p = EmcPose{};
    p.tran.x = 20.0 * std::sin(kTwoPi * t / 4.0);
    p.tran.y = 15.0 * std::sin(kTwoPi * t / 3.0);
    p.tran.z = 508.0 + 5.0 * std::sin(kTwoPi * t / 5.0);
    p.a = 4.0 * std::sin(kTwoPi * t / 6.0);
    p.b = 3.0 * std::sin(kTwoPi * t / 7.0);
    p.c = 6.0 * std::sin(kTwoPi * t / 8.0);
  }
  return path;
}

// The next sample of a module's walk along the path, back and forth (0 … N−1, N−2 … 0, 1 …): the path's end
// is not its start, and a jump there would hand the forward kinematics one far warm start per pass.
std::size_t next_sample(KinsModule& m) {
  const std::size_t k = m.at;
  if (m.backwards ? m.at == 0 : m.at + 1 == kSamples) m.backwards = !m.backwards;
  m.at = m.backwards ? m.at - 1 : m.at + 1;
  return k;
}

double max_pose_difference(const EmcPose& p, const EmcPose& q) {
  return std::max({std::abs(p.tran.x - q.tran.x), std::abs(p.tran.y - q.tran.y),
                   std::abs(p.tran.z - q.tran.z), std::abs(p.a - q.a), std::abs(p.b - q.b),
                   std::abs(p.c - q.c)});
}

[[noreturn]] void fail(const std::string& message) {
  throw std::runtime_error(message);
}

// Both modules along the whole path, once: inverse kinematics agreeing, forward kinematics returning the
// poses. Also the first walk of each module along the path and its joints for the forward calls.
void verify(KinsModule& pkmkins, KinsModule& genhexkins, const pkm::Mechanism& mechanism,
            const std::vector<EmcPose>& path) {
  constexpr double kInverseAgreementMm = 1e-6;
  const KinsFlags iflags = 0, fflags = 0;
  KinsFlags out_flags = 0;
  double worst_inverse = 0.0;
  for (KinsModule* m : {&pkmkins, &genhexkins}) m->joints.resize(kSamples);
  for (std::size_t k = 0; k < kSamples; ++k) {
    for (KinsModule* m : {&pkmkins, &genhexkins}) {
      if (m->inverse(&path[k], m->joints[k].data(), &iflags, &out_flags) != 0) {
        fail(std::string(m->name) + ": inverse kinematics failed at sample " + std::to_string(k));
      }
    }
    for (int j = 0; j < kJoints; ++j) {
      worst_inverse = std::max(worst_inverse, std::abs(pkmkins.joints[k][j] - genhexkins.joints[k][j]));
    }
    if (!(worst_inverse <= kInverseAgreementMm)) {
      fail("the modules' inverse kinematics disagree at sample " + std::to_string(k) + " by " +
           std::to_string(worst_inverse) + " mm (limit 1e-6)");
    }
  }
  std::printf("inverse kinematics, pkmkins vs genhexkins: max |joint difference| %.3g mm over %zu samples\n",
              worst_inverse, kSamples);
  double worst_interface = 0.0;
  for (std::size_t k = 0; k < kSamples; ++k) {
    Joints joints{};
    if (!interface_inverse(mechanism, path[k], joints.data())) {
      fail("Mechanism::actuator_values_at failed at sample " + std::to_string(k));
    }
    for (int j = 0; j < kJoints; ++j) {
      worst_interface = std::max(worst_interface, std::abs(joints[j] - genhexkins.joints[k][j]));
    }
  }
  if (!(worst_interface <= kInverseAgreementMm)) {
    fail("Mechanism::actuator_values_at and genhexkins disagree by " + std::to_string(worst_interface) +
         " mm");
  }
  std::printf(
      "inverse kinematics, Mechanism::actuator_values_at vs genhexkins: max |joint difference| %.3g mm\n",
      worst_interface);

  for (KinsModule* m : {&pkmkins, &genhexkins}) {
    const double tolerance = m == &pkmkins ? 1e-8 : 1e-6;
    double worst = 0.0;
    double iterations = 0.0;
    std::uint32_t most = 0;
    for (std::size_t i = 0; i < kSamples; ++i) {
      const std::size_t k = next_sample(*m);
      if (m->forward(m->joints[k].data(), &m->feedback, &fflags, &out_flags) != 0) {
        fail(std::string(m->name) + ": forward kinematics failed at sample " + std::to_string(k));
      }
      const double error = max_pose_difference(m->feedback, path[k]);
      if (!(error <= tolerance)) {
        fail(std::string(m->name) + ": forward kinematics off the pose at sample " + std::to_string(k) +
             " by " + std::to_string(error) + " (mm or deg)");
      }
      worst = std::max(worst, error);
      iterations += pin(m->iterations_pin).u32;
      most = std::max(most, pin(m->iterations_pin).u32);
    }
    std::printf("forward kinematics, %-10s: max |pose error| %.3g (mm, deg); pin %s: mean %.2f, max %u\n",
                m->name, worst, m->iterations_pin, iterations / kSamples, most);
  }
}

// The first forward call of each module from home, before anything else, as LinuxCNC makes at start-up.
// genhexkins (switchkins) starts its first forward call from its own saved pose, all zeros, not from the pose
// passed in; that fails (too far), and the next call starts from the pose passed in.
void start_forward(KinsModule& m, const EmcPose& home) {
  const KinsFlags fflags = 0;
  KinsFlags iflags = 0;
  Joints joints{};
  if (m.inverse(&home, joints.data(), &fflags, &iflags) != 0) fail(std::string(m.name) + ": no IK at home");
  for (int attempt = 0; attempt < 2; ++attempt) {
    m.feedback = home;
    if (m.forward(joints.data(), &m.feedback, &fflags, &iflags) == 0 &&
        max_pose_difference(m.feedback, home) < 1e-6)
      return;
    std::printf(
        "%s: the first forward call failed (switchkins starts it from its saved pose, zeros); again\n",
        m.name);
  }
  fail(std::string(m.name) + ": forward kinematics fail at home");
}

// ---------------------------------------------------------------------------------------------------------------
// The per-call table.
using Clock = std::chrono::steady_clock;
constexpr int kPasses = 5;

struct CallTimes {
  std::vector<std::int64_t> inverse, forward, period;  // ns
};

struct Summary {
  double mean = 0.0, p99_9 = 0.0, worst = 0.0;
};

Summary summarise(std::vector<std::int64_t> ns) {
  Summary s;
  double sum = 0.0;
  for (const std::int64_t t : ns) sum += static_cast<double>(t);
  s.mean = sum / static_cast<double>(ns.size());
  // The smallest time at or above 99.9 % of the calls.
  const auto rank = static_cast<std::size_t>(std::ceil(0.999 * static_cast<double>(ns.size()))) - 1;
  std::nth_element(ns.begin(), ns.begin() + static_cast<std::ptrdiff_t>(rank), ns.end());
  s.p99_9 = static_cast<double>(ns[rank]);
  s.worst = static_cast<double>(*std::max_element(ns.begin(), ns.end()));
  return s;
}

std::int64_t ns_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
}

// One pass along the path: per servo period, the command's inverse and then the forward of its joints, each
// timed on its own; the period's time spans both (one clock reading less than their sum).
void time_pass(KinsModule& m, const std::vector<EmcPose>& path, CallTimes& times) {
  const KinsFlags iflags = 0, fflags = 0;
  KinsFlags out_flags = 0;
  double joints[kJoints];
  for (std::size_t i = 0; i < kSamples; ++i) {
    const std::size_t k = next_sample(m);
    const Clock::time_point t0 = Clock::now();
    const int inverse = m.inverse(&path[k], joints, &iflags, &out_flags);
    const Clock::time_point t1 = Clock::now();
    const int forward = m.forward(joints, &m.feedback, &fflags, &out_flags);
    const Clock::time_point t2 = Clock::now();
    if (inverse != 0 || forward != 0) fail(std::string(m.name) + ": a kinematics call failed while timed");
    times.inverse.push_back(ns_between(t0, t1));
    times.forward.push_back(ns_between(t1, t2));
    times.period.push_back(ns_between(t0, t2));
  }
}

// The cost of one clock reading, which every timed call includes once.
double clock_reading_ns() {
  constexpr int kReadings = 100'000;
  const Clock::time_point start = Clock::now();
  for (int i = 0; i < kReadings; ++i) benchmark::DoNotOptimize(Clock::now());
  return static_cast<double>(ns_between(start, Clock::now())) / kReadings;
}

void print_table(KinsModule& pkmkins, KinsModule& genhexkins, const std::vector<EmcPose>& path) {
  CallTimes pkm_times, genhex_times;
  for (CallTimes* t : {&pkm_times, &genhex_times}) {
    for (auto* v : {&t->inverse, &t->forward, &t->period}) v->reserve(kPasses * kSamples);
  }
  // Alternating which module goes first, so that a noisy stretch of a shared machine hits both alike.
  for (int pass = 0; pass < kPasses; ++pass) {
    if (pass % 2 == 0) {
      time_pass(pkmkins, path, pkm_times);
      time_pass(genhexkins, path, genhex_times);
    } else {
      time_pass(genhexkins, path, genhex_times);
      time_pass(pkmkins, path, pkm_times);
    }
  }
  const std::array<const char*, 3> calls = {"inverse", "forward", "inv+fwd/period"};
  const std::array<Summary, 3> p = {summarise(pkm_times.inverse), summarise(pkm_times.forward),
                                    summarise(pkm_times.period)};
  const std::array<Summary, 3> g = {summarise(genhex_times.inverse), summarise(genhex_times.forward),
                                    summarise(genhex_times.period)};
  const double reading_ns = clock_reading_ns();
  std::printf(
      "\nper call, %d passes x %zu samples (1 kHz path), modules alternating per pass; steady_clock, one "
      "reading "
      "%.0f ns (included once in each time)\n",
      kPasses, kSamples, reading_ns);
  std::printf("%-11s %-15s %10s %10s %10s\n", "module", "call", "mean ns", "p99.9 ns", "worst ns");
  for (const auto& [name, s] : {std::pair{"pkmkins", p}, std::pair{"genhexkins", g}}) {
    for (std::size_t c = 0; c < calls.size(); ++c) {
      std::printf("%-11s %-15s %10.0f %10.0f %10.0f\n", name, calls[c], s[c].mean, s[c].p99_9, s[c].worst);
    }
  }
  // The last column takes the clock reading out of both means: it weighs on the short calls' ratio.
  std::printf("\n%-15s %11s %11s %11s %16s\n", "pkmkins/genhex", "mean", "p99.9", "worst", "mean - reading");
  for (std::size_t c = 0; c < calls.size(); ++c) {
    std::printf("%-15s %11.3f %11.3f %11.3f %16.3f\n", calls[c], p[c].mean / g[c].mean,
                p[c].p99_9 / g[c].p99_9, p[c].worst / g[c].worst,
                (p[c].mean - reading_ns) / (g[c].mean - reading_ns));
  }
  std::printf("\n");
}

// ---------------------------------------------------------------------------------------------------------------
// The hot IK side by side: genhexkins' kinematicsInverse and Mechanism::actuator_values_at, each over the
// whole path as one timed block, the two alternating block by block (a noisy stretch of a shared machine hits
// both alike). The per-call time of a block is its time over the samples; the medians of the blocks are
// compared.
constexpr int kHotBlocks = 21;

double median_of(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

double genhexkins_block_ns(const KinsModule& genhexkins, const std::vector<EmcPose>& path) {
  const KinsFlags iflags = 0;
  KinsFlags out_flags = 0;
  double joints[kJoints];
  const Clock::time_point start = Clock::now();
  for (const EmcPose& world : path) {
    if (genhexkins.inverse(&world, joints, &iflags, &out_flags) != 0) fail("genhexkins: inverse failed");
    benchmark::DoNotOptimize(joints);
  }
  return static_cast<double>(ns_between(start, Clock::now())) / static_cast<double>(path.size());
}

double interface_block_ns(const pkm::Mechanism& mechanism, const std::vector<EmcPose>& path) {
  double joints[kJoints];
  const Clock::time_point start = Clock::now();
  for (const EmcPose& world : path) {
    if (!interface_inverse(mechanism, world, joints)) fail("Mechanism::actuator_values_at failed");
    benchmark::DoNotOptimize(joints);
  }
  return static_cast<double>(ns_between(start, Clock::now())) / static_cast<double>(path.size());
}

void print_hot_inverse(const KinsModule& genhexkins, const pkm::Mechanism& mechanism,
                       const std::vector<EmcPose>& path) {
  std::vector<double> genhex_ns, interface_ns;
  for (int block = 0; block < kHotBlocks; ++block) {
    if (block % 2 == 0) {
      genhex_ns.push_back(genhexkins_block_ns(genhexkins, path));
      interface_ns.push_back(interface_block_ns(mechanism, path));
    } else {
      interface_ns.push_back(interface_block_ns(mechanism, path));
      genhex_ns.push_back(genhexkins_block_ns(genhexkins, path));
    }
  }
  const double g = median_of(genhex_ns), p = median_of(interface_ns);
  std::printf(
      "hot IK side by side, %d blocks x %zu samples each, alternating; per call, median (fastest) of the "
      "blocks:\n",
      kHotBlocks, kSamples);
  std::printf("  genhexkins kinematicsInverse          %7.1f ns (%.1f)\n", g,
              *std::min_element(genhex_ns.begin(), genhex_ns.end()));
  std::printf("  Mechanism::actuator_values_at (pkm)   %7.1f ns (%.1f)\n", p,
              *std::min_element(interface_ns.begin(), interface_ns.end()));
  std::printf("  genhexkins / pkm                      %7.2f x\n\n", g / p);
}

// ---------------------------------------------------------------------------------------------------------------
// Google Benchmarks: one call per iteration along the path.
void BM_Inverse(benchmark::State& state, KinsModule* m, const std::vector<EmcPose>* path) {
  const KinsFlags iflags = 0;
  KinsFlags fflags = 0;
  double joints[kJoints];
  std::size_t k = 0;
  for (auto _ : state) {
    if (m->inverse(&(*path)[k], joints, &iflags, &fflags) != 0) {
      state.SkipWithError("inverse kinematics failed");
      break;
    }
    benchmark::DoNotOptimize(joints);
    k = k + 1 == kSamples ? 0 : k + 1;
  }
}

void BM_InterfaceInverse(benchmark::State& state, const pkm::Mechanism* mechanism,
                         const std::vector<EmcPose>* path) {
  double joints[kJoints];
  std::size_t k = 0;
  for (auto _ : state) {
    if (!interface_inverse(*mechanism, (*path)[k], joints)) {
      state.SkipWithError("Mechanism::actuator_values_at failed");
      break;
    }
    benchmark::DoNotOptimize(joints);
    k = k + 1 == kSamples ? 0 : k + 1;
  }
}

void BM_Forward(benchmark::State& state, KinsModule* m) {
  const KinsFlags fflags = 0;
  KinsFlags iflags = 0;
  for (auto _ : state) {
    if (m->forward(m->joints[next_sample(*m)].data(), &m->feedback, &fflags, &iflags) != 0) {
      state.SkipWithError("forward kinematics failed");
      break;
    }
    benchmark::DoNotOptimize(m->feedback);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  KinsModule pkmkins, genhexkins;
  try {
    genhexkins = load_genhexkins();
    pkmkins = load_pkmkins();
    const std::unique_ptr<pkm::Machine> machine = load_interface_machine();
    const pkm::Mechanism& mechanism = *machine->mechanism;
    const std::vector<EmcPose> path = servo_path();
    start_forward(pkmkins, path.front());
    start_forward(genhexkins, path.front());
    verify(pkmkins, genhexkins, mechanism, path);
    print_table(pkmkins, genhexkins, path);
    print_hot_inverse(genhexkins, mechanism, path);

    for (KinsModule* m : {&pkmkins, &genhexkins}) {
      benchmark::RegisterBenchmark((std::string("BM_Inverse/") + m->name).c_str(), BM_Inverse, m, &path);
    }
    benchmark::RegisterBenchmark("BM_Inverse/pkm_actuator_values", BM_InterfaceInverse, &mechanism, &path);
    for (KinsModule* m : {&pkmkins, &genhexkins}) {
      benchmark::RegisterBenchmark((std::string("BM_Forward/") + m->name).c_str(), BM_Forward, m);
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "linuxcnc_kins_bench: %s\n", e.what());
    return 1;
  }
  unload(pkmkins);
  unload(genhexkins);
  return 0;
}
