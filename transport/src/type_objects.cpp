// The generated type object registrations, in one file: their headers (Fast DDS's TypeObject.h)
// are large, and only this file needs them.
#include <teleop/msg/armTypeObject.h>
#include <teleop/msg/baseTypeObject.h>
#include <teleop/msg/handTypeObject.h>
#include <teleop/msg/statusTypeObject.h>
#include <teleop/msg/twinTypeObject.h>

#include "teleop/transport/type_support.h"

namespace teleop::transport {

void register_type_objects() {
  registerbaseTypes();
  registerarmTypes();
  registerhandTypes();
  registerstatusTypes();
  registertwinTypes();
}

}  // namespace teleop::transport
