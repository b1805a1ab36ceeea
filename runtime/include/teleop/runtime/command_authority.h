#pragma once
// Whether a node's commands are in force: the nodes that take them (every node whose status awaits
// the command topic) say in their NodeStatus whom they follow and whether its newest command is
// in force (FlowStatus). A leader whose commands are refused, found invalid, or sent to a robot
// that holds is not in command, and must neither pretend to be (`running`) nor render the force
// of a robot that does not follow it.
//
// The statuses are read on a Fast DDS thread (deserializing one allocates for its longer strings),
// which leaves each taker's verdict in atomics; the loop sums them up without allocating or waiting.

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include <teleop/msg/status.h>

#include "teleop/common/fixed_text.h"
#include "teleop/common/node_event.h"
#include "teleop/common/stream_session.h"
#include "teleop/transport/callback_gate.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/reader.h"

namespace teleop::runtime {

/// Why the commands are not in force.
enum class CommandRefusal : uint8_t {
  kNone,         ///< in force at every node that takes them
  kNoTaker,      ///< no node that takes them has said anything yet
  kNotYet,       ///< a taker has not followed any writer yet
  kOtherWriter,  ///< a taker follows another writer
  kNotAccepted,  ///< a taker does not accept this node
  kInvalid,      ///< a taker follows this node but finds its commands invalid (e.g. wrong size)
  kHolding,      ///< a taker follows this node but holds (safe hold, a latched reflex, a fault)
};

const char* to_string(CommandRefusal refusal);

class CommandAuthority {
 public:
  /// `self`: this node's command writer on `command_topic` (teleop's topic name, as in FlowStatus);
  /// `self_name`: this node's name (what a taker that does not accept it names).
  CommandAuthority(transport::Participant& participant, const WriterId& self, const std::string& self_name,
                   std::string command_topic);
  /// Waits for a status being judged on Fast DDS's thread; no status is judged after.
  ~CommandAuthority() { gate_.close(); }
  CommandAuthority(const CommandAuthority&) = delete;
  CommandAuthority& operator=(const CommandAuthority&) = delete;

  /// Sums up what the takers said, at `now_mono_ns`, and logs a change. Loop: real-time safe.
  void poll(int64_t now_mono_ns);

  bool in_command() const { return refusal_ == CommandRefusal::kNone; }
  CommandRefusal refusal() const { return refusal_; }
  /// The taker that refuses, and what it says (whom it follows, its reason, its state), as of the
  /// last change the loop saw.
  const FixedText<32>& taker() const { return taker_; }
  const FixedText<32>& detail() const { return detail_; }

 private:
  static constexpr size_t kTakers = 4;
  /// A taker's verdict is forgotten once its status is this old (it stopped, or left).
  static constexpr int64_t kForgetNs = 3'000'000'000;
  /// One node that takes the commands: its verdict for the loop, its words for the log.
  struct Taker {
    std::atomic<int64_t> seen_ns{0};
    std::atomic<CommandRefusal> refusal{CommandRefusal::kNoTaker};
    FixedText<32> name;    // under words_
    FixedText<32> detail;  // under words_
  };

  // Fast DDS's thread
  void judge(const msg::NodeStatus& status);
  Taker& slot_for(const msg::Name& name);
  // the loop's
  void summarise(int64_t now_mono_ns);
  void report_change(int64_t now_mono_ns);

  std::array<char, 33> self_;  // our writer's GUID in hex, as a taker's FlowStatus names it
  FixedText<32> self_name_;
  std::string command_topic_;
  NodeEventQueue* events_;
  std::array<Taker, kTakers> takers_{};
  std::mutex words_;  // names and details; the loop only tries it
  size_t refusing_ = kTakers;  // the taker the loop's verdict comes from
  CommandRefusal refusal_ = CommandRefusal::kNoTaker;
  CommandRefusal reported_ = CommandRefusal::kNoTaker;
  FixedText<32> taker_;
  FixedText<32> detail_;
  transport::CallbackGate gate_;  // closed first when this goes: judge() never outlives it
  transport::Reader<msg::NodeStatus> statuses_;  // last: its thread may call judge() at once
};

}  // namespace teleop::runtime
