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
// CLOCK_REALTIME "now" of the tests; commands are stamped with it unless a test says otherwise
constexpr int64_t kNow = 1'700'000'000'000'000'000;

JointLimits limits() {
  JointLimits l;
  for (size_t i = 0; i < kJoints; ++i) {
    l.q_min_rad[i] = -1.0 - 0.1 * static_cast<double>(i);
    l.q_max_rad[i] = 1.0 + 0.1 * static_cast<double>(i);
  }
  l.max_velocity_radps = 2.0;
  l.max_stiffness_nm_per_rad = 500.0;
  l.max_damping_nms_per_rad = 50.0;
  l.max_torque_nm = JointLimits::filled(10.0);
  return l;
}

// a command well inside every limit
msg::JointCommand valid_command(uint64_t seq) {
  msg::JointCommand c;
  c.header().seq(seq);
  c.header().stamp_ns(kNow);
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
  EXPECT_EQ(std::string(to_string(CommandIssue::kUnknownMode)), "rejected_unknown_mode");
  EXPECT_EQ(std::string(to_string(CommandIssue::kPositionLimit)), "clamped_position");
  EXPECT_EQ(std::string(to_string(CommandIssue::kVelocityLimit)), "clamped_velocity");
  EXPECT_EQ(std::string(to_string(CommandIssue::kGainLimit)), "clamped_gain");
  EXPECT_EQ(std::string(to_string(CommandIssue::kTorqueLimit)), "clamped_torque");
}

TEST(CommandValidator, AcceptsValidCommandUnchanged) {
  CommandValidator v(kJoints, limits());
  const msg::JointCommand cmd = valid_command(1);
  ValidCommand out = marked();
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kAccepted);
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kAccepted);
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
        EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected) << f.name << "[" << joint << "] = " << bad;
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
      EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected) << f.name << " of size " << size;
      expect_untouched(out);
      ++expected_rejects;
    }
  }
  // the mode sequence too
  for (size_t size : {size_t{0}, kJoints + 1}) {
    msg::JointCommand cmd = valid_command(++seq);
    cmd.mode().resize(size, msg::CONTROL_GRAVITY);
    ValidCommand out;
    EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected) << "mode of size " << size;
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kWrongSize), 1u);
  EXPECT_EQ(v.count(CommandIssue::kNonFinite), 0u);
}

TEST(CommandValidator, RejectsDuplicateAndOlderSequenceNumbers) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(10), kNow, out), CommandVerdict::kAccepted);
  msg::JointCommand dup = valid_command(10);
  dup.q_des_rad({0.9, 0.9, 0.9});
  out = marked();
  EXPECT_EQ(v.validate(dup, kNow, out), CommandVerdict::kRejected);
  expect_untouched(out);
  out = marked();
  EXPECT_EQ(v.validate(valid_command(9), kNow, out), CommandVerdict::kRejected);
  expect_untouched(out);
  EXPECT_EQ(v.validate(valid_command(1), kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 3u);
  EXPECT_EQ(v.rejected(), 3u);
  // a newer one is accepted again, also after a gap
  EXPECT_EQ(v.validate(valid_command(15), kNow, out), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_command(16), kNow, out), CommandVerdict::kAccepted);
  EXPECT_EQ(v.rejected(), 3u);
}

TEST(CommandValidator, RejectsSequenceZeroAsNotNewer) {
  // the first sample of a writer is 1; 0 can only come from an unstamped command
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  EXPECT_EQ(v.validate(valid_command(0), kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 1u);
}

TEST(CommandValidator, RejectedCommandDoesNotAdvanceTheSequence) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(1), kNow, out), CommandVerdict::kAccepted);
  msg::JointCommand bad = valid_command(5);
  bad.tau_ff_nm()[0] = kNan;
  EXPECT_EQ(v.validate(bad, kNow, out), CommandVerdict::kRejected);
  // 2..4 are still newer than the last accepted one (1)
  EXPECT_EQ(v.validate(valid_command(2), kNow, out), CommandVerdict::kAccepted);
}

TEST(CommandValidator, ClampedCommandAdvancesTheSequence) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  msg::JointCommand cmd = valid_command(3);
  cmd.q_des_rad()[0] = 5.0;
  ASSERT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
  EXPECT_EQ(v.validate(valid_command(3), kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 1u);
}

TEST(CommandValidator, ClampsPositionToJointLimitsAndCountsEachJoint) {
  CommandValidator v(kJoints, limits());
  msg::JointCommand cmd = valid_command(1);
  cmd.q_des_rad({5.0, -7.0, 0.3});  // joint 0 above 1.0, joint 1 below -1.1, joint 2 fine
  ValidCommand out;
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
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
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kClamped);
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
    EXPECT_EQ(v.validate(clamped, kNow, out), CommandVerdict::kClamped);
    msg::JointCommand nan = valid_command(++seq);
    nan.q_des_rad()[1] = kNan;
    EXPECT_EQ(v.validate(nan, kNow, out), CommandVerdict::kRejected);
    EXPECT_EQ(v.validate(valid_command(++seq), kNow, out), CommandVerdict::kAccepted);
  }
  EXPECT_EQ(v.count(CommandIssue::kTorqueLimit), 10u);
  EXPECT_EQ(v.count(CommandIssue::kNonFinite), 10u);
  EXPECT_EQ(v.rejected(), 10u);
}


TEST(CommandValidator, RejectsCommandsStampedTooLongAgoOrTooFarAhead) {
  JointLimits l = limits();
  l.max_command_age_s = 0.2;
  CommandValidator v(kJoints, l);
  ValidCommand out = marked();
  msg::JointCommand old = valid_command(1);
  old.header().stamp_ns(kNow - 300'000'000);
  EXPECT_EQ(v.validate(old, kNow, out), CommandVerdict::kRejected);
  msg::JointCommand ahead = valid_command(2);
  ahead.header().stamp_ns(kNow + 300'000'000);  // a sender whose clock runs ahead
  EXPECT_EQ(v.validate(ahead, kNow, out), CommandVerdict::kRejected);
  expect_untouched(out);
  EXPECT_EQ(v.count(CommandIssue::kStale), 2u);
  msg::JointCommand recent = valid_command(3);
  recent.header().stamp_ns(kNow - 150'000'000);
  EXPECT_EQ(v.validate(recent, kNow, out), CommandVerdict::kAccepted);
}

TEST(CommandValidator, AcceptsAnyAgeWhenTheCheckIsOff) {
  JointLimits l = limits();
  l.max_command_age_s = kInf;  // `off` in the file
  CommandValidator v(kJoints, l);
  ValidCommand out;
  msg::JointCommand old = valid_command(1);
  old.header().stamp_ns(0);
  EXPECT_EQ(v.validate(old, kNow, out), CommandVerdict::kAccepted);
}

TEST(CommandValidator, RejectsMixedModesAndCartesianModeInAJointCommand) {
  CommandValidator v(kJoints, limits());
  ValidCommand out = marked();
  msg::JointCommand mixed = valid_command(1);
  mixed.mode()[1] = msg::CONTROL_POSITION_PD;
  EXPECT_EQ(v.validate(mixed, kNow, out), CommandVerdict::kRejected);
  msg::JointCommand cartesian = valid_command(2);
  cartesian.mode().assign(kJoints, msg::CONTROL_CARTESIAN_IMPEDANCE);
  EXPECT_EQ(v.validate(cartesian, kNow, out), CommandVerdict::kRejected);
  expect_untouched(out);
  EXPECT_EQ(v.count(CommandIssue::kMixedModes), 2u);
  msg::JointCommand pd = valid_command(3);
  pd.mode().assign(kJoints, msg::CONTROL_POSITION_PD);
  EXPECT_EQ(v.validate(pd, kNow, out), CommandVerdict::kAccepted);
  EXPECT_EQ(out.mode, msg::CONTROL_POSITION_PD);
}

msg::CartesianCommand valid_cartesian(uint64_t seq) {
  msg::CartesianCommand c;
  c.header().seq(seq);
  c.header().stamp_ns(kNow);
  c.target_pose().position_m().x(0.5);
  c.target_pose().position_m().y(-0.1);
  c.target_pose().position_m().z(0.6);
  c.target_pose().orientation().w(0.0);
  c.target_pose().orientation().x(1.0);
  c.stiffness_translational_n_per_m().x(500);
  c.stiffness_translational_n_per_m().y(500);
  c.stiffness_translational_n_per_m().z(500);
  c.stiffness_rotational_nm_per_rad().x(30);
  c.stiffness_rotational_nm_per_rad().y(30);
  c.stiffness_rotational_nm_per_rad().z(30);
  c.damping_ratio(1.0);
  c.nullspace_stiffness_nm_per_rad(5);
  return c;
}

TEST(CommandValidator, AcceptsACartesianCommandAndSetsTheMode) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  EXPECT_EQ(v.validate(valid_cartesian(1), kNow, out), CommandVerdict::kAccepted);
  EXPECT_EQ(out.mode, msg::CONTROL_CARTESIAN_IMPEDANCE);
  EXPECT_EQ(out.x_des_m[0], 0.5);
  EXPECT_EQ(out.orientation_wxyz[1], 1.0);
  EXPECT_EQ(out.translational_stiffness_n_per_m[2], 500.0);
  EXPECT_EQ(out.nullspace_stiffness_nm_per_rad, 5.0);
}

TEST(CommandValidator, RejectsNonFiniteCartesianCommandsAndNonUnitOrientations) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  msg::CartesianCommand nan = valid_cartesian(1);
  nan.target_twist().angular_radps().y(kNan);
  EXPECT_EQ(v.validate(nan, kNow, out), CommandVerdict::kRejected);
  msg::CartesianCommand inf = valid_cartesian(2);
  inf.target_pose().position_m().z(kInf);
  EXPECT_EQ(v.validate(inf, kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kNonFinite), 2u);
  msg::CartesianCommand zero = valid_cartesian(3);
  zero.target_pose().orientation().x(0.0);  // all zero: no rotation at all
  EXPECT_EQ(v.validate(zero, kNow, out), CommandVerdict::kRejected);
  msg::CartesianCommand doubled = valid_cartesian(4);
  doubled.target_pose().orientation().x(2.0);
  EXPECT_EQ(v.validate(doubled, kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kBadOrientation), 2u);
  // rounding off unit is normalised
  msg::CartesianCommand rounded = valid_cartesian(5);
  rounded.target_pose().orientation().x(1.005);
  EXPECT_EQ(v.validate(rounded, kNow, out), CommandVerdict::kAccepted);
  EXPECT_DOUBLE_EQ(out.orientation_wxyz[1], 1.0);
}

TEST(CommandValidator, ClampsCartesianTargetsToTheWorkspaceAndGainsToTheirLimits) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  msg::CartesianCommand far = valid_cartesian(1);
  far.target_pose().position_m().x(5.0);
  far.stiffness_translational_n_per_m().y(1e7);
  far.target_twist().linear_mps().z(-50.0);
  EXPECT_EQ(v.validate(far, kNow, out), CommandVerdict::kClamped);
  EXPECT_EQ(out.x_des_m[0], limits().workspace_max_m[0]);
  EXPECT_EQ(out.translational_stiffness_n_per_m[1], limits().max_translational_stiffness_n_per_m);
  EXPECT_EQ(out.twist_des[2], -limits().max_linear_velocity_mps);
  EXPECT_EQ(v.count(CommandIssue::kWorkspaceLimit), 1u);
  EXPECT_EQ(v.count(CommandIssue::kGainLimit), 1u);
  EXPECT_EQ(v.count(CommandIssue::kVelocityLimit), 1u);
}

TEST(CommandValidator, TracksCartesianSequenceNumbersApartFromJointOnes) {
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(100), kNow, out), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_cartesian(1), kNow, out), CommandVerdict::kAccepted) << "another writer, its own numbers";
  EXPECT_EQ(v.validate(valid_cartesian(1), kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 1u);
}

TEST(CommandValidator, ComparesSequenceNumbersWithinASessionOnly) {
  // a restarted leader numbers from 1 again: its first command is taken, its predecessor's
  // numbers do not count against it
  CommandValidator v(kJoints, limits());
  ValidCommand out;
  ASSERT_EQ(v.validate(valid_command(8000), kNow, out, 1), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_command(1), kNow, out, 2), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_command(2), kNow, out, 2), CommandVerdict::kAccepted);
  EXPECT_EQ(v.validate(valid_command(2), kNow, out, 2), CommandVerdict::kRejected);
  EXPECT_EQ(v.validate(valid_command(0), kNow, out, 3), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kSequenceOld), 2u);
}

TEST(CommandValidator, RejectsAndCountsAControlModeOutsideTheEnum) {
  CommandValidator v(kJoints, limits());
  ValidCommand out = marked();
  msg::JointCommand cmd = valid_command(1);
  cmd.mode()[1] = static_cast<msg::ControlMode>(77);
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected);
  expect_untouched(out);
  cmd.mode().assign(kJoints, static_cast<msg::ControlMode>(-1));
  EXPECT_EQ(v.validate(cmd, kNow, out), CommandVerdict::kRejected);
  EXPECT_EQ(v.count(CommandIssue::kUnknownMode), 2u);
  EXPECT_EQ(v.count(CommandIssue::kMixedModes), 0u);
}

}  // namespace
}  // namespace teleop::follower
