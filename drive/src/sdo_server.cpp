#include "sdo_server.h"

#include "teleop/drive/drive_objects.h"

namespace teleop::drive {

namespace sdo_abort = can::sdo_abort;
using can::CanError;
using can::CanFrame;
using can::SdoType;

namespace {

uint32_t mask_to_bits(uint32_t value, unsigned bits) { return bits >= 32 ? value : value & ((1u << bits) - 1); }
uint8_t bytes_of(const ObjectInfo& info) { return static_cast<uint8_t>((info.bits + 7) / 8); }

}  // namespace

SdoServer::SdoServer(can::NodeId node, DriveLink& link, const NmtSlave& nmt, const FaultInjection& faults)
    : node_(node), link_(link), nmt_(nmt), faults_(faults) {}

void SdoServer::handle(const CanFrame& frame, ObjectDictionary& objects) {
  if (nmt_.state() == can::NmtState::kStopped) return;
  ++link_.stats().sdo_requests;
  const Target target{frame.dlc >= 3 ? can::le::get_u16(&frame.data[1]) : uint16_t{0},
                      frame.dlc >= 4 ? frame.data[3] : uint8_t{0}};
  const auto request = can::decode_sdo_request(frame);
  if (!request.ok()) {
    if (request.error() == CanError::kUnsupported || request.error() == CanError::kInvalidCommand) {
      abort(target, sdo_abort::kInvalidCommand);
    } else {
      ++link_.stats().malformed_frames;  // not an SDO frame at all (dlc, RTR): no answer
    }
    return;
  }
  if (request->type == SdoType::kAbort) return;  // nothing is in progress with expedited transfers
  // the injection object stays reachable, so the refusal can be switched off again
  if (faults_.sdo_refused() && target.index != drive_od::kFaultInjection) {
    abort(target, sdo_abort::kLocalControl);
    return;
  }
  ObjectInfo info;
  if (const uint32_t code = ObjectDictionary::find(target.index, target.subindex, info); code != 0) {
    abort(target, code);
    return;
  }
  if (request->type == SdoType::kUploadRequest) {
    upload(target, info, objects);
  } else {
    download(target, *request, info, objects);
  }
}

void SdoServer::upload(Target target, const ObjectInfo& info, const ObjectDictionary& objects) {
  uint32_t value = 0;
  if (const uint32_t code = objects.read(target.index, target.subindex, value); code != 0) {
    abort(target, code);
    return;
  }
  const uint8_t bytes = bytes_of(info);
  const auto response =
      can::encode_sdo_upload_response(node_, target.index, target.subindex, mask_to_bits(value, bytes * 8), bytes);
  if (response.ok()) link_.send(*response);
}

void SdoServer::download(Target target, const can::SdoMessage& request, const ObjectInfo& info,
                         ObjectDictionary& objects) {
  if (!info.writable) {
    abort(target, sdo_abort::kReadOnly);
    return;
  }
  const uint8_t bytes = bytes_of(info);
  if (request.size != 0 && request.size != bytes) {
    abort(target, request.size > bytes ? sdo_abort::kLengthTooHigh : sdo_abort::kLengthTooLow);
    return;
  }
  if (const uint32_t code = objects.write(target.index, target.subindex, mask_to_bits(request.data, bytes * 8));
      code != 0) {
    abort(target, code);
    return;
  }
  if (const auto response = can::encode_sdo_download_response(node_, target.index, target.subindex); response.ok()) {
    link_.send(*response);
  }
}

void SdoServer::abort(Target target, uint32_t code) {
  if (const auto f = can::encode_sdo_abort(node_, target.index, target.subindex, code, true); f.ok()) {
    link_.send(*f);
    ++link_.stats().sdo_aborts_sent;
  }
}

}  // namespace teleop::drive
