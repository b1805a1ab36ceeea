#include "bus_commands.h"

#include <unistd.h>

#include "choice_option.h"
#include "config_option.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/view/foxglove_scene.h"

BusCommands::BusCommands(CLI::App& app) : app_(&app) {
  CLI::App* topic = app.add_subcommand("topic", "the topics on the bus: list, info, echo, hz");
  topic->require_subcommand(1);
  list_ = topic->add_subcommand("list", "every topic with its type and the number of writers and readers");
  list_->add_flag("-v,--verbose", verbose_, "also the nodes that write and read each topic");
  info_ = topic->add_subcommand("info", "one topic: its type, each writer and reader with node, host and QoS");
  info_->add_option("topic", topic_, "topic name, e.g. teleop/leader/joint_command")->required();
  echo_ = topic->add_subcommand("echo", "print the samples of a topic as YAML");
  echo_->add_option("topic", echo_options_.topic, "topic name")->required();
  echo_->add_option("--field", echo_options_.field,
                    "print only this field, a dotted path (header.seq, q_rad, links[0].peer)");
  echo_->add_flag(
      "--once", [this](int64_t) { echo_options_.count = 1; }, "print one sample and exit");
  echo_->add_option("-n,--count", echo_options_.count, "print this many samples and exit");
  hz_ = topic->add_subcommand("hz", "rate, period spread, sample age and loss of a topic, once a second");
  hz_->add_option("topic", hz_options_.topic, "topic name")->required();
  hz_->add_option("-w,--window", hz_options_.window, "arrivals the statistics are computed over (default 1000)")
      ->check(CLI::Range(2, 1'000'000));
  hz_->add_option("-n,--count", hz_options_.count, "stop after this many samples");
  hz_->add_option("-d,--duration", hz_options_.duration_s, "stop after this many seconds")->check(CLI::PositiveNumber);
  for (CLI::App* c : {list_, info_, echo_, hz_}) add_bus_options(c);

  monitor_ = app.add_subcommand("monitor", "a live view of every node on the bus: state, faults, loop, flows, links");
  monitor_->add_option("--refresh", monitor_options_.refresh_s, "seconds between refreshes (default 1)")
      ->check(CLI::Range(0.1, 60.0));
  monitor_->add_option("-d,--duration", monitor_options_.duration_s, "stop after this many seconds")
      ->check(CLI::PositiveNumber);
  monitor_->add_flag("--lines,!--screen", lines_,
                     "one line per node per refresh (default when the output is not a terminal) or a redrawn screen");
  add_bus_options(monitor_);
  add_record();
  add_replay();
  add_bridge();
}

void BusCommands::add_record() {
  record_ = app_->add_subcommand(
      "record", "record the bus (every teleop topic, or those given) into an MCAP file or a rosbag2 sqlite3 folder");
  record_->add_option("-o,--output", record_options_.dir, "the recording: an MCAP file, e.g. run1.mcap (must not exist "
                                                          "yet), or with --storage sqlite3 a folder")
      ->required();
  record_
      ->add_option("--storage", record_options_.format, "mcap (default: one file, each topic's schema embedded) or "
                                                        "sqlite3 (rosbag2's folder layout)")
      ->transform(teleop::cli::one_of<teleop::tools::RecordingFormat>(
          {{"mcap", teleop::tools::RecordingFormat::kMcap}, {"sqlite3", teleop::tools::RecordingFormat::kSqlite3}}))
      ->option_text("mcap|sqlite3");
  record_
      ->add_option("--compression", record_options_.compression, "an MCAP recording's chunks: zstd (default), lz4, none")
      ->transform(teleop::cli::one_of<teleop::bag::McapCompression>({{"zstd", teleop::bag::McapCompression::kZstd},
                                                        {"lz4", teleop::bag::McapCompression::kLz4},
                                                        {"none", teleop::bag::McapCompression::kNone}}))
      ->option_text("zstd|lz4|none");
  record_->add_option("--topics", record_options_.topics, "only these topics")->delimiter(',');
  record_->add_option("-d,--duration", record_options_.duration_s, "stop after this many seconds")
      ->check(CLI::PositiveNumber);
  record_
      ->add_option_function<double>(
          "--max-mb", [this](double mb) { record_options_.max_bytes = static_cast<int64_t>(mb * 1e6); },
          "stop with an error once the recording would grow beyond this many MB (as on a full disk)")
      ->check(CLI::Range(0.1, 1e9));
  add_bus_options(record_);
}

void BusCommands::add_replay() {
  replay_ = app_->add_subcommand("replay", "publish a recording again with its recorded timing");
  replay_->add_option("recording", replay_options_.dir, "the recording (an MCAP file or a sqlite3 bag folder)")
      ->required();
  replay_->add_option("--topics", replay_options_.topics, "only these topics")->delimiter(',');
  replay_->add_option("--rate", replay_options_.rate, "speed factor (2: twice as fast)")
      ->check(CLI::Range(0.01, 100.0));
  replay_->add_flag("--loop", replay_options_.loop, "start again at the end, until interrupted");
  replay_->add_flag(
      "--keep-stamps", replay_options_.keep_stamps,
      "publish the recorded header stamps (default: restamped now, so receivers do not refuse them as stale)");
  replay_
      ->add_option("--wait-for-readers", replay_options_.wait_for_readers_s,
                   "seconds to wait for a reader of every replayed topic before starting (default 5)")
      ->check(CLI::Range(0.0, 600.0));
  replay_->add_option("--compare", replay_options_.compare_topic,
                      "a recorded JointState topic to compare with its live samples during the replay (RMSE)");
  add_bus_options(replay_);
}

void BusCommands::add_bridge() {
  bridge_ = app_->add_subcommand(
      "bridge", "serve the bus to Foxglove or Lichtblick (Foxglove WebSocket protocol, read-only): every teleop topic "
                "as a channel with its ROS 2 schema");
  bridge_->add_option("--address", bridge_options_.address, "the address to listen on (default 127.0.0.1: this host only)");
  bridge_->add_option("--port", bridge_options_.port, "the port (default 8765; 0: any free one, printed)");
  bridge_
      ->add_option("--max-rate", bridge_options_.max_rate_hz,
                   "messages per second per subscription at most (default 50; 0: every sample)")
      ->check(CLI::Range(0.0, 1e6));
  bridge_
      ->add_option("--queue", bridge_options_.queue_capacity,
                   "frames waiting per client at most; beyond, the oldest is dropped and counted (default 1024)")
      ->check(CLI::Range(1, 1 << 24));
  bridge_
      ->add_option("--scene", bridge_scene_,
                   "also the scene of this follower, twin or hand config for the 3D panel (scene/transforms, "
                   "scene/geometry, scene/forces); a file or a name in config/nodes")
      ->transform(teleop::cli::named_config("nodes"))
      ->check(CLI::ExistingFile);
  add_bus_options(bridge_);
}

void BusCommands::add_bus_options(CLI::App* command) {
  command
      ->add_option("-c,--config", bus_.config_path,
                   "join the bus as this node config says (domain, discovery, security); a file or a name in "
                   "config/nodes")
      ->transform(teleop::cli::named_config("nodes"))
      ->check(CLI::ExistingFile);
  command->add_option("--domain", bus_.domain_id, "DDS domain id (overrides the config)")->check(CLI::Range(0, 232));
  command
      ->add_option("--discovery-time", bus_.discovery_s,
                   "seconds to listen to discovery before answering or giving up on a topic (default 2)")
      ->check(CLI::Range(0.1, 600.0));
}

std::optional<int> BusCommands::run() {
  using namespace teleop::tools;
  const bool any = list_->parsed() || info_->parsed() || echo_->parsed() || hz_->parsed() || monitor_->parsed() ||
                   record_->parsed() || replay_->parsed() || bridge_->parsed();
  if (!any) return std::nullopt;
  teleop::runtime::install_shutdown_handlers();
  if (record_->parsed()) return run_record();
  if (replay_->parsed()) return run_replay();
  if (bridge_->parsed()) return run_bridge();
  if (list_->parsed()) return topic_list(bus_, verbose_, stdout);
  if (info_->parsed()) return topic_info(bus_, topic_, stdout);
  if (echo_->parsed()) return topic_echo(bus_, echo_options_, stdout);
  if (hz_->parsed()) return topic_hz(bus_, hz_options_, stdout);
  monitor_options_.lines = lines_.value_or(isatty(fileno(stdout)) == 0);
  return run_monitor(bus_, monitor_options_, stdout);
}

int BusCommands::run_record() {
  const teleop::tools::RecordResult r = teleop::tools::record(bus_, record_options_, stderr);
  std::printf(
      "recorded %llu samples (%.1f MB) of %zu topics in %.1f s into %s; dropped %llu (queue full), "
      "missed upstream %llu (sequence gaps); cpu %.2f s (%.1f %% of one core)\n",
      static_cast<unsigned long long>(r.messages), static_cast<double>(r.bytes) * 1e-6, r.topics.size(), r.seconds,
      record_options_.dir.c_str(), static_cast<unsigned long long>(r.dropped),
      static_cast<unsigned long long>(r.missed), r.cpu_s, r.seconds > 0 ? 100.0 * r.cpu_s / r.seconds : 0.0);
  return 0;
}

int BusCommands::run_replay() {
  const teleop::tools::ReplayResult r = teleop::tools::replay(bus_, replay_options_, stderr);
  std::printf("%s", teleop::tools::format_replay(r, replay_options_).c_str());
  return r.published > 0 ? 0 : 1;
}

int BusCommands::run_bridge() {
  std::vector<teleop::bridge::ComputedSource> sources;
  if (!bridge_scene_.empty()) {
    // the arms for the 3D panel: view computes, the bridge serves
    auto scene = std::make_shared<teleop::view::FoxgloveScene>(bridge_scene_, bus_.config_path, bus_.domain_id);
    sources.push_back({teleop::view::FoxgloveScene::channels(), 30.0,
                       [scene](std::vector<teleop::JsonMessage>& out) { scene->poll(out); }});
  }
  return teleop::bridge::run_bridge(bus_, bridge_options_, stderr, std::move(sources));
}
