#include "canopen_sdo_client.h"

#include <cstdio>
#include <stdexcept>

namespace teleop::robot {

using can::SdoMessage;
using can::SdoType;

std::string object_name(can::NodeId node, uint16_t index, uint8_t subindex) {
  char text[48];
  std::snprintf(text, sizeof text, "node %u, 0x%04X:%02X", unsigned{node}, unsigned{index}, unsigned{subindex});
  return text;
}

SdoMessage SdoClient::transfer(const can::Result<can::CanFrame>& request, can::NodeId node, uint16_t index,
                               uint8_t subindex) {
  const std::string what = object_name(node, index, subindex);
  if (!request.ok()) throw std::runtime_error("SDO " + what + ": cannot encode the request");
  if (const can::CanStatus sent = bus_.send(*request); sent != can::CanStatus::kOk) {
    throw std::runtime_error("SDO " + what + ": the bus refused the request (" + can::to_string(sent) + ")");
  }
  const uint32_t answer_id = can::cob::kSdoTx + node;
  // on a real bus the time is the clock's: other nodes' frames arriving faster than the poll
  // (heartbeats, EMCY) must not hold the wait open; with a pump, each poll is one pump's time
  const auto deadline = std::chrono::steady_clock::now() + wait_.timeout;
  auto out_of_time = [&] { return !wait_.pump && std::chrono::steady_clock::now() > deadline; };
  for (std::chrono::nanoseconds waited{0}; waited <= wait_.timeout && !out_of_time(); waited += wait_.poll) {
    if (wait_.pump) wait_.pump();
    can::CanFrame frame;
    while (!out_of_time() &&
           bus_.receive(frame, wait_.pump ? std::chrono::nanoseconds::zero() : wait_.poll) == can::CanStatus::kOk) {
      if (frame.id != answer_id || frame.extended()) {
        if (other_frames) other_frames(frame);
        continue;
      }
      const auto answer = can::decode_sdo_response(frame);
      if (!answer.ok() || answer->index != index || answer->subindex != subindex) continue;  // not ours
      if (answer->type == SdoType::kAbort) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%08X", answer->abort_code);
        throw std::runtime_error("SDO " + what + ": the drive refused it (abort code " + code + ")");
      }
      return *answer;
    }
  }
  throw std::runtime_error("SDO " + what + ": no answer within " +
                           std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(wait_.timeout).count()) +
                           " ms (is the drive on the bus, with this node id?)");
}

void SdoClient::write(can::NodeId node, uint16_t index, uint8_t subindex, uint32_t value, uint8_t size) {
  const SdoMessage answer = transfer(can::encode_sdo_download_request(node, index, subindex, value, size), node, index,
                                     subindex);
  if (answer.type != SdoType::kDownloadResponse) {
    throw std::runtime_error("SDO " + object_name(node, index, subindex) + ": the drive answered a write with a read");
  }
}

uint32_t SdoClient::read(can::NodeId node, uint16_t index, uint8_t subindex) {
  const SdoMessage answer = transfer(can::encode_sdo_upload_request(node, index, subindex), node, index, subindex);
  if (answer.type != SdoType::kUploadResponse) {
    throw std::runtime_error("SDO " + object_name(node, index, subindex) + ": the drive answered a read with a write");
  }
  return answer.data;
}

}  // namespace teleop::robot
