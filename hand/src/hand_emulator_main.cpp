// teleop_hand_emulator: the hand's motor controllers as a process on a SocketCAN interface.
// Runs N EmulatedDrives (one raw socket each, filtered to the frames addressed to its node),
// stepped in real time, so that a CANopen master, candump or cansend can talk to them:
//   teleop_hand_emulator --interface vcan0 [--nodes 1-9] [--rate 1000] [--duration 0]
//                        [--inject SECONDS:NODE:KIND[:VALUE] ...]   (fault_schedule.h)
//                        [--plant motor|mujoco] [--model FILE] [--keyframe NAME]
//                        [--sim-log FILE]
// --plant motor (default): each drive turns its own DC-motor link between hard stops.
// --plant mujoco: the drives turn the MuJoCo hand (node n = motor n-1, so nodes 1-9), by default
// config/models/svh_hand_grasp.xml with its object; SIGUSR1 releases the object's support.
// --duration 0 runs until SIGINT / SIGTERM. Prints one status line per node at exit.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "emulator/sim_log.h"
#include "teleop/can/socketcan_bus.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/version.h"
#include "teleop/drive/drive_group.h"
#include "teleop/hand/fault_schedule.h"
#include "teleop/hand/grasp_object.h"
#include "teleop/hand/mujoco_drive_plants.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
volatile std::sig_atomic_t g_release = 0;
void on_signal(int) { g_stop = 1; }
void on_release(int) { g_release = 1; }

constexpr const char* kDefaultModel = "config/models/svh_hand_grasp.xml";
constexpr double kSimLogIntervalS = 0.02;

// The MuJoCo hand as the drives' plant, its actuators' limit the most a drive's motor can give:
// the winding's stall current through k_t, the gearbox and its efficiency (so MuJoCo never clamps
// a torque a drive makes).
std::unique_ptr<teleop::hand::MujocoDrivePlants> load_mujoco_hand(const std::string& path, const std::string& keyframe,
                                                                  const teleop::drive::EmulatedDriveConfig& drive) {
  teleop::sim::MujocoModel model = teleop::sim::MujocoModel::load(path);
  if (!keyframe.empty()) model.reset(keyframe);
  const teleop::drive::EmulatedMotorParams& m = drive.motor;
  const double stall_torque_nm =
      m.supply_v / m.resistance_ohm * m.torque_constant_nm_per_a * m.gear_ratio * m.gear_efficiency;
  return std::make_unique<teleop::hand::MujocoDrivePlants>(
      teleop::hand::HandPlant(std::move(model), teleop::hand::HandCoupling::svh()), stall_torque_nm);
}

int64_t now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1000000000LL + t.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_hand_emulator: the hand's CANopen motor controllers on a SocketCAN interface"};
  app.set_version_flag("--version", teleop::version_text());
  std::string interface;
  std::string nodes = "1-9";
  double rate_hz = 1000.0;
  double duration_s = 0.0;
  std::vector<std::string> inject;
  std::string plant_kind = "motor";
  std::string model_path;
  std::string keyframe;
  std::string sim_log_path;
  app.add_option("--interface", interface, "SocketCAN interface (vcan0, can0)")->required();
  app.add_option("--nodes", nodes, "node ids FIRST-LAST (or one id)");
  app.add_option("--rate", rate_hz, "drive step rate [Hz]")->check(CLI::Range(1.0, 20000.0));
  app.add_option("--duration", duration_s, "run time [s], 0 = until SIGINT/SIGTERM")->check(CLI::NonNegativeNumber);
  app.add_option("--inject", inject,
                 "fault at a time: SECONDS:NODE:KIND[:VALUE], KIND = heartbeat-stop|heartbeat-resume|emcy:CODE|"
                 "stall|free|drop-tpdo[:N]|tpdo-resume|drop-rpdo[:N]|rpdo-resume|refuse-sdo|accept-sdo|bus-off|"
                 "restarted (repeatable)");
  app.add_option("--plant", plant_kind,
                 "what the motors turn: motor (each drive its own DC-motor link) or mujoco (the MuJoCo hand, "
                 "nodes 1-9 = motors 0-8)")
      ->check(CLI::IsMember({"motor", "mujoco"}));
  app.add_option("--model", model_path,
                 std::string("MuJoCo hand model for --plant mujoco (default ") + kDefaultModel +
                     "; SIGUSR1 releases its object's support)");
  app.add_option("--keyframe", keyframe, "start the MuJoCo model from this keyframe");
  app.add_option("--sim-log", sim_log_path, "CSV of the MuJoCo hand's state every 20 ms (joints, object, torques)");
  CLI11_PARSE(app, argc, argv);
  const bool mujoco = plant_kind == "mujoco";
  if (!mujoco && (!model_path.empty() || !keyframe.empty() || !sim_log_path.empty())) {
    std::fprintf(stderr, "teleop_hand_emulator: --model, --keyframe and --sim-log need --plant mujoco\n");
    return 2;
  }
  const auto dash = nodes.find('-');
  const int first = std::atoi(nodes.substr(0, dash).c_str());
  const int last = dash == std::string::npos ? first : std::atoi(nodes.substr(dash + 1).c_str());
  if (first < 1 || last > 127 || first > last) {
    std::fprintf(stderr, "teleop_hand_emulator: --nodes %s: need FIRST-LAST within 1-127\n", nodes.c_str());
    return 2;
  }
  if (mujoco && last > static_cast<int>(teleop::hand::kHandMotors)) {
    std::fprintf(stderr, "teleop_hand_emulator: --nodes %s: the MuJoCo hand's nodes are 1-9 (node n turns motor n-1)\n",
                 nodes.c_str());
    return 2;
  }
  std::vector<teleop::hand::ScheduledFault> faults;
  try {
    for (const std::string& spec : inject) {
      faults.push_back(teleop::hand::parse_fault_spec(spec));
      if (faults.back().node < first || faults.back().node > last) {
        throw std::invalid_argument("fault '" + spec + "': node is not emulated here");
      }
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "teleop_hand_emulator: %s\n", e.what());
    return 2;
  }
  std::sort(faults.begin(), faults.end(), [](const auto& a, const auto& b) { return a.at_s < b.at_s; });

  std::vector<std::unique_ptr<teleop::can::SocketCanBus>> buses;
  std::unique_ptr<teleop::hand::MujocoDrivePlants> plants;
  std::unique_ptr<teleop::hand::GraspObject> object;
  std::unique_ptr<teleop::hand::emulator::SimLog> sim_log;
  std::unique_ptr<teleop::drive::DriveGroup> hand;
  try {
    std::vector<teleop::drive::DriveGroupNode> drive_nodes;
    for (int node = first; node <= last; ++node) {
      teleop::can::SocketCanOptions options;
      options.filters = teleop::can::canopen_node_filters(static_cast<uint8_t>(node));
      // every RPDO2 COB-ID: a master may pack several nodes' targets into one frame on the id
      // of another node (dummy mapping, docs/can_bus_budget.md)
      options.filters.push_back({teleop::can::cob::kRpdo2, 0x780, false});
      buses.push_back(std::make_unique<teleop::can::SocketCanBus>(interface, options));
      teleop::drive::DriveGroupNode n;
      n.bus = buses.back().get();
      n.config.node_id = static_cast<teleop::can::NodeId>(node);
      n.config.serial = static_cast<uint32_t>(node);
      n.channel = static_cast<size_t>(node - 1);
      drive_nodes.push_back(n);
    }
    if (mujoco) {
      if (model_path.empty()) {
        model_path = teleop::find_data(kDefaultModel, kDefaultModel).string();
        if (model_path.empty()) {
          throw std::runtime_error(
              std::string("no ") + kDefaultModel + " in " +
              teleop::data_candidates_text(kDefaultModel, kDefaultModel, teleop::DataRoots::current()));
        }
      }
      plants = load_mujoco_hand(model_path, keyframe, drive_nodes.front().config);
      if (mj_name2id(plants->hand().model(), mjOBJ_BODY, "object") >= 0) {
        object = std::make_unique<teleop::hand::GraspObject>(plants->hand());
      }
      if (!sim_log_path.empty()) {
        sim_log = std::make_unique<teleop::hand::emulator::SimLog>(sim_log_path, kSimLogIntervalS);
      }
    }
    hand = std::make_unique<teleop::drive::DriveGroup>(drive_nodes, plants.get());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_hand_emulator: %s\n", e.what());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGUSR1, on_release);
  std::fprintf(stderr, "teleop_hand_emulator: nodes %d-%d on %s at %.0f Hz, %zu faults scheduled, plant %s%s%s\n",
               first, last, interface.c_str(), rate_hz, faults.size(), plant_kind.c_str(), mujoco ? " " : "",
               mujoco ? model_path.c_str() : "");
  size_t next_fault = 0;

  const int64_t period_ns = static_cast<int64_t>(1e9 / rate_hz);
  const int64_t start = now_ns();
  const int64_t end = duration_s > 0.0 ? start + static_cast<int64_t>(duration_s * 1e9) : INT64_MAX;
  int64_t next = start;
  int64_t last_step = start;
  uint64_t overruns = 0;
  while (g_stop == 0 && next < end) {
    const int64_t t = now_ns();
    // step by the real time elapsed (bounded, so a long stall does not run minutes of physics)
    const double dt = static_cast<double>(std::min<int64_t>(t - last_step, 50 * period_ns)) * 1e-9;
    last_step = t;
    while (next_fault < faults.size() && t - start >= static_cast<int64_t>(faults[next_fault].at_s * 1e9)) {
      const teleop::hand::ScheduledFault& f = faults[next_fault++];
      const size_t i = f.node - static_cast<size_t>(first);
      const auto status = teleop::hand::apply_fault(f, hand->drive(i), *buses[i]);
      std::fprintf(stderr, "teleop_hand_emulator: t=%.3f s: injected %s into node %u: %s\n",
                   static_cast<double>(t - start) * 1e-9, teleop::hand::to_string(f.kind), unsigned{f.node},
                   teleop::can::to_string(status));
    }
    if (g_release != 0) {
      g_release = 0;
      if (object) object->release();
      std::fprintf(stderr, "teleop_hand_emulator: t=%.3f s: SIGUSR1: %s\n", static_cast<double>(t - start) * 1e-9,
                   object ? "the object's support released" : "no object in this plant");
    }
    if (sim_log) {
      // in pieces of the log's interval: a row every 20 ms of simulated time, however much time
      // one wake covers (in a slow VM a wake can cover 200 ms)
      for (double left = dt; left > 0.0; left -= kSimLogIntervalS) {
        hand->step(std::min(left, kSimLogIntervalS));
        sim_log->sample(hand->time_s(), *plants, object.get());
      }
    } else {
      hand->step(dt);
    }
    next += period_ns;
    if (next < now_ns()) {
      ++overruns;
      next = now_ns();
    }
    const timespec wake{static_cast<time_t>(next / 1000000000LL), static_cast<long>(next % 1000000000LL)};
    ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
  }
  for (size_t i = 0; i < hand->drives(); ++i) {
    const teleop::drive::EmulatedDrive& d = hand->drive(i);
    const auto& s = d.stats();
    std::fprintf(stderr, "node %u: nmt %s, rx %llu, tx %llu, sdo %llu, sync %llu\n", unsigned{d.node_id()},
                 teleop::can::to_string(d.nmt_state()), static_cast<unsigned long long>(s.frames_received),
                 static_cast<unsigned long long>(s.frames_sent), static_cast<unsigned long long>(s.sdo_requests),
                 static_cast<unsigned long long>(s.syncs));
  }
  if (plants) {
    std::fprintf(stderr, "teleop_hand_emulator: %.3f s simulated in %llu MuJoCo steps, %d MuJoCo warnings\n",
                 hand->time_s(), static_cast<unsigned long long>(hand->plant_steps()),
                 plants->hand().mujoco_warnings());
  }
  std::fprintf(stderr, "teleop_hand_emulator: %llu cycle overruns\n", static_cast<unsigned long long>(overruns));
  return 0;
}
