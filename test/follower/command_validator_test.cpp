#include "teleop/follower/command_validator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>


namespace teleop::follower {
namespace {

constexpr size_t kJoints = 3;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

JointLimits limits() {
  JointLimits l;
  for (size_t i = 0; i < kJoints; ++i) {
    l.q_min_rad[i] = -1.0 - 0.1 * static_cast<double>(i);
    l.q_max_rad[i] = 1.0 + 0.1 * static_cast<double>(i);
  }
  l.max_velocity_radps = 2.0;
  l.max_stiffness_nm_per_rad = 500.0;
  l.max_damping_nms_per_rad = 50.0;
  l.max_torque_nm = 10.0;
  return l;
}

// a command well inside every limit
msg::JointCommand valid_command(uint64_t seq) {
  msg::JointCommand c;
  c.header().seq(seq);
  c.robot("panda");
  c.arm("right");
  c.mode(std::vector<msg::ControlMode>(kJoints, msg::CONTROL_JOINT_IMPEDANCE));
  c.q_des_rad({0.1, -0.2, 0.3});
  c.dq_des_radps({0.5, -0.5, 0.0});
  c.tau_ff_nm({1.0, -2.0, 0.5});
  c.stiffness_nm_per_rad({100.0, 200.0, 300.0});
  c.damping_nms_per_rad({5.0, 10.0, 0.0});
  return c;
}

// the joint fields, by name, for tests that go through each of them
struct Field {
  const char* name;
  std::function<std::vector<double>&(msg::JointCommand&)> get;
};

std::vector<Field> fields() {
  return {
      {"q_des_rad", [](msg::JointCommand& c) -> std::vector<double>& { return c.q_des_rad(); }},
      {"dq_des_radps", [](msg::JointCommand& c) -> std::vector<double>& { return c.dq_des_radps(); }},
      {"tau_ff_nm", [](msg::JointCommand& c) -> std::vector<double>& { return c.tau_ff_nm(); }},
      {"stiffness_nm_per_rad", [](msg::JointCommand& c) -> std::vector<double>& { return c.stiffness_nm_per_rad(); }},
      {"damping_nms_per_rad", [](msg::JointCommand& c) -> std::vector<double>& { return c.damping_nms_per_rad(); }},
  };
}

uint64_t total_count(const CommandValidator& v) {
  uint64_t n = 0;
  for (size_t i = 0; i < static_cast<size_t>(CommandIssue::kCount); ++i) n += v.count(static_cast<CommandIssue>(i));
  return n;
}

// a ValidCommand filled with a marker, to see whether the validator wrote it
ValidCommand marked() {
  ValidCommand out;
  out.q_des_rad.fill(42.0);
  out.dq_des_radps.fill(42.0);
  out.tau_ff_nm.fill(42.0);
  out.stiffness.fill(42.0);
  out.damping.fill(42.0);
  return out;
}

void expect_untouched(const ValidCommand& out) {
  for (size_t i = 0; i < kJoints; ++i) {
    EXPECT_EQ(out.q_des_rad[i], 42.0);
    EXPECT_EQ(out.dq_des_radps[i], 42.0);
    EXPECT_EQ(out.tau_ff_nm[i], 42.0);
    EXPECT_EQ(out.stiffness[i], 42.0);
    EXPECT_EQ(out.damping[i], 42.0);
  }
}

TEST(CommandValidator, NamesEveryIssue) {
  EXPECT_EQ(std::string(to_string(CommandIssue::kWrongSize)), "rejected_wrong_size");
  EXPECT_EQ(std::string(to_string(CommandIssue::kNonFinite)), "rejected_non_finite");
  EXPECT_EQ(std::string(to_string(CommandIssue::kSequenceOld)), "rejected_old_sequence");
  EXPECT_EQ(std::string(to_string(CommandIssue::kPositionLimit)), "clamped_position");
  EXPECT_EQ(std::string(to_string(CommandIssue::kVelocityLimit)), "clamped_velocity");
  EXPECT_EQ(std::string(to_string(CommandIssue::kGainLimit)), "clamped_gain");
  EXPECT_EQ(std::string(to_string(CommandIssue::kTorqueLimit)), "clamped_torque");
}

TEST(CommandValidator, AcceptsValidCommandUnchanged) {
  CommandValidator v(kJoints, limits());
  const msg::JointCommand cmd = valid_command(1);
  ValidCommand out = marked();
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kAccepted);
  for (size_t i = 0; i < kJoints; ++i) {
    EXPECT_EQ(out.q_des_rad[i], cmd.q_des_rad()[i]);
    EXPECT_EQ(out.dq_des_radps[i], cmd.dq_des_radps()[i]);
    EXPECT_EQ(out.tau_ff_nm[i], cmd.tau_ff_nm()[i]);
    EXPECT_EQ(out.stiffness[i], cmd.stiffness_nm_per_rad()[i]);
    EXPECT_EQ(out.damping[i], cmd.damping_nms_per_rad()[i]);
  }
  EXPECT_EQ(v.rejected(), 0u);
  EXPECT_EQ(total_count(v), 0u);
}

TEST(CommandValidator, AcceptsValuesExactlyOnTheLimits) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.q_des_rad({-1.0, 1.1, -1.2});
  cmd.dq_des_radps({2.0, -2.0, 2.0});
  cmd.tau_ff_nm({10.0, -10.0, 0.0});
  cmd.stiffness_nm_per_rad({0.0, 500.0, 0.0});
  cmd.damping_nms_per_rad({50.0, 0.0, 50.0});
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kAccepted);
  EXPECT_EQ(total_count(v), 0u);
  EXPECT_EQ(out.q_des_rad[1], 1.1);
  EXPECT_EQ(out.dq_des_radps[1], -2.0);
}

TEST(CommandValidator, RejectsNanAndInfInEachFieldAndCountsThemAsNonFinite) {
  CommandValidator v(kJoints, limits());
  uint64_t seq = 0;
  uint64_t expected_rejects = 0;
  for (const Field& f : fields()) {
    for (double bad : {kNan, kInf, -kInf}) {
      for (size_t joint = 0; joint < kJoints; ++joint) {
        msg::JointCommand cmd = valid_command(++seq);
        f.get(cmd)[joint] = bad;
        ValidCommand out = marked();
        EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kRejected) << f.name << "[" << joint << "] = " << bad;
        expect_untouched(out);
        ++expected_rejects;
        EXPECT_EQ(v.count(CommandIssue::kNonFinite), expected_rejects) << f.name;
      }
    }
  }
  EXPECT_EQ(v.rejected(), expected_rejects);
  EXPECT_EQ(total_count(v), expected_rejects);  // nothing counted under another reason
}

TEST(CommandValidator, RejectsAndCountsWrongSequenceLengthInEachField) {
  CommandValidator v(kJoints, limits());
  uint64_t seq = 0;
  uint64_t expected_rejects = 0;
  for (const Field& f : fields()) {
    for (size_t size : {size_t{0}, kJoints - 1, kJoints + 1}) {
      msg::JointCommand cmd = valid_command(++seq);
      f.get(cmd).resize(size, 0.0);
      ValidCommand out = marked();
      EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kRejected) << f.name << " of size " << size;
      expect_untouched(out);
      ++expected_rejects;
    }
  }
  // the mode sequence too
  for (size_t size : {size_t{0}, kJoints + 1}) {
    msg::JointCommand cmd = valid_command(++seq);
    cmd.mode().resize(size, msg::CONTROL_GRAVITY);
    ValidCommand out;
    EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kRejected) << "mode of size " << size;
    ++expected_rejects;
  }
  EXPECT_EQ(v.count(CommandIssue::kWrongSize), expected_rejects);
  EXPECT_EQ(v.rejected(), expected_rejects);
  EXPECT_EQ(total_count(v), expected_rejects);
}

TEST(CommandValidator, CountsWrongSizeBeforeNonFiniteWhenBothApply) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.q_des_rad({kNan});
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kWrongSize), 1u);
  EXPECT_EQ(v.count(CommandIssue::kNonFinite), 0u);
}

TEST(CommandValidator, RejectsDuplicateAndOlderSequenceNumbers) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(10), out), CommandVerdict::kAccepted);
  msg::JointCommand dup = valid_command(10);
  dup.q_des_rad({0.9, 0.9, 0.9});
  out = marked();
  EXPECT_EQ(v.validate(dup, out), CommandVerdict::kRejected);
  expect_untouched(out);
  out = marked();
  EXPECT_EQ(v.validate(valid_command(9), out), CommandVerdict::kRejected);
  expect_untouched(out);
  EXPECT_EQ(v.validate(valid_command(1), out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 3u);
  EXPECT_EQ(v.rejected(), 3u);
  // a newer one is accepted again, also after a gap
  EXPECT_EQ(v.validate(valid_command(15), out), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_command(16), out), CommandVerdict::kAccepted);
  EXPECT_EQ(v.rejected(), 3u);
}

TEST(CommandValidator, RejectsSequenceZeroAsNotNewer) {
  // the first sample of a writer is 1; 0 can only come from an unstamped command
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  EXPECT_EQ(v.validate(valid_command(0), out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 1u);
}

TEST(CommandValidator, RejectedCommandDoesNotAdvanceTheSequence) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(1), out), CommandVerdict::kAccepted);
  msg::JointCommand bad = valid_command(5);
  bad.tau_ff_nm()[0] = kNan;
  EXPECT_EQ(v.validate(bad, out), CommandVerdict::kRejected);
  // 2..4 are still newer than the last accepted one (1)
  EXPECT_EQ(v.validate(valid_command(2), out), CommandVerdict::kAccepted);
}

TEST(CommandValidator, ClampedCommandAdvancesTheSequence) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  msg::JointCommand cmd = valid_command(3);
  cmd.q_des_rad()[0] = 5.0;
  ASSERT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(v.validate(valid_command(3), out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 1u);
}

TEST(CommandValidator, ClampsPositionToJointLimitsAndCountsEachJoint) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.q_des_rad({5.0, -7.0, 0.3});  // joint 0 above 1.0, joint 1 below -1.1, joint 2 fine
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.q_des_rad[0], 1.0);
  EXPECT_EQ(out.q_des_rad[1], -1.1);
  EXPECT_EQ(out.q_des_rad[2], 0.3);
  EXPECT_EQ(v.count(CommandIssue::kPositionLimit), 2u);
  EXPECT_EQ(total_count(v), 2u);
  EXPECT_EQ(v.rejected(), 0u);
  // the other fields pass through
  EXPECT_EQ(out.dq_des_radps[0], 0.5);
  EXPECT_EQ(out.tau_ff_nm[1], -2.0);
  EXPECT_EQ(out.stiffness[2], 300.0);
}

TEST(CommandValidator, ClampsVelocitySymmetricallyAndCounts) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.dq_des_radps({3.0, -100.0, 1.5});
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.dq_des_radps[0], 2.0);
  EXPECT_EQ(out.dq_des_radps[1], -2.0);
  EXPECT_EQ(out.dq_des_radps[2], 1.5);
  EXPECT_EQ(v.count(CommandIssue::kVelocityLimit), 2u);
  EXPECT_EQ(total_count(v), 2u);
}

TEST(CommandValidator, ClampsTorqueSymmetricallyAndCounts) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.tau_ff_nm({-10.5, 0.0, 1e6});
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.tau_ff_nm[0], -10.0);
  EXPECT_EQ(out.tau_ff_nm[1], 0.0);
  EXPECT_EQ(out.tau_ff_nm[2], 10.0);
  EXPECT_EQ(v.count(CommandIssue::kTorqueLimit), 2u);
  EXPECT_EQ(total_count(v), 2u);
}

TEST(CommandValidator, ClampsNegativeAndExcessiveGainsAndCounts) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.stiffness_nm_per_rad({-1.0, 600.0, 250.0});
  cmd.damping_nms_per_rad({51.0, 20.0, -0.5});
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.stiffness[0], 0.0);
  EXPECT_EQ(out.stiffness[1], 500.0);
  EXPECT_EQ(out.stiffness[2], 250.0);
  EXPECT_EQ(out.damping[0], 50.0);
  EXPECT_EQ(out.damping[1], 20.0);
  EXPECT_EQ(out.damping[2], 0.0);
  EXPECT_EQ(v.count(CommandIssue::kGainLimit), 4u);
  EXPECT_EQ(total_count(v), 4u);
}

TEST(CommandValidator, CountsEveryClampReasonWhenAllFieldsExceedLimits) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.q_des_rad()[2] = 9.0;
  cmd.dq_des_radps()[2] = 9.0;
  cmd.tau_ff_nm()[2] = -90.0;
  cmd.stiffness_nm_per_rad()[2] = 9000.0;
  cmd.damping_nms_per_rad()[2] = 900.0;
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.q_des_rad[2], 1.2);
  EXPECT_EQ(out.dq_des_radps[2], 2.0);
  EXPECT_EQ(out.tau_ff_nm[2], -10.0);
  EXPECT_EQ(out.stiffness[2], 500.0);
  EXPECT_EQ(out.damping[2], 50.0);
  EXPECT_EQ(v.count(CommandIssue::kPositionLimit), 1u);
  EXPECT_EQ(v.count(CommandIssue::kVelocityLimit), 1u);
  EXPECT_EQ(v.count(CommandIssue::kTorqueLimit), 1u);
  EXPECT_EQ(v.count(CommandIssue::kGainLimit), 2u);
  EXPECT_EQ(v.rejected(), 0u);
}

TEST(CommandValidator, AccumulatesCountsOverManyCommands) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  uint64_t seq = 0;
  for (int i = 0; i < 10; ++i) {
    msg::JointCommand clamped = valid_command(++seq);
    clamped.tau_ff_nm()[0] = 11.0;
    EXPECT_EQ(v.validate(clamped, out), CommandVerdict::kClamped);
    msg::JointCommand nan = valid_command(++seq);
    nan.q_des_rad()[1] = kNan;
    EXPECT_EQ(v.validate(nan, out), CommandVerdict::kRejected);
    EXPECT_EQ(v.validate(valid_command(++seq), out), CommandVerdict::kAccepted);
  }
  EXPECT_EQ(v.count(CommandIssue::kTorqueLimit), 10u);
  EXPECT_EQ(v.count(CommandIssue::kNonFinite), 10u);
  EXPECT_EQ(v.rejected(), 10u);
}

}  // namespace
}  // namespace teleop::follower
