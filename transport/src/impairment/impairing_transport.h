#pragma once
// A Fast DDS chaining transport around UDPv4 that passes every outgoing RTPS message through
// an ImpairmentEngine: below the DDS reliability protocol, so reliable topics retransmit and
// heartbeats get lost as on a real link.

#include <fastdds/rtps/transport/ChainingTransport.h>
#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>

#include <memory>

#include "teleop/transport/impairment/impairment_engine.h"

namespace teleop::transport::impairment {

struct ImpairingTransportDescriptor : public eprosima::fastdds::rtps::ChainingTransportDescriptor {
  ImpairingTransportDescriptor(std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> low,
                               std::shared_ptr<ImpairmentEngine> impairment)
      : ChainingTransportDescriptor(std::move(low)), engine(std::move(impairment)) {}

  eprosima::fastdds::rtps::TransportInterface* create_transport() const override;

  std::shared_ptr<ImpairmentEngine> engine;
};

class ImpairingTransport : public eprosima::fastdds::rtps::ChainingTransport {
 public:
  explicit ImpairingTransport(const ImpairingTransportDescriptor& descriptor)
      : ChainingTransport(descriptor), engine_(descriptor.engine) {}

  eprosima::fastdds::rtps::TransportDescriptorInterface* get_configuration() override {
    return low_level_transport_->get_configuration();
  }

  bool send(eprosima::fastrtps::rtps::SenderResource* low_sender_resource, const eprosima::fastrtps::rtps::octet* buffer,
            uint32_t size, eprosima::fastrtps::rtps::LocatorsIterator* begin,
            eprosima::fastrtps::rtps::LocatorsIterator* end, const std::chrono::steady_clock::time_point& timeout) override {
    return engine_->send(low_sender_resource, buffer, size, begin, end, timeout);
  }

  void receive(eprosima::fastdds::rtps::TransportReceiverInterface* next_receiver,
               const eprosima::fastrtps::rtps::octet* buffer, uint32_t size,
               const eprosima::fastrtps::rtps::Locator_t& local_locator,
               const eprosima::fastrtps::rtps::Locator_t& remote_locator) override {
    // impairment happens on the sending side only
    next_receiver->OnDataReceived(buffer, size, local_locator, remote_locator);
  }

 private:
  std::shared_ptr<ImpairmentEngine> engine_;
};

inline eprosima::fastdds::rtps::TransportInterface* ImpairingTransportDescriptor::create_transport() const {
  return new ImpairingTransport(*this);
}

}  // namespace teleop::transport::impairment
