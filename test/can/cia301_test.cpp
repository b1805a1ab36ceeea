// CiA 301 codecs: round trips for every service and rejection of malformed frames.
#include "teleop/can/cia301.h"

#include <gtest/gtest.h>

#include "allocation_counter.h"

namespace teleop::can {
namespace {

CanFrame raw(uint32_t id, std::initializer_list<uint8_t> bytes, uint8_t flags = 0) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  for (uint8_t b : bytes) f.data[f.dlc++] = b;
  return f;
}

CanFrame with_dlc(CanFrame f, uint8_t dlc) {
  f.dlc = dlc;
  return f;
}

// ---------------------------------------------------------------------------------------------

TEST(Cia301, ClassifiesPredefinedConnectionSet) {
  struct Case {
    uint32_t id;
    Service service;
    NodeId node;
    uint8_t pdo;
  };
  const Case cases[] = {
      {0x000, Service::kNmt, 0, 0},        {0x080, Service::kSync, 0, 0},      {0x085, Service::kEmcy, 5, 0},
      {0x181, Service::kTpdo, 1, 1},       {0x201, Service::kRpdo, 1, 1},      {0x2FF, Service::kTpdo, 127, 2},
      {0x305, Service::kRpdo, 5, 2},       {0x385, Service::kTpdo, 5, 3},      {0x405, Service::kRpdo, 5, 3},
      {0x485, Service::kTpdo, 5, 4},       {0x505, Service::kRpdo, 5, 4},      {0x585, Service::kSdoResponse, 5, 0},
      {0x605, Service::kSdoRequest, 5, 0}, {0x705, Service::kHeartbeat, 5, 0}, {0x100, Service::kUnknown, 0, 0},
      {0x001, Service::kUnknown, 0, 0},    {0x180, Service::kUnknown, 0, 0},   {0x7E5, Service::kUnknown, 0, 0},
  };
  for (const Case& c : cases) {
    const ServiceId s = classify(raw(c.id, {}));
    EXPECT_EQ(s.service, c.service) << std::hex << c.id;
    EXPECT_EQ(s.node, c.node) << std::hex << c.id;
    EXPECT_EQ(s.pdo_number, c.pdo) << std::hex << c.id;
  }
  EXPECT_EQ(classify(raw(0x181, {}, CanFrame::kExtended)).service, Service::kUnknown);
  EXPECT_EQ(tpdo_cob_id(1, 3), 0x183);
  EXPECT_EQ(rpdo_cob_id(4, 3), 0x503);
}

// --- NMT --------------------------------------------------------------------------------------

TEST(Nmt, RoundTripsEveryCommandForEveryAddressing) {
  for (NmtCommand c : {NmtCommand::kStart, NmtCommand::kStop, NmtCommand::kEnterPreOperational, NmtCommand::kResetNode,
                       NmtCommand::kResetCommunication}) {
    for (NodeId node : {NodeId{0}, NodeId{1}, NodeId{42}, NodeId{127}}) {
      const auto f = encode_nmt(c, node);
      ASSERT_TRUE(f.ok());
      EXPECT_EQ(f->id, 0x000u);
      EXPECT_EQ(f->dlc, 2);
      EXPECT_EQ(f->data[0], static_cast<uint8_t>(c));
      const auto m = decode_nmt(*f);
      ASSERT_TRUE(m.ok());
      EXPECT_EQ(m->command, c);
      EXPECT_EQ(m->node, node);
    }
  }
}

TEST(Nmt, RejectsMalformedFrames) {
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x05, 0x00})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x03, 0x05})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x80})).error(), CanError::kInvalidNode);
  EXPECT_EQ(decode_nmt(raw(0x001, {0x01, 0x01})).error(), CanError::kInvalidId);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x01}, CanFrame::kRtr)).error(), CanError::kRemoteFrame);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x01}, CanFrame::kExtended)).error(), CanError::kExtendedFrame);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x01}, CanFrame::kError)).error(), CanError::kErrorFrame);
  EXPECT_EQ(decode_nmt(raw(0x000, {0x01, 0x01}, 0x80)).error(), CanError::kInvalidField);  // unknown flag bit
  EXPECT_EQ(encode_nmt(NmtCommand::kStart, 128).error(), CanError::kInvalidNode);
  EXPECT_EQ(encode_nmt(static_cast<NmtCommand>(0x07), 1).error(), CanError::kInvalidCommand);
}

// --- SYNC -------------------------------------------------------------------------------------

TEST(Sync, RoundTripsWithAndWithoutCounter) {
  const auto plain = encode_sync();
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->id, 0x080u);
  EXPECT_EQ(plain->dlc, 0);
  EXPECT_EQ(decode_sync(*plain)->counter, 0);
  for (uint8_t counter : {uint8_t{1}, uint8_t{17}, uint8_t{240}}) {
    const auto f = encode_sync(counter);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(f->dlc, 1);
    EXPECT_EQ(decode_sync(*f)->counter, counter);
  }
}

TEST(Sync, RejectsBadCounterAndLength) {
  EXPECT_EQ(encode_sync(241).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(decode_sync(raw(0x080, {0})).error(), CanError::kInvalidField);
  EXPECT_EQ(decode_sync(raw(0x080, {241})).error(), CanError::kInvalidField);
  EXPECT_EQ(decode_sync(raw(0x080, {1, 2})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_sync(raw(0x081, {})).error(), CanError::kInvalidId);
  EXPECT_EQ(decode_sync(raw(0x080, {}, CanFrame::kRtr)).error(), CanError::kRemoteFrame);
}

// --- EMCY -------------------------------------------------------------------------------------

TEST(Emcy, RoundTripsCodeRegisterAndVendorBytes) {
  EmcyMessage m;
  m.node = 9;
  m.error_code = emcy::kFollowingError;
  m.error_register = 0x21;
  m.vendor = {1, 2, 3, 4, 5};
  const auto f = encode_emcy(m);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->id, 0x089u);
  EXPECT_EQ(f->dlc, 8);
  EXPECT_EQ(f->data[0], 0x11);  // little-endian 0x8611
  EXPECT_EQ(f->data[1], 0x86);
  EXPECT_EQ(f->data[2], 0x21);
  EXPECT_EQ(f->data[7], 5);
  const auto d = decode_emcy(*f);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->node, 9);
  EXPECT_EQ(d->error_code, emcy::kFollowingError);
  EXPECT_EQ(d->error_register, 0x21);
  EXPECT_EQ(d->vendor, m.vendor);
}

TEST(Emcy, RejectsWrongLengthIdAndNode) {
  EXPECT_EQ(decode_emcy(raw(0x081, {0x10, 0x23, 0x03})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_emcy(raw(0x080, {0, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidId);  // that is SYNC
  EXPECT_EQ(decode_emcy(raw(0x100, {0, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidId);
  EmcyMessage m;
  m.node = 0;
  EXPECT_EQ(encode_emcy(m).error(), CanError::kInvalidNode);
  m.node = 128;
  EXPECT_EQ(encode_emcy(m).error(), CanError::kInvalidNode);
}

TEST(Emcy, ErrorRegisterFollowsErrorClass) {
  EXPECT_EQ(error_register_for(emcy::kErrorReset), 0x00);
  EXPECT_EQ(error_register_for(emcy::kGeneric), 0x01);
  EXPECT_EQ(error_register_for(emcy::kOverCurrent), 0x03);
  EXPECT_EQ(error_register_for(0x3210), 0x05);
  EXPECT_EQ(error_register_for(0x4210), 0x09);
  EXPECT_EQ(error_register_for(emcy::kHeartbeatError), 0x11);
  EXPECT_EQ(error_register_for(emcy::kPdoLengthError), 0x11);
  EXPECT_EQ(error_register_for(emcy::kFollowingError), 0x21);
  EXPECT_EQ(error_register_for(emcy::kMotorBlocked), 0x21);
  EXPECT_EQ(error_register_for(0xFF01), 0x81);
}

// --- heartbeat --------------------------------------------------------------------------------

TEST(Heartbeat, RoundTripsEveryStateAndBootUpIsZero) {
  for (NmtState s : {NmtState::kBootUp, NmtState::kStopped, NmtState::kOperational, NmtState::kPreOperational}) {
    const auto f = encode_heartbeat(5, s);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(f->id, 0x705u);
    EXPECT_EQ(f->dlc, 1);
    const auto d = decode_heartbeat(*f);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->node, 5);
    EXPECT_EQ(d->state, s);
  }
  EXPECT_EQ(encode_heartbeat(5, NmtState::kBootUp)->data[0], 0x00);
  EXPECT_EQ(encode_heartbeat(5, NmtState::kPreOperational)->data[0], 0x7F);
}

TEST(Heartbeat, RejectsUnknownStateAndWrongLength) {
  EXPECT_EQ(decode_heartbeat(raw(0x705, {0x01})).error(), CanError::kInvalidField);
  EXPECT_EQ(decode_heartbeat(raw(0x705, {0x85})).error(), CanError::kInvalidField);  // guarding toggle bit
  EXPECT_EQ(decode_heartbeat(raw(0x705, {})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_heartbeat(raw(0x705, {0x05, 0x00})).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_heartbeat(raw(0x700, {0x05})).error(), CanError::kInvalidId);
  EXPECT_EQ(decode_heartbeat(raw(0x705, {}, CanFrame::kRtr)).error(), CanError::kRemoteFrame);  // node guarding
  EXPECT_EQ(encode_heartbeat(0, NmtState::kOperational).error(), CanError::kInvalidNode);
}

// --- SDO --------------------------------------------------------------------------------------

TEST(Sdo, DownloadRequestRoundTripsEverySize) {
  const uint8_t specifier[] = {0, 0x2F, 0x2B, 0x27, 0x23};
  const uint32_t value[] = {0, 0xAB, 0xABCD, 0xABCDEF, 0xABCDEF01};
  for (uint8_t size = 1; size <= 4; ++size) {
    const auto f = encode_sdo_download_request(3, 0x607A, 0, value[size], size);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(f->id, 0x603u);
    EXPECT_EQ(f->dlc, 8);
    EXPECT_EQ(f->data[0], specifier[size]);
    EXPECT_EQ(f->data[1], 0x7A);
    EXPECT_EQ(f->data[2], 0x60);
    const auto m = decode_sdo_request(*f);
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(m->type, SdoType::kDownloadRequest);
    EXPECT_EQ(m->node, 3);
    EXPECT_EQ(m->index, 0x607A);
    EXPECT_EQ(m->subindex, 0);
    EXPECT_EQ(m->size, size);
    EXPECT_EQ(m->data, value[size]);
  }
}

TEST(Sdo, UploadRequestAndResponsesRoundTrip) {
  const auto up = encode_sdo_upload_request(3, 0x1018, 2);
  ASSERT_TRUE(up.ok());
  EXPECT_EQ(up->data[0], 0x40);
  const auto upm = decode_sdo_request(*up);
  ASSERT_TRUE(upm.ok());
  EXPECT_EQ(upm->type, SdoType::kUploadRequest);
  EXPECT_EQ(upm->index, 0x1018);
  EXPECT_EQ(upm->subindex, 2);

  const uint8_t specifier[] = {0, 0x4F, 0x4B, 0x47, 0x43};
  for (uint8_t size = 1; size <= 4; ++size) {
    const auto f = encode_sdo_upload_response(3, 0x6041, 0, 0x37, size);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(f->id, 0x583u);
    EXPECT_EQ(f->data[0], specifier[size]);
    const auto m = decode_sdo_response(*f);
    ASSERT_TRUE(m.ok());
    EXPECT_EQ(m->type, SdoType::kUploadResponse);
    EXPECT_EQ(m->size, size);
    EXPECT_EQ(m->data, 0x37u);
  }

  const auto ack = encode_sdo_download_response(3, 0x6040, 0);
  ASSERT_TRUE(ack.ok());
  EXPECT_EQ(ack->data[0], 0x60);
  const auto ackm = decode_sdo_response(*ack);
  ASSERT_TRUE(ackm.ok());
  EXPECT_EQ(ackm->type, SdoType::kDownloadResponse);
  EXPECT_EQ(ackm->index, 0x6040);
}

TEST(Sdo, AbortRoundTripsFromBothSides) {
  const auto server = encode_sdo_abort(3, 0x1234, 5, sdo_abort::kNoObject, true);
  ASSERT_TRUE(server.ok());
  EXPECT_EQ(server->id, 0x583u);
  EXPECT_EQ(server->data[0], 0x80);
  EXPECT_EQ(server->data[7], 0x06);  // 0x06020000 little-endian
  const auto m = decode_sdo_response(*server);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->type, SdoType::kAbort);
  EXPECT_EQ(m->abort_code, sdo_abort::kNoObject);
  EXPECT_EQ(m->index, 0x1234);
  EXPECT_EQ(m->subindex, 5);

  const auto client = encode_sdo_abort(3, 0x1234, 5, sdo_abort::kTimeout, false);
  ASSERT_TRUE(client.ok());
  EXPECT_EQ(client->id, 0x603u);
  const auto c = decode_sdo_request(*client);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->type, SdoType::kAbort);
  EXPECT_EQ(c->abort_code, sdo_abort::kTimeout);
}

TEST(Sdo, ExpeditedWithoutSizeIndicatedHasSizeZero) {
  const auto m = decode_sdo_request(raw(0x603, {0x22, 0x17, 0x10, 0x00, 0x64, 0x00, 0x00, 0x00}));
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->size, 0);
  EXPECT_EQ(m->data, 100u);
}

TEST(Sdo, EncodersRejectValuesTooWideAndBadNodes) {
  EXPECT_EQ(encode_sdo_download_request(3, 0x6060, 0, 0x100, 1).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(encode_sdo_download_request(3, 0x6060, 0, 1, 0).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(encode_sdo_download_request(3, 0x6060, 0, 1, 5).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(encode_sdo_upload_response(3, 0x6041, 0, 0x10000, 2).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(encode_sdo_upload_request(0, 0x6041, 0).error(), CanError::kInvalidNode);
  EXPECT_EQ(encode_sdo_abort(128, 0x6041, 0, 0, true).error(), CanError::kInvalidNode);
}

TEST(Sdo, DecodersRejectWrongDlcAndIds) {
  const CanFrame ok = *encode_sdo_upload_request(3, 0x6041, 0);
  EXPECT_EQ(decode_sdo_request(with_dlc(ok, 7)).error(), CanError::kInvalidDlc);
  EXPECT_EQ(decode_sdo_request(with_dlc(ok, 4)).error(), CanError::kInvalidDlc);
  // a request is not a response and vice versa
  EXPECT_EQ(decode_sdo_response(ok).error(), CanError::kInvalidId);
  EXPECT_EQ(decode_sdo_request(*encode_sdo_download_response(3, 0x6040, 0)).error(), CanError::kInvalidId);
  EXPECT_EQ(decode_sdo_request(raw(0x600, {0x40, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidId);
  CanFrame rtr = ok;
  rtr.flags = CanFrame::kRtr;
  EXPECT_EQ(decode_sdo_request(rtr).error(), CanError::kRemoteFrame);
}

TEST(Sdo, DecodersReportSegmentedAndBlockAsUnsupported) {
  // requests: download segment (ccs 0), initiate segmented download (e = 0), upload segment,
  // block upload, block download
  for (uint8_t cs : {uint8_t{0x00}, uint8_t{0x21}, uint8_t{0x60}, uint8_t{0xA0}, uint8_t{0xC0}}) {
    EXPECT_EQ(decode_sdo_request(raw(0x603, {cs, 0, 0x10, 0, 0, 0, 0, 0})).error(), CanError::kUnsupported)
        << std::hex << int{cs};
  }
  // responses: segmented upload (e = 0), upload segment, download segment response, block
  for (uint8_t cs : {uint8_t{0x41}, uint8_t{0x00}, uint8_t{0x20}, uint8_t{0xA0}, uint8_t{0xC0}}) {
    EXPECT_EQ(decode_sdo_response(raw(0x583, {cs, 0, 0x10, 0, 0, 0, 0, 0})).error(), CanError::kUnsupported)
        << std::hex << int{cs};
  }
}

TEST(Sdo, DecodersRejectUnknownSpecifiersAndReservedBits) {
  EXPECT_EQ(decode_sdo_request(raw(0x603, {0xE0, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_request(raw(0x603, {0x41, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_request(raw(0x603, {0x33, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_request(raw(0x603, {0x2A, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_response(raw(0x583, {0x61, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_response(raw(0x583, {0x81, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
  EXPECT_EQ(decode_sdo_response(raw(0x583, {0xE0, 0, 0, 0, 0, 0, 0, 0})).error(), CanError::kInvalidCommand);
}

// --- PDO --------------------------------------------------------------------------------------

TEST(Pdo, MapEntryConvertsToAndFromMappingObjectValue) {
  const PdoMapEntry e{0x607A, 0, 32};
  EXPECT_EQ(e.to_u32(), 0x607A0020u);
  EXPECT_EQ(PdoMapEntry::from_u32(0x60410010), (PdoMapEntry{0x6041, 0, 16}));
  EXPECT_TRUE(kDummy32.dummy());
  EXPECT_FALSE(e.dummy());
}

TEST(Pdo, PacksTpdoOfPositionCurrentStatuswordLittleEndian) {
  const auto mapping = PdoMapping::make({{0x6064, 0, 32}, {0x6078, 0, 16}, {0x6041, 0, 16}});
  ASSERT_TRUE(mapping.ok());
  EXPECT_EQ(mapping->dlc(), 8);
  EXPECT_EQ(mapping->total_bits(), 64u);
  const uint64_t values[] = {static_cast<uint32_t>(-2), static_cast<uint16_t>(-5), 0x1237};
  const auto f = encode_pdo(0x181, *mapping, values);
  ASSERT_TRUE(f.ok());
  const uint8_t expected[] = {0xFE, 0xFF, 0xFF, 0xFF, 0xFB, 0xFF, 0x37, 0x12};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(f->data[i], expected[i]) << i;
  uint64_t out[3];
  ASSERT_EQ(decode_pdo(*f, *mapping, out), CanError::kNone);
  EXPECT_EQ(sign_extend(out[0], 32), -2);
  EXPECT_EQ(sign_extend(out[1], 16), -5);
  EXPECT_EQ(out[2], 0x1237u);
}

TEST(Pdo, RoundTripsOddBitWidths) {
  const auto mapping =
      PdoMapping::make({{0x2000, 1, 1}, {0x2000, 2, 7}, {0x2000, 3, 12}, {0x2000, 4, 20}, {0x2000, 5, 24}});
  ASSERT_TRUE(mapping.ok());
  EXPECT_EQ(mapping->total_bits(), 64u);
  EXPECT_EQ(mapping->offset_bits(3), 20u);
  const uint64_t values[] = {1, 0x55, 0xABC, 0xFEDCB, 0x123456};
  const auto f = encode_pdo(0x200, *mapping, values);
  ASSERT_TRUE(f.ok());
  uint64_t out[5];
  ASSERT_EQ(decode_pdo(*f, *mapping, out), CanError::kNone);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(out[i], values[i]) << i;
  // values wider than their entry are truncated, not spilled into the neighbours
  const uint64_t wide[] = {3, 0xFF, 0, 0, 0};
  ASSERT_EQ(decode_pdo(*encode_pdo(0x200, *mapping, wide), *mapping, out), CanError::kNone);
  EXPECT_EQ(out[0], 1u);
  EXPECT_EQ(out[1], 0x7Fu);
  EXPECT_EQ(out[2], 0u);
}

TEST(Pdo, DummyEntriesSkipOtherNodesBytes) {
  const auto first = *PdoMapping::make({{0x607A, 0, 32}, kDummy32});
  const auto second = *PdoMapping::make({kDummy32, {0x607A, 0, 32}});
  const auto full = *PdoMapping::make({{0x607A, 0, 32}, {0x607A, 0, 32}});
  const uint64_t targets[] = {1000, static_cast<uint32_t>(-2000)};
  const auto f = encode_pdo(0x301, full, targets);
  ASSERT_TRUE(f.ok());
  uint64_t a[2];
  uint64_t b[2];
  ASSERT_EQ(decode_pdo(*f, first, a), CanError::kNone);
  ASSERT_EQ(decode_pdo(*f, second, b), CanError::kNone);
  EXPECT_EQ(a[0], 1000u);
  EXPECT_EQ(a[1], 0u);
  EXPECT_EQ(b[0], 0u);
  EXPECT_EQ(sign_extend(b[1], 32), -2000);
}

TEST(Pdo, MappingRejectsTooManyBitsOrEntries) {
  PdoMapping m;
  EXPECT_EQ(m.add({0x6064, 0, 32}), CanError::kNone);
  EXPECT_EQ(m.add({0x6064, 0, 32}), CanError::kNone);
  EXPECT_EQ(m.add({0x6041, 0, 16}), CanError::kMappingTooLong);
  EXPECT_EQ(m.size(), 2u);
  PdoMapping z;
  EXPECT_EQ(z.add({0x6041, 0, 0}), CanError::kInvalidMapping);
  EXPECT_EQ(z.add({0x6041, 0, 65}), CanError::kInvalidMapping);
  PdoMapping nine;
  for (int i = 0; i < 8; ++i) EXPECT_EQ(nine.add({0x2000, 0, 1}), CanError::kNone);
  EXPECT_EQ(nine.add({0x2000, 0, 1}), CanError::kInvalidMapping);
  EXPECT_EQ(PdoMapping::make({{0x6064, 0, 32}, {0x6064, 0, 32}, {0x6041, 0, 8}}).error(), CanError::kMappingTooLong);
}

TEST(Pdo, DecodeRejectsShortFrameAndAcceptsLongerOne) {
  const auto mapping = *PdoMapping::make({{0x6040, 0, 16}, {0x607A, 0, 32}});
  const uint64_t values[] = {0x0F, 1234};
  CanFrame f = *encode_pdo(0x201, mapping, values);
  EXPECT_EQ(f.dlc, 6);
  uint64_t out[2];
  EXPECT_EQ(decode_pdo(with_dlc(f, 5), mapping, out), CanError::kInvalidDlc);
  EXPECT_EQ(decode_pdo(with_dlc(f, 8), mapping, out), CanError::kNone);
  EXPECT_EQ(out[1], 1234u);
  CanFrame rtr = f;
  rtr.flags = CanFrame::kRtr;
  EXPECT_EQ(decode_pdo(rtr, mapping, out), CanError::kRemoteFrame);
  uint64_t too_few[1];
  EXPECT_EQ(decode_pdo(f, mapping, too_few), CanError::kInvalidMapping);
}

TEST(Pdo, EncodeRejectsValueCountMismatchAndLongId) {
  const auto mapping = *PdoMapping::make({{0x6040, 0, 16}});
  const uint64_t two[] = {1, 2};
  EXPECT_EQ(encode_pdo(0x201, mapping, two).error(), CanError::kInvalidMapping);
  const uint64_t one[] = {1};
  EXPECT_EQ(encode_pdo(0x800, mapping, one).error(), CanError::kInvalidId);
}

TEST(Pdo, SignExtendsAnyWidth) {
  EXPECT_EQ(sign_extend(0xFF, 8), -1);
  EXPECT_EQ(sign_extend(0x7F, 8), 127);
  EXPECT_EQ(sign_extend(0x800, 12), -2048);
  EXPECT_EQ(sign_extend(0xFFFFFFFF, 32), -1);
  EXPECT_EQ(sign_extend(0x80000000, 32), INT32_MIN);
  EXPECT_EQ(sign_extend(~uint64_t{0}, 64), -1);
  EXPECT_EQ(sign_extend(5, 0), 0);
}

// --- real-time discipline -----------------------------------------------------------------------

TEST(Cia301, EncodeAndDecodeDoNotAllocate) {
  const auto mapping = *PdoMapping::make({{0x6064, 0, 32}, {0x6078, 0, 16}, {0x6041, 0, 16}});
  const uint64_t values[] = {1, 2, 3};
  uint64_t out[3];
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(decode_nmt(*encode_nmt(NmtCommand::kStart, 1)).ok());
    ASSERT_TRUE(decode_sync(*encode_sync(3)).ok());
    ASSERT_TRUE(decode_emcy(*encode_emcy({1, 0x2310, 3, {}})).ok());
    ASSERT_TRUE(decode_heartbeat(*encode_heartbeat(1, NmtState::kOperational)).ok());
    ASSERT_TRUE(decode_sdo_request(*encode_sdo_download_request(1, 0x6040, 0, 6, 2)).ok());
    ASSERT_TRUE(decode_sdo_response(*encode_sdo_upload_response(1, 0x6041, 0, 0x237, 2)).ok());
    ASSERT_EQ(decode_pdo(*encode_pdo(0x181, mapping, values), mapping, out), CanError::kNone);
    ASSERT_EQ(classify(*encode_sync()).service, Service::kSync);
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::can
