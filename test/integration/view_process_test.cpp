// `teleop view` and `teleop render` as processes under a virtual display (Xvfb, Mesa's software
// OpenGL; test/support/virtual_display.h), issue 22: the window opens on the demo's follower and
// twin and shows the robot where the camera looks; a follower state published by the test moves
// the picture, a twin state the ghost; a signal or --frames ends it with 0; without a display it
// says so and exits 1; a recorded stiff-wall run becomes an MP4 that ffprobe reads, a recording
// of the bus poses the robot as the live view does. Small
// windows (320 x 240) and few frames: software OpenGL pays for every pixel.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <thread>

#include "process_helpers.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/topics.h"
#include "teleop/view/image.h"
#include "tool_processes.h"
#include "virtual_display.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

// the follower's keyframe facing_wall (config/models/scene_wall.xml)
const std::vector<double> kFacingWall{0, -0.2438, 0, -2.1400, 0, 3.4638, 0.7854};

std::vector<double> turned(double joint1_rad) {
  std::vector<double> q = kFacingWall;
  q[0] += joint1_rad;
  return q;
}

// the pixels where two pictures of the same size differ (any channel by more than `tolerance`)
struct Difference {
  int pixels = 0;
  int min_x = 1 << 30, min_y = 1 << 30, max_x = -1, max_y = -1;
};

Difference difference(const view::Image& a, const view::Image& b, int tolerance = 12) {
  Difference d;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  for (int y = 0; y < std::min(a.height, b.height); ++y) {
    for (int x = 0; x < std::min(a.width, b.width); ++x) {
      const uint8_t* p = a.pixel(x, y);
      const uint8_t* q = b.pixel(x, y);
      if (std::abs(p[0] - q[0]) > tolerance || std::abs(p[1] - q[1]) > tolerance || std::abs(p[2] - q[2]) > tolerance) {
        ++d.pixels;
        d.min_x = std::min(d.min_x, x);
        d.min_y = std::min(d.min_y, y);
        d.max_x = std::max(d.max_x, x);
        d.max_y = std::max(d.max_y, y);
      }
    }
  }
  return d;
}

// a program's path as the shell finds it (the process helpers execute paths)
std::string in_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string candidate = dirs.substr(start, end - start) + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return program;
}

class ViewProcessTest : public ::testing::Test {
 protected:
  VirtualDisplay display;
  std::string dir = make_temp_dir();
  int domain = unique_domain();

  // `teleop view` on the follower's scene, small and without text, `frames` frames once every
  // shown topic delivered; the last one as `png`
  std::string config = source("config/nodes/follower.yaml");

  ProcessResult view(const std::string& png, std::vector<std::string> extra = {}) const {
    std::vector<std::string> args = {"view",
                                     "-c",
                                     config,
                                     "--no-overlay",
                                     "--width",
                                     "320",
                                     "--height",
                                     "240",
                                     "--frames",
                                     "3",
                                     "--wait",
                                     "20",
                                     "--screenshot",
                                     dir + "/" + png};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_process(tool(args, domain), 60s);
  }
  view::Image picture(const std::string& png) const { return view::read_png(dir + "/" + png); }
};

// publishes a follower and a twin state at 100 Hz from the test's own participant
class StatePublisher {
 public:
  explicit StatePublisher(int domain) : participant_(bus_participant(domain, "view_test")) {
    follower_ = participant_.make_writer(transport::topics::kFollowerState);
    twin_ = participant_.make_writer(transport::topics::kTwinState);
    hand_ = participant_.make_writer(transport::topics::kHandJoints);
    thread_ = std::thread([this] { loop(); });
  }
  ~StatePublisher() {
    stop_ = true;
    thread_.join();
  }
  void follower(const std::vector<double>& q) {
    const std::lock_guard lock(mutex_);
    follower_q_ = q;
  }
  void twin(const std::vector<double>& q) {
    const std::lock_guard lock(mutex_);
    twin_q_ = q;
  }
  void hand(const std::vector<double>& q) {
    const std::lock_guard lock(mutex_);
    hand_q_ = q;
  }

 private:
  void loop() {
    msg::JointState s;
    uint64_t seq = 0;
    while (!stop_) {
      std::vector<double> f, t, h;
      {
        const std::lock_guard lock(mutex_);
        f = follower_q_;
        t = twin_q_;
        h = hand_q_;
      }
      for (auto& [writer, q] : {std::pair{&follower_, f}, std::pair{&twin_, t}, std::pair{&hand_, h}}) {
        if (q.empty()) continue;
        s.header().seq(++seq);
        s.q_rad(q);
        s.dq_radps(std::vector<double>(q.size(), 0.0));
        s.tau_measured_nm(std::vector<double>(q.size(), 0.0));
        (void)writer->write(s);
      }
      std::this_thread::sleep_for(10ms);
    }
  }

  transport::Participant participant_;
  transport::Writer<msg::JointState> follower_;
  transport::Writer<msg::JointState> twin_;
  transport::Writer<msg::JointState> hand_;
  std::mutex mutex_;
  std::vector<double> follower_q_, twin_q_, hand_q_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST_F(ViewProcessTest, TheWindowShowsTheDemosFollowerAndTwinWhereTheCameraLooks) {
  // the scene before anyone is measured: the wall, no robot
  const ProcessResult empty = run_process(tool({"view", "--no-overlay", "--width", "320", "--height", "240", "--frames",
                                                "3", "--screenshot", dir + "/empty.png"},
                                               domain),
                                          60s);
  ASSERT_EQ(empty.exit_status, 0) << empty.output;
  EXPECT_NE(empty.output.find("teleop view: scene_wall.xml"), std::string::npos) << empty.output;

  RunningProcess follower(node(dir, "follower", domain, 40));
  RunningProcess twin(node(dir, "twin", domain, 40));
  const ProcessResult live = view("live.png");
  ASSERT_EQ(live.exit_status, 0) << live.output << follower.output() << twin.output();
  EXPECT_TRUE(std::regex_search(live.output, std::regex(R"(teleop view: \d+ frames in [0-9.]+ s)"))) << live.output;
  // the robot: a large part of the picture, reaching into its middle half (the free camera looks
  // at the model's centre, between the robot and the wall)
  const Difference robot = difference(picture("empty.png"), picture("live.png"));
  EXPECT_GT(robot.pixels, 320 * 240 / 50) << live.output;
  EXPECT_LT(robot.min_x, 240);
  EXPECT_GT(robot.max_x, 80);
  EXPECT_LT(robot.min_y, 180);
  EXPECT_GT(robot.max_y, 60);
  follower.stop(SIGINT, 10s);
  twin.stop(SIGINT, 10s);
}

TEST_F(ViewProcessTest, TheFollowersStateMovesThePictureAndTheGhostFollowsTheTwin) {
  StatePublisher bus(domain);
  bus.follower(kFacingWall);
  ASSERT_EQ(view("a.png", {"--no-twin"}).exit_status, 0);
  bus.follower(turned(0.8));
  const ProcessResult b = view("b.png", {"--no-twin"});
  ASSERT_EQ(b.exit_status, 0) << b.output;
  const Difference moved = difference(picture("a.png"), picture("b.png"));
  EXPECT_GT(moved.pixels, 320 * 240 / 100) << "the arm turned by 0.8 rad about its first joint";

  // the twin's state as a ghost: where the arm turned to, over the follower that did not turn
  bus.follower(kFacingWall);
  bus.twin(turned(0.8));
  const ProcessResult c = view("c.png");
  ASSERT_EQ(c.exit_status, 0) << c.output;
  const Difference ghost = difference(picture("a.png"), picture("c.png"));
  EXPECT_GT(ghost.pixels, moved.pixels / 4) << "the ghost adds the turned arm to the picture";
  // translucent: not the solid arm of b
  EXPECT_GT(difference(picture("b.png"), picture("c.png")).pixels, moved.pixels / 4);

  bus.twin(turned(-0.8));
  const ProcessResult d = view("d.png");
  ASSERT_EQ(d.exit_status, 0) << d.output;
  const Difference followed = difference(picture("c.png"), picture("d.png"));
  EXPECT_GT(followed.pixels, moved.pixels / 4) << "the ghost follows the twin";
}

// issue 20 item 5: the hand node's 20 joint angles pose the emulator's MuJoCo hand
TEST_F(ViewProcessTest, TheHandsJointStateClosesItsFingersInThePicture) {
  config = source("config/nodes/hand_mujoco.yaml");
  StatePublisher bus(domain);
  bus.hand(std::vector<double>(20, 0.0));
  const ProcessResult open = view("open.png");
  ASSERT_EQ(open.exit_status, 0) << open.output;
  EXPECT_NE(open.output.find("svh_hand_grasp.xml"), std::string::npos) << open.output;
  // every flexion joint 0.6 rad, the spreads 0.3: a closing hand
  std::vector<double> closed(20, 0.6);
  closed[17] = closed[18] = closed[19] = 0.3;
  bus.hand(closed);
  const ProcessResult shut = view("closed.png");
  ASSERT_EQ(shut.exit_status, 0) << shut.output;
  EXPECT_GT(difference(picture("open.png"), picture("closed.png")).pixels, 320 * 240 / 100)
      << "the fingers closed by 0.6 rad";
  // an arm's state does not pose the hand
  EXPECT_EQ(open.output.find("teleop/twin"), std::string::npos) << open.output;
}

TEST_F(ViewProcessTest, ASignalClosesTheViewWithZero) {
  RunningProcess view_process(tool({"view", "--width", "320", "--height", "240", "--max-fps", "10"}, domain));
  ASSERT_TRUE(view_process.wait_for_output("teleop view: scene_wall.xml", 30s)) << view_process.output();
  view_process.run_for(1000ms);
  EXPECT_EQ(view_process.stop(SIGINT, 20s), 0) << view_process.output();
  EXPECT_TRUE(std::regex_search(view_process.output(), std::regex(R"(teleop view: \d+ frames in )")))
      << view_process.output();
}

TEST(ViewWithoutDisplayTest, SaysThereIsNoDisplayAndExits1) {
  const char* old = std::getenv("DISPLAY");
  const std::string saved = old != nullptr ? old : "";
  unsetenv("DISPLAY");
  const ProcessResult r = run_process(tool({"view", "--frames", "1"}, unique_domain()), 30s);
  const std::string dir = make_temp_dir();
  write_file(dir + "/follower.csv", "t_s,wall_s,lateness_us,q_0,q_1,q_2,q_3,q_4,q_5,q_6\n0,1,0,0,0,0,-2,0,3,0\n");
  const ProcessResult render = run_process({bin("teleop"), "render", dir, "-o", dir + "/x.mp4"}, 30s);
  if (old != nullptr) setenv("DISPLAY", saved.c_str(), 1);
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("teleop view: no display to open a window on"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
  EXPECT_EQ(render.exit_status, 1) << render.output;
  EXPECT_NE(render.output.find("teleop render: no display"), std::string::npos) << render.output;
}

// a recording, as `teleop record` writes it, rendered like a run: its follower and twin joint
// states become the run's traces, the robot stands where it was recorded
TEST_F(ViewProcessTest, RenderPosesTheRobotFromARecording) {
  StatePublisher publisher(domain);
  publisher.follower(turned(0.6));
  publisher.twin(kFacingWall);
  const std::string recording = dir + "/r.mcap";
  const ProcessResult record = run_process(
      tool({"record", "-o", recording, "--topics", "teleop/follower/joint_state,teleop/twin/joint_state", "--duration",
            "3"},
           domain),
      30s);
  ASSERT_EQ(record.exit_status, 0) << record.output;
  const ProcessResult render = run_process({bin("teleop"), "render", recording, "--width", "320", "--height", "240",
                                            "--fps", "10", "--no-overlay", "--still", dir + "/recorded.png"},
                                           120s);
  ASSERT_EQ(render.exit_status, 0) << render.output;
  EXPECT_NE(render.output.find(recording + "_traces/follower.csv from " + recording), std::string::npos)
      << render.output;
  EXPECT_NE(render.output.find("(follower.csv, twin.csv)"), std::string::npos) << render.output;
  EXPECT_TRUE(std::filesystem::exists(recording + "_traces/run.mp4")) << render.output;

  // the same pose live in `teleop view`: the recorded still shows the arm where the live one is
  ASSERT_EQ(view("live.png").exit_status, 0);
  const view::Image recorded = picture("recorded.png");
  const view::Image live = picture("live.png");
  ASSERT_EQ(recorded.width, 320);
  EXPECT_LT(difference(recorded, live).pixels, 320 * 240 / 50) << "the recorded pose differs from the live one";
}

// a short stiff-wall run (MMT: follower, twin, leader's haptic arm) rendered from its traces
TEST_F(ViewProcessTest, RenderMakesAPlayableMp4OfAStiffWallRun) {
  const ProcessResult run = run_process(
      {bin("teleop"), "experiment", source("config/experiments/stiff_wall.yaml"), "--runs", "mmt", "--profiles", "none",
       "--duration", "3", "--no-plots", "--report-dir", dir, "--domain", std::to_string(domain)},
      90s);
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const std::string run_dir = dir + "/mmt/none";
  const ProcessResult render = run_process({bin("teleop"), "render", run_dir, "-o", dir + "/clip.mp4", "--width", "320",
                                            "--height", "240", "--fps", "10", "--still", dir + "/still.png"},
                                           120s);
  ASSERT_EQ(render.exit_status, 0) << render.output;
  EXPECT_NE(render.output.find("(follower.csv, twin.csv)"), std::string::npos) << render.output;
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(render.output, m, std::regex(R"(teleop render: (\d+) frames \(([0-9.]+) s of the run\))")))
      << render.output;
  const int frames = std::stoi(m[1]);
  const double run_s = std::stod(m[2]);
  // the whole of the follower's trace: from its first row to its last on the wall clock (a loaded
  // machine starts the loop late: less than the run's 3 s)
  std::istringstream trace(read_file(run_dir + "/follower.csv"));
  std::string line, first, last;
  std::getline(trace, line);
  while (std::getline(trace, line)) {
    if (line.empty()) continue;
    if (first.empty()) first = line;
    last = line;
  }
  auto wall_s = [](const std::string& row) { return std::stod(row.substr(row.find(',') + 1)); };
  ASSERT_FALSE(first.empty());
  EXPECT_NEAR(run_s, wall_s(last) - wall_s(first), 0.01) << render.output;
  EXPECT_GT(run_s, 1.0) << render.output;
  // one frame per tenth of a second, the first at 0; the log rounds the run's length to 0.01 s
  // (2.7996 s printed as 2.80 s has 28 frames, not 29)
  const auto frames_of = [](double s) { return static_cast<int>(std::floor(s * 10 + 1e-9)) + 1; };
  EXPECT_GE(frames, frames_of(run_s - 0.005)) << render.output;
  EXPECT_LE(frames, frames_of(run_s + 0.005)) << render.output;

  const ProcessResult probe =
      run_process({in_path("ffprobe"), "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                   "stream=codec_name,width,height,nb_read_frames", "-show_entries", "format=duration", "-of",
                   "default=noprint_wrappers=1", dir + "/clip.mp4"},
                  30s);
  ASSERT_EQ(probe.exit_status, 0) << probe.output;
  EXPECT_NE(probe.output.find("codec_name=h264"), std::string::npos) << probe.output;
  EXPECT_NE(probe.output.find("width=320\nheight=240"), std::string::npos) << probe.output;
  EXPECT_NE(probe.output.find("nb_read_frames=" + std::to_string(frames) + "\n"), std::string::npos) << probe.output;
  ASSERT_TRUE(std::regex_search(probe.output, m, std::regex(R"(duration=([0-9.]+))"))) << probe.output;
  EXPECT_NEAR(std::stod(m[1]), frames / 10.0, 0.15) << probe.output;

  const view::Image still = view::read_png(dir + "/still.png");
  EXPECT_EQ(still.width, 320);
  EXPECT_EQ(still.height, 240);
}

}  // namespace
}  // namespace teleop::test
