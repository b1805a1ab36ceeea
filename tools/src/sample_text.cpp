#include "teleop/tools/sample_text.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "deserialized.h"
#include "field_columns.h"
#include "field_writer.h"
#include "teleop/runtime/status_names.h"
#include "teleop/transport/type_support.h"

namespace teleop::tools {
namespace {

using W = FieldVisitor;

std::string_view text(const msg::Name& name) { return name.c_str(); }

const char* mode_name(msg::ControlMode mode) {
  switch (mode) {
    case msg::CONTROL_GRAVITY:
      return "gravity";
    case msg::CONTROL_JOINT_IMPEDANCE:
      return "joint_impedance";
    case msg::CONTROL_CARTESIAN_IMPEDANCE:
      return "cartesian_impedance";
    case msg::CONTROL_POSITION_PD:
      return "position_pd";
  }
  return "unknown";
}

void walk(const msg::SampleHeader& h, W& w) {
  w.begin("header");
  w.value("seq", static_cast<uint64_t>(h.seq()));
  w.value("stamp_ns", static_cast<int64_t>(h.stamp_ns()));
  w.value("stamp_mono_ns", static_cast<int64_t>(h.stamp_mono_ns()));
  w.value("source", text(h.source()));
  w.end();
}

void walk(std::string_view name, const msg::Vector3& v, W& w) {
  w.begin(name);
  w.value("x", v.x());
  w.value("y", v.y());
  w.value("z", v.z());
  w.end();
}

void walk(std::string_view name, const msg::Pose& p, W& w) {
  w.begin(name);
  walk("position_m", p.position_m(), w);
  w.begin("orientation");
  w.value("w", p.orientation().w());
  w.value("x", p.orientation().x());
  w.value("y", p.orientation().y());
  w.value("z", p.orientation().z());
  w.end();
  w.end();
}

void walk(std::string_view name, const msg::Twist& t, W& w) {
  w.begin(name);
  walk("linear_mps", t.linear_mps(), w);
  walk("angular_radps", t.angular_radps(), w);
  w.end();
}

void walk(const msg::JointState& s, W& w) {
  walk(s.header(), w);
  w.value("robot", text(s.robot()));
  w.value("arm", text(s.arm()));
  w.list("q_rad", s.q_rad());
  w.list("dq_radps", s.dq_radps());
  w.list("tau_measured_nm", s.tau_measured_nm());
  w.list("tau_ext_nm", s.tau_ext_nm());
}

void walk(const msg::JointCommand& s, W& w) {
  walk(s.header(), w);
  w.value("robot", text(s.robot()));
  w.value("arm", text(s.arm()));
  w.list("mode", s.mode(), mode_name);
  w.list("q_des_rad", s.q_des_rad());
  w.list("dq_des_radps", s.dq_des_radps());
  w.list("tau_ff_nm", s.tau_ff_nm());
  w.list("stiffness_nm_per_rad", s.stiffness_nm_per_rad());
  w.list("damping_nms_per_rad", s.damping_nms_per_rad());
}

void walk(const msg::CartesianCommand& s, W& w) {
  walk(s.header(), w);
  w.value("robot", text(s.robot()));
  w.value("arm", text(s.arm()));
  w.value("frame", text(s.frame()));
  walk("target_pose", s.target_pose(), w);
  walk("target_twist", s.target_twist(), w);
  walk("stiffness_translational_n_per_m", s.stiffness_translational_n_per_m(), w);
  walk("stiffness_rotational_nm_per_rad", s.stiffness_rotational_nm_per_rad(), w);
  w.value("damping_ratio", s.damping_ratio());
  w.value("nullspace_stiffness_nm_per_rad", s.nullspace_stiffness_nm_per_rad());
}

void walk(const msg::WrenchStamped& s, W& w) {
  walk(s.header(), w);
  w.value("frame", text(s.frame()));
  walk("force_n", s.force_n(), w);
  walk("torque_nm", s.torque_nm(), w);
}

void walk(const msg::JointTorque& s, W& w) {
  walk(s.header(), w);
  w.value("robot", text(s.robot()));
  w.value("arm", text(s.arm()));
  w.list("tau_nm", s.tau_nm());
}

void walk(const msg::HandCommand& s, W& w) {
  walk(s.header(), w);
  w.list("target_position_rad", s.target_position_rad());
  w.list("current_limit_a", s.current_limit_a());
  w.value("enable", s.enable());
  w.value("fault_reset", s.fault_reset());
}

void walk(const msg::HandState& s, W& w) {
  walk(s.header(), w);
  w.list("position_rad", s.position_rad());
  w.list("velocity_radps", s.velocity_radps());
  w.list("current_a", s.current_a());
  const auto integer = [](auto v) { return std::to_string(v); };
  w.list("statusword", s.statusword(), integer);
  w.list("error_code", s.error_code(), integer);
  w.list("faults", s.faults(), integer);
}

void walk(const msg::LoopStatistics& l, W& w) {
  w.begin("loop");
  w.value("rate_hz", l.rate_hz());
  w.value("cycles", static_cast<uint64_t>(l.cycles()));
  w.value("overruns", static_cast<uint64_t>(l.overruns()));
  w.value("skipped", static_cast<uint64_t>(l.skipped()));
  w.value("lateness_p50_ns", static_cast<int64_t>(l.lateness_p50_ns()));
  w.value("lateness_p99_ns", static_cast<int64_t>(l.lateness_p99_ns()));
  w.value("lateness_max_ns", static_cast<int64_t>(l.lateness_max_ns()));
  w.end();
}

void walk(const msg::LinkStatistics& l, W& w) {
  w.value("peer", text(l.peer()));
  w.value("profile", text(l.profile()));
  w.value("messages", static_cast<uint64_t>(l.messages()));
  w.value("delivered", static_cast<uint64_t>(l.delivered()));
  w.value("lost", static_cast<uint64_t>(l.lost()));
  w.value("outage", static_cast<uint64_t>(l.outage()));
  w.value("queue", static_cast<uint64_t>(l.queue()));
  w.value("duplicated", static_cast<uint64_t>(l.duplicated()));
  w.value("reordered", static_cast<uint64_t>(l.reordered()));
  w.value("delay_p50_ns", static_cast<int64_t>(l.delay_p50_ns()));
  w.value("delay_p99_ns", static_cast<int64_t>(l.delay_p99_ns()));
}

void walk(const msg::FlowStatus& f, W& w) {
  w.value("topic", std::string_view(f.topic().c_str()));
  w.value("awaited", f.awaited());
  w.value("writers", static_cast<int64_t>(f.writers()));
  w.value("received", static_cast<uint64_t>(f.received()));
  w.value("lost", static_cast<uint64_t>(f.lost()));
  w.value("latency_ns", static_cast<int64_t>(f.latency_ns()));
  w.value("clock_offset_ns", static_cast<int64_t>(f.clock_offset_ns()));
  w.value("age_ns", static_cast<int64_t>(f.age_ns()));
}

template <typename Item>
void walk_items(std::string_view name, const std::vector<Item>& items, W& w) {
  if (items.empty()) {
    w.value(name, std::string_view("[]"));
    return;
  }
  w.begin(name);
  for (size_t i = 0; i < items.size(); ++i) {
    w.begin_item(i);
    walk(items[i], w);
    w.end();
  }
  w.end();
}

void walk(const msg::NodeStatus& s, W& w) {
  walk(s.header(), w);
  w.value("role", std::string_view(runtime::role_name(s.role())));
  w.value("state", std::string_view(runtime::state_name(s.state())));
  w.list("fault_codes", s.fault_codes(), [](uint32_t f) { return std::string(runtime::fault_name(f)); });
  walk(s.loop(), w);
  walk_items("links", s.links(), w);
  walk_items("flows", s.flows(), w);
  w.value("tdpa_energy_j", s.tdpa_energy_j());
  w.value("can_bus_state", text(s.can_bus_state()));
}

void walk(const msg::ResetRequest& s, W& w) {
  walk(s.header(), w);
  w.value("target", text(s.target()));
}

void walk(const msg::EmergencyStop& s, W& w) {
  walk(s.header(), w);
  w.value("engaged", s.engaged());
  w.value("target", text(s.target()));
  w.value("origin", std::string_view(s.origin().c_str()));
}

void walk(const msg::TdpaEnergy& s, W& w) {
  walk(s.header(), w);
  w.value("session", static_cast<uint64_t>(s.session()));
  w.list("energy_in_j", s.energy_in_j());
  w.list("energy_out_j", s.energy_out_j());
}

void walk(const msg::GeomDistances& s, W& w) {
  walk(s.header(), w);
  w.list("pair", s.pair(), [](const msg::Name& n) { return std::string(n.c_str()); });
  w.list("distance_m", s.distance_m());
}

void walk(const msg::ObjectPose& s, W& w) {
  walk(s.header(), w);
  w.value("body", text(s.body()));
  walk("world_pose", s.world_pose(), w);
  walk("world_twist", s.world_twist(), w);
}

template <typename... T>
struct TypeList {};

using AllTypes = TypeList<msg::JointState, msg::JointCommand, msg::CartesianCommand, msg::WrenchStamped,
                          msg::JointTorque, msg::HandCommand, msg::HandState, msg::NodeStatus, msg::ResetRequest,
                          msg::TdpaEnergy, msg::GeomDistances, msg::ObjectPose, msg::EmergencyStop>;

// the sample's fields, deserialized as the type it is, to `visitor`
template <typename T, typename... Rest>
void visit_fields(TypeList<T, Rest...>, const transport::SampleType& type, const std::vector<uint8_t>& cdr,
                  FieldVisitor& visitor) {
  if (type.dds_name == typename transport::PubSubTypeOf<T>::type().getName()) {
    walk(deserialized<T>(cdr), visitor);
  } else if constexpr (sizeof...(Rest) > 0) {
    visit_fields(TypeList<Rest...>{}, type, cdr, visitor);
  } else {
    throw std::runtime_error("no text form for type " + type.dds_name);
  }
}

// the encapsulation header's second byte: 0x01 little endian (CDR_LE), 0x00 big endian
bool little_endian(const std::vector<uint8_t>& cdr) { return cdr[1] == 0x01; }

template <typename V>
V load(const std::vector<uint8_t>& cdr, size_t at, bool le) {
  uint8_t bytes[sizeof(V)];
  std::memcpy(bytes, cdr.data() + at, sizeof(V));
  if (le != (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)) std::reverse(bytes, bytes + sizeof(V));
  V v;
  std::memcpy(&v, bytes, sizeof(V));
  return v;
}

template <typename V>
void store(std::vector<uint8_t>& cdr, size_t at, V v, bool le) {
  uint8_t bytes[sizeof(V)];
  std::memcpy(bytes, &v, sizeof(V));
  if (le != (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)) std::reverse(bytes, bytes + sizeof(V));
  std::memcpy(cdr.data() + at, bytes, sizeof(V));
}

// SampleHeader leads every type: seq, stamp_ns, stamp_mono_ns, 8 bytes each right after the
// 4-byte encapsulation (CDR aligns from there)
constexpr size_t kSeqAt = 4;
constexpr size_t kStampAt = 12;
constexpr size_t kStampMonoAt = 20;
constexpr size_t kHeaderEnd = 28;

bool is_cdr(const std::vector<uint8_t>& cdr) { return cdr.size() >= kHeaderEnd && cdr[0] == 0x00 && cdr[1] <= 0x01; }

}  // namespace

std::string sample_text(const transport::SampleType& type, const std::vector<uint8_t>& cdr, std::string_view field) {
  FieldWriter writer{std::string(field)};
  visit_fields(AllTypes{}, type, cdr, writer);
  if (!field.empty() && !writer.matched()) {
    throw std::runtime_error(type.dds_name + " has no field '" + std::string(field) + "'");
  }
  return writer.text();
}

std::vector<std::pair<std::string, std::string>> sample_fields(const transport::SampleType& type,
                                                               const std::vector<uint8_t>& cdr) {
  FieldColumns columns;
  visit_fields(AllTypes{}, type, cdr, columns);
  return std::move(columns.columns());
}

bool read_header(const std::vector<uint8_t>& cdr, HeaderView& header) {
  if (!is_cdr(cdr)) return false;
  const bool le = little_endian(cdr);
  header.seq = load<uint64_t>(cdr, kSeqAt, le);
  header.stamp_ns = load<int64_t>(cdr, kStampAt, le);
  header.stamp_mono_ns = load<int64_t>(cdr, kStampMonoAt, le);
  return true;
}

bool restamp_header(std::vector<uint8_t>& cdr, int64_t stamp_ns, int64_t stamp_mono_ns) {
  if (!is_cdr(cdr)) return false;
  const bool le = little_endian(cdr);
  store(cdr, kStampAt, stamp_ns, le);
  store(cdr, kStampMonoAt, stamp_mono_ns, le);
  return true;
}

}  // namespace teleop::tools
