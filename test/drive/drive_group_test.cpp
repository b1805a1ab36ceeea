// DriveGroup: drives on their own links, or in lock-step with a shared plant (a fake here;
// the MuJoCo hand in mujoco_hand_adapter_test.cpp).
#include "teleop/drive/drive_group.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "teleop/can/virtual_can_bus.h"

namespace teleop::drive {
namespace {

// Records what the drives apply: time and torque per channel between steps.
class FakeSharedPlant final : public SharedDrivePlant {
 public:
  class Channel final : public DrivePlant {
   public:
    double position_rad() const override { return 0.0; }
    double velocity_radps() const override { return 0.0; }
    void apply(double, double dt_s, bool) override { applied_s += dt_s; }
    double applied_s = 0.0;
  };
  explicit FakeSharedPlant(size_t n) : channels_(n) {}
  size_t channels() const override { return channels_.size(); }
  DrivePlant& channel(size_t k) override { return channels_[k]; }
  double step_s() const override { return 1e-3; }
  void step() override {
    // every drive has applied its torque for exactly one step when the plant steps
    for (const Channel& c : channels_) applied_per_step.push_back(c.applied_s);
    for (Channel& c : channels_) c.applied_s = 0.0;
    ++steps;
  }
  std::vector<Channel> channels_;
  std::vector<double> applied_per_step;
  int steps = 0;
};

struct Buses {
  can::VirtualCanBus bus;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints;
  std::vector<DriveGroupNode> nodes(size_t n) {
    std::vector<DriveGroupNode> out;
    for (size_t k = 0; k < n; ++k) {
      endpoints.push_back(bus.open("drive"));
      DriveGroupNode node;
      node.bus = endpoints.back().get();
      node.config.node_id = static_cast<can::NodeId>(k + 1);
      node.channel = k;
      out.push_back(node);
    }
    return out;
  }
};

TEST(DriveGroup, DrivesAndASharedPlantAdvanceInLockStep) {
  Buses buses;
  FakeSharedPlant plant(3);
  DriveGroup group(buses.nodes(3), &plant);
  group.step(4e-3);
  EXPECT_EQ(plant.steps, 4);
  EXPECT_EQ(group.plant_steps(), 4u);
  for (const double s : plant.applied_per_step) EXPECT_NEAR(s, 1e-3, 1e-12);
  // a part of a step waits for the rest
  group.step(0.6e-3);
  EXPECT_EQ(plant.steps, 4);
  group.step(0.6e-3);
  EXPECT_EQ(plant.steps, 5);
  EXPECT_NEAR(group.time_s(), 5e-3, 1e-12);
  for (size_t i = 0; i < group.drives(); ++i) EXPECT_NEAR(group.drive(i).time_s(), 5e-3, 1e-12);
  // the drives booted (their boot-up went out on the first step)
  for (size_t i = 0; i < group.drives(); ++i) EXPECT_TRUE(group.drive(i).booted());
}

TEST(DriveGroup, WithoutAPlantEachDriveTurnsItsOwnLink) {
  Buses buses;
  DriveGroup group(buses.nodes(2));
  EXPECT_EQ(group.plant(), nullptr);
  group.step(2.5e-3);
  EXPECT_NEAR(group.time_s(), 2.5e-3, 1e-12);
  EXPECT_NEAR(group.drive(1).time_s(), 2.5e-3, 1e-12);
  EXPECT_EQ(group.plant_steps(), 0u);
}

TEST(DriveGroup, RefusesChannelsThePlantDoesNotHaveOrThatTwoDrivesTurn) {
  Buses buses;
  FakeSharedPlant plant(2);
  auto nodes = buses.nodes(3);
  EXPECT_THROW(DriveGroup(nodes, &plant), std::invalid_argument);  // channel 2 of 2
  nodes.resize(2);
  nodes[1].channel = 0;
  EXPECT_THROW(DriveGroup(nodes, &plant), std::invalid_argument);  // channel 0 twice
  nodes[1].bus = nullptr;
  EXPECT_THROW(DriveGroup(nodes, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::drive
