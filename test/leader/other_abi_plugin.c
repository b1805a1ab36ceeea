/* A plugin of a later interface than the leader knows: the leader must refuse it by name. */
#include <stddef.h>

#include "teleop/leader/teleop_device_v1.h"

static const teleop_device_v1 kLater = {2u, TELEOP_DEVICE_CARTESIAN, NULL, NULL, NULL, NULL, NULL};

__attribute__((visibility("default"))) const teleop_device_v1* teleop_device_v1_entry(void) { return &kLater; }
