#include "drive_config.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "teleop/can/cia301.h"

namespace teleop::drive {

namespace {

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

void validate(const EmulatedDriveConfig& config) {
  const EmulatedMotorParams& m = config.motor;
  const EmulatedControllerParams& c = config.control;
  if (!can::valid_node(config.node_id)) {
    throw std::invalid_argument("EmulatedDrive: node id " + std::to_string(config.node_id) + " is not in 1..127");
  }
  if (!positive_finite(m.supply_v) || !positive_finite(m.resistance_ohm) || !positive_finite(m.inductance_h) ||
      !positive_finite(m.torque_constant_nm_per_a) || !positive_finite(m.rotor_inertia_kgm2) ||
      !positive_finite(m.gear_ratio) || !positive_finite(m.gear_efficiency) || !positive_finite(m.link_inertia_kgm2) ||
      !positive_finite(m.encoder_ticks_per_rev) || !(m.viscous_nms_per_rad >= 0) ||
      !(m.stop_stiffness_nm_per_rad >= 0) || !(m.stop_damping_nms_per_rad >= 0)) {
    throw std::invalid_argument("EmulatedDrive: motor parameters must be positive and finite");
  }
  if (!(m.stop_min_rad < m.stop_max_rad)) throw std::invalid_argument("EmulatedDrive: stop_min_rad >= stop_max_rad");
  if (!(config.initial_position_rad >= m.stop_min_rad && config.initial_position_rad <= m.stop_max_rad)) {
    throw std::invalid_argument("EmulatedDrive: initial_position_rad outside the hard stops");
  }
  if (!positive_finite(c.substep_s) || c.substep_s > 1e-3 || c.position_loop_divider == 0) {
    throw std::invalid_argument("EmulatedDrive: substep_s must be in (0, 1 ms], position_loop_divider >= 1");
  }
  if (!positive_finite(c.max_reference_velocity_radps) || !positive_finite(c.velocity_filter_hz) ||
      !(c.position_kp_a_per_rad >= 0) || !(c.position_ki_a_per_rad_s >= 0) || !(c.position_kd_a_s_per_rad >= 0) ||
      !(c.position_integral_limit_a >= 0) || !(c.current_kp_v_per_a >= 0) || !(c.current_ki_v_per_a_s >= 0)) {
    throw std::invalid_argument("EmulatedDrive: controller gains must be finite and >= 0");
  }
  if (!positive_finite(config.rated_current_a) || !positive_finite(config.peak_current_a) ||
      !(config.max_current_a >= 0) || config.max_current_a > config.peak_current_a) {
    throw std::invalid_argument("EmulatedDrive: need rated, peak > 0 and 0 <= max_current_a <= peak_current_a");
  }
  if (!(config.following_error_window_rad > 0) || !(config.fault_reaction_time_s >= 0)) {
    throw std::invalid_argument("EmulatedDrive: following_error_window_rad > 0, fault_reaction_time_s >= 0");
  }
  if (config.abort_connection_option < can::cia402::abort_connection::kNoAction ||
      config.abort_connection_option > can::cia402::abort_connection::kQuickStop) {
    throw std::invalid_argument("EmulatedDrive: abort_connection_option must be 0..3 (CiA 402 0x6007)");
  }
}

}  // namespace teleop::drive
