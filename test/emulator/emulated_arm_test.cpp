// The emulated arm of CiA 402 torque drives (teleop::emulator) turning the MuJoCo arm of the
// stiff-wall scene, driven by the follower's `hardware: canopen` over four virtual buses (two
// drives each, 1 kHz): the drives carry the arm's weight only through their torque, the quick stop
// holds it with their own position loops, and the master's torque reaches the joints.
#include "teleop/emulator/emulated_arm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "canopen_hardware.h"
#include "teleop/can/virtual_can_bus.h"
#include "teleop/robot/mujoco_hardware.h"

namespace teleop::emulator {
namespace {

robot::MujocoHardwareConfig wall_scene(bool gravity_compensated) {
  robot::MujocoHardwareConfig c;
  c.model_path = std::string(TELEOP_SOURCE_DIR) + "/config/models/scene_wall.xml";
  c.keyframe = "facing_wall";
  c.period_s = 1e-3;
  c.gravity_compensated = gravity_compensated;
  return c;
}

// a Panda-sized arm of drives: gear 100 at 90 %, 16-bit encoders, the Panda's largest torques
robot::CanopenHardwareConfig arm_of_drives() {
  robot::CanopenHardwareConfig config;
  const double max_torque_nm[7] = {87, 87, 87, 87, 12, 12, 12};
  for (int k = 0; k < 7; ++k) {
    robot::CanopenJointConfig j;
    j.bus = "can" + std::to_string(k / 2);
    j.node = static_cast<uint8_t>(k + 1);
    j.axis.gear_ratio = 100.0;
    j.axis.gear_efficiency = 0.9;
    j.axis.encoder_ticks_per_rev = 65536.0;
    j.axis.rated_torque_nm = max_torque_nm[k] / (100.0 * 0.9) / 2.0;  // rated: half the largest
    j.axis.max_torque_nm = max_torque_nm[k];
    config.joints.push_back(j);
  }
  return config;
}

class ArmRig {
 public:
  ArmRig() : arm_(wall_scene(false)), gravity_(wall_scene(true)), config_(arm_of_drives()) {
    for (int b = 0; b < 4; ++b) {
      buses_.push_back(std::make_unique<can::VirtualCanBus>());
      masters_.push_back(buses_.back()->open("master"));
    }
    std::vector<can::CanBus*> endpoints;
    for (const robot::CanopenJointConfig& j : config_.joints) {
      endpoints_.push_back(buses_[static_cast<size_t>(j.bus.back() - '0')]->open("drive"));
      endpoints.push_back(endpoints_.back().get());
    }
    emulated_ = std::make_unique<EmulatedArm>(arm_, 1e-3, config_, endpoints);
    emulated_->step(1e-3);  // powered on
  }
  std::unique_ptr<robot::CanopenHardware> start() {
    robot::SdoWait wait;
    wait.pump = [this] { step(); };
    std::vector<can::CanBus*> masters;
    for (auto& m : masters_) masters.push_back(m.get());
    return std::make_unique<robot::CanopenHardware>(config_, 1e-3, masters, wait, [this] { return now_ns_; });
  }
  void step() {
    emulated_->step(1e-3);
    now_ns_ += 1'000'000;
  }
  /// g(q) at the emulated arm's pose, as the compensated twin of the scene adds it.
  JointVector gravity_at(const JointVector& q) {
    gravity_.place(q);
    (void)gravity_.write(JointVector{});
    robot::ArmState s;
    (void)gravity_.read(s);
    return s.tau_measured_nm;
  }
  const robot::ArmState& truth() const { return emulated_->plant().state(); }
  EmulatedArm& emulated() { return *emulated_; }

 private:
  robot::MujocoHardware arm_;
  robot::MujocoHardware gravity_;
  robot::CanopenHardwareConfig config_;
  std::vector<std::unique_ptr<can::VirtualCanBus>> buses_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> masters_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::unique_ptr<EmulatedArm> emulated_;
  int64_t now_ns_ = 0;
};

double largest_move(const robot::ArmState& a, const robot::ArmState& b) {
  double moved = 0.0;
  for (size_t j = 0; j < 7; ++j) moved = std::max(moved, std::abs(a.q_rad[j] - b.q_rad[j]));
  return moved;
}

TEST(EmulatedArm, TheDrivesHoldTheArmAgainstGravityAndTheMastersTorqueMovesIt) {
  ArmRig rig;
  const robot::ArmState start = rig.truth();
  auto hw = rig.start();  // configured, enabled, holding in the quick stop
  robot::ArmState state;
  // held by the drives' own position loops for a second
  for (int i = 0; i < 1000; ++i) {
    ASSERT_NE(hw->read(state), robot::HardwareStatus::kFault) << "cycle " << i;
    ASSERT_EQ(hw->hold(), robot::HardwareStatus::kOk);
    rig.step();
  }
  EXPECT_LT(largest_move(rig.truth(), start), 0.01);
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(state.q_rad[j], rig.truth().q_rad[j], 1e-3) << j;
  // the master's g(q) carries it: the drives resumed, the weight is on their torque
  const robot::ArmState before = rig.truth();
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(hw->read(state), robot::HardwareStatus::kOk) << i;
    ASSERT_EQ(hw->write(rig.gravity_at(state.q_rad)), robot::HardwareStatus::kOk);
    rig.step();
  }
  EXPECT_LT(largest_move(rig.truth(), before), 0.02);
  for (size_t k = 0; k < 7; ++k) {
    EXPECT_EQ(rig.emulated().drives().drive(k).state(), can::cia402::State::kOperationEnabled) << k;
  }
  EXPECT_GT(std::abs(state.tau_measured_nm[1]), 5.0) << "the shoulder carries the arm";
  // without it, the arm falls: the torque path is the only thing holding it
  const robot::ArmState carried = rig.truth();
  for (int i = 0; i < 200; ++i) {
    (void)hw->read(state);
    (void)hw->write(JointVector{});
    rig.step();
  }
  EXPECT_GT(largest_move(rig.truth(), carried), 0.05);
}

}  // namespace
}  // namespace teleop::emulator
