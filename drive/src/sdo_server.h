#pragma once
// The drive's SDO server (CiA 301): expedited uploads and downloads of the object dictionary,
// answered with the abort code of every refused access. No segmented or block transfers: no
// object here is longer than four bytes.

#include <cstdint>

#include "drive_link.h"
#include "fault_injection.h"
#include "nmt_slave.h"
#include "object_dictionary.h"
#include "teleop/can/cia301.h"

namespace teleop::drive {

class SdoServer {
 public:
  SdoServer(can::NodeId node, DriveLink& link, const NmtSlave& nmt, const FaultInjection& faults);

  /// A request on the drive's SDO receive COB-ID: the response or abort is sent at once.
  void handle(const can::CanFrame& frame, ObjectDictionary& objects);

 private:
  // one request's object, as the frame names it (the abort names it even for a bad request)
  struct Target {
    uint16_t index = 0;
    uint8_t subindex = 0;
  };
  void upload(Target target, const ObjectInfo& info, const ObjectDictionary& objects);
  void download(Target target, const can::SdoMessage& request, const ObjectInfo& info, ObjectDictionary& objects);
  void abort(Target target, uint32_t code);

  can::NodeId node_;
  DriveLink& link_;
  const NmtSlave& nmt_;
  const FaultInjection& faults_;
};

}  // namespace teleop::drive
