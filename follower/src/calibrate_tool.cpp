#include "teleop/follower/calibrate_tool.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "calibration_file.h"
#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/output_file.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/follower/follower_config.h"
#include "teleop/follower/payload_calibration.h"
#include "teleop/runtime/node_config.h"
#include "teleop/runtime/shutdown_signal.h"

namespace teleop::follower {
namespace {

struct Setup {
  FollowerConfig follower;
  double rate_hz = 1000.0;
  std::string out_path;
};

Setup read_setup(const CalibrateOptions& options, const robot::HardwareRegistry& hardware) {
  ConfigNode root = ConfigNode::load_file(resolve_config("nodes", options.config_path));
  for (const std::string& set : options.sets) root.apply_override(set);
  Setup s;
  s.rate_hz = runtime::parse_node_config(root.child("node"), "follower").rate_hz;
  // the model as it is: the calibration measures what it lacks
  s.follower = parse_follower_config(root, hardware, CalibrationUse::kIgnore);
  s.out_path = options.out_path.empty() ? s.follower.calibration_file : options.out_path;
  if (s.out_path.empty()) {
    throw ConfigError(root.file() + ": no follower.calibration.file and no --out: nowhere to write the calibration");
  }
  if (s.follower.calibration_plan.poses.size() < 2) {
    throw ConfigError(root.file() + ": follower.calibration.poses: give the poses to measure (6 or more)");
  }
  check_output_file(s.out_path, "--out");
  return s;
}

// the plan at the node's rate; false when stopped (a signal) or the robot failed
bool drive(PayloadCalibration& calibration, double rate_hz, size_t poses) {
  MonotonicClock clock;
  RatePacer pacer(clock, static_cast<int64_t>(1e9 / rate_hz));
  pacer.start();
  size_t reported = 0;
  while (!runtime::shutdown_requested()) {
    pacer.wait_next();
    if (!calibration.cycle()) return !calibration.robot_failed();
    if (calibration.poses_done() != reported) {
      reported = calibration.poses_done();
      std::printf("teleop_calibrate: pose %zu of %zu measured\n", reported, poses);
      std::fflush(stdout);
    }
  }
  return false;
}

}  // namespace

int run_calibration(const CalibrateOptions& options, const robot::HardwareRegistry& hardware) {
  runtime::install_shutdown_handlers();
  Setup setup;
  try {
    setup = read_setup(options, hardware);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "teleop_calibrate: %s\n", e.what());
    return 2;
  }
  try {
    const double period_s = 1.0 / setup.rate_hz;
    const std::unique_ptr<robot::RobotHardware> robot = setup.follower.hardware->make(period_s);
    ArmControl control(setup.follower.control, period_s);
    const PayloadCalibrationPlan& plan = setup.follower.calibration_plan;
    PayloadCalibration calibration(*robot, control, plan, period_s);
    std::printf("teleop_calibrate: %s, %zu poses, %.0f s at %.0f Hz\n", robot->name(), plan.poses.size(),
                calibration.duration_s(), setup.rate_hz);
    const bool completed = drive(calibration, setup.rate_hz, plan.poses.size());
    (void)robot->hold();
    if (!completed) {
      std::fprintf(stderr, "teleop_calibrate: %s after %zu of %zu poses; nothing written\n",
                   calibration.robot_failed() ? "the robot failed" : "stopped", calibration.poses_done(), plan.poses.size());
      return 1;
    }
    // the fit on the controller's model, the one the follower will correct
    const sim::MujocoModel model = sim::MujocoModel::load(setup.follower.control.model_path);
    control::ArmDynamics dynamics(model.model(), setup.follower.control.ee_site);
    const control::PayloadFit fit = control::identify_payload(dynamics, calibration.samples());
    std::ofstream out(setup.out_path);
    out << calibration_text(fit, robot->name(), plan.poses.size());
    out.close();
    if (!out) throw std::runtime_error("cannot write " + setup.out_path);
    const control::Payload& p = fit.calibration.payload;
    std::printf("teleop_calibrate: payload %.4f kg at [%.4f, %.4f, %.4f] m (residual %.3f Nm rms, conditioning %.3f); wrote %s\n",
                p.mass_kg, p.com_m.x(), p.com_m.y(), p.com_m.z(), fit.residual_rms_nm, fit.conditioning,
                setup.out_path.c_str());
    return 0;
  } catch (const std::exception& e) {  // the robot, the model, a fit the poses cannot support
    std::fprintf(stderr, "teleop_calibrate: %s\n", e.what());
    return 1;
  }
}

}  // namespace teleop::follower
