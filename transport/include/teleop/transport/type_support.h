#pragma once
// Maps each sample type to its fastddsgen-generated type support.

#include <teleop/msg/armPubSubTypes.h>
#include <teleop/msg/handPubSubTypes.h>
#include <teleop/msg/statusPubSubTypes.h>
#include <teleop/msg/twinPubSubTypes.h>

namespace teleop::transport {

template <typename T>
struct PubSubTypeOf;

#define TELEOP_PUBSUB_TYPE(Msg)            \
  template <>                              \
  struct PubSubTypeOf<msg::Msg> {          \
    using type = msg::Msg##PubSubType;     \
  };

TELEOP_PUBSUB_TYPE(JointState)
TELEOP_PUBSUB_TYPE(JointCommand)
TELEOP_PUBSUB_TYPE(CartesianCommand)
TELEOP_PUBSUB_TYPE(WrenchStamped)
TELEOP_PUBSUB_TYPE(JointTorque)
TELEOP_PUBSUB_TYPE(HandCommand)
TELEOP_PUBSUB_TYPE(HandState)
TELEOP_PUBSUB_TYPE(NodeStatus)
TELEOP_PUBSUB_TYPE(ResetRequest)
TELEOP_PUBSUB_TYPE(EmergencyStop)
TELEOP_PUBSUB_TYPE(TdpaEnergy)
TELEOP_PUBSUB_TYPE(GeomDistances)
TELEOP_PUBSUB_TYPE(ObjectPose)

#undef TELEOP_PUBSUB_TYPE

/// Registers the XTypes type objects of every teleop type with Fast DDS, once per process (the
/// generated registration is guarded: idl/register_types_once.cmake), so that dynamic types can be
/// built from them in this process. Discovery announces none of them, nor the type information
/// (docs/transport.md, "Type objects"). A sample's constructor registers its file's types too, but
/// a participant may create endpoints before any sample exists. Setup time.
void register_type_objects();

}  // namespace teleop::transport
