#pragma once
// A recording's joint states as the traces a run leaves (`<node>.csv`, docs/plots.md), so that
// `teleop render` poses the robot from a recording as from a run's folder.

#include <string>
#include <vector>

namespace teleop::tools {

/// Writes into `out_dir` (created) follower.csv from teleop/follower/joint_state, and twin.csv
/// and leader.csv from the twin's and the leader's when the recording has them: columns t_s (since
/// the recording's first message), wall_s (the receive time) and q_<i>; a topic that carries
/// several arms (the box task's) gets <arm>_q_<i> per arm, a row per sample once every arm was
/// seen, each arm's latest joints. Returns the files written. Throws bag::BagError for a recording
/// that cannot be read, std::runtime_error when it holds no follower joint state or a file cannot
/// be written.
std::vector<std::string> write_recording_traces(const std::string& recording, const std::string& out_dir);

}  // namespace teleop::tools
