#include "mcap_compression.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

namespace teleop::bag::mcap {
namespace {

// level 1: a recorder keeps up with the bus on a loaded host; higher levels gain little on CDR
constexpr int kZstdLevel = 1;
// lz4 expands a byte to at most ~255: a larger claimed size is a corrupt field, not allocated
constexpr uint64_t kLz4MaxRatio = 256;
constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 31;

// the size a chunk claims, checked against its compressed data before any buffer is sized by it
void check_claimed_size(Compression c, ByteSpan in, uint64_t size, const std::string& what) {
  bool plausible = size <= kMaxChunkBytes;
  if (c == Compression::kZstd) {
    const unsigned long long framed = ZSTD_getFrameContentSize(in.data, in.size);
    plausible = plausible && (framed == ZSTD_CONTENTSIZE_UNKNOWN || framed == size);
    plausible = plausible && framed != ZSTD_CONTENTSIZE_ERROR;
  } else if (c == Compression::kLz4) {
    plausible = plausible && size <= in.size * kLz4MaxRatio + 65536;
  } else {
    plausible = plausible && size == in.size;
  }
  if (!plausible) throw BagError(what + ": corrupt (its uncompressed size " + std::to_string(size) + " cannot be)");
}

void compress_zstd(ByteSpan in, std::vector<uint8_t>& out) {
  out.resize(ZSTD_compressBound(in.size));
  const size_t n = ZSTD_compress(out.data(), out.size(), in.data, in.size, kZstdLevel);
  if (ZSTD_isError(n)) throw BagError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
  out.resize(n);
}

void compress_lz4(ByteSpan in, std::vector<uint8_t>& out) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = in.size;  // lets a reader size its buffer
  out.resize(LZ4F_compressFrameBound(in.size, &prefs));
  const size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data, in.size, &prefs);
  if (LZ4F_isError(n)) throw BagError(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
  out.resize(n);
}

void decompress_zstd(ByteSpan in, std::vector<uint8_t>& out, const std::string& what) {
  const size_t n = ZSTD_decompress(out.data(), out.size(), in.data, in.size);
  if (ZSTD_isError(n)) throw BagError(what + ": corrupt zstd data (" + ZSTD_getErrorName(n) + ")");
  if (n != out.size()) throw BagError(what + ": zstd data decompresses to a size other than the chunk says");
}

struct Lz4Context {
  LZ4F_dctx* dctx = nullptr;
  ~Lz4Context() { LZ4F_freeDecompressionContext(dctx); }
};

void decompress_lz4(ByteSpan in, std::vector<uint8_t>& out, const std::string& what) {
  Lz4Context ctx;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx.dctx, LZ4F_VERSION))) throw BagError(what + ": lz4 init");
  size_t in_at = 0;
  size_t out_at = 0;
  size_t hint = 1;
  while (hint != 0) {
    size_t in_n = in.size - in_at;
    size_t out_n = out.size() - out_at;
    hint = LZ4F_decompress(ctx.dctx, out.data() + out_at, &out_n, in.data + in_at, &in_n, nullptr);
    if (LZ4F_isError(hint)) throw BagError(what + ": corrupt lz4 data (" + LZ4F_getErrorName(hint) + ")");
    in_at += in_n;
    out_at += out_n;
    // no progress with input left or output full: the frame is longer than the chunk says
    if (hint != 0 && in_n == 0 && out_n == 0) throw BagError(what + ": lz4 data truncated or larger than its chunk");
  }
  if (out_at != out.size()) throw BagError(what + ": lz4 data decompresses to a size other than the chunk says");
}

}  // namespace

const char* compression_name(Compression c) {
  switch (c) {
    case Compression::kZstd: return "zstd";
    case Compression::kLz4: return "lz4";
    case Compression::kNone: break;
  }
  return "";
}

Compression compression_named(const std::string& name, const std::string& what) {
  if (name == "zstd") return Compression::kZstd;
  if (name == "lz4") return Compression::kLz4;
  if (name.empty()) return Compression::kNone;
  throw BagError(what + ": compression \"" + name + "\" is not one teleop reads (zstd, lz4, none)");
}

void compress(Compression c, ByteSpan in, std::vector<uint8_t>& out) {
  switch (c) {
    case Compression::kZstd: return compress_zstd(in, out);
    case Compression::kLz4: return compress_lz4(in, out);
    case Compression::kNone: out.assign(in.data, in.data + in.size); return;
  }
}

void decompress(Compression c, ByteSpan in, uint64_t size, std::vector<uint8_t>& out, const std::string& what) {
  check_claimed_size(c, in, size, what);
  out.resize(static_cast<size_t>(size));
  switch (c) {
    case Compression::kZstd: return decompress_zstd(in, out, what);
    case Compression::kLz4: return decompress_lz4(in, out, what);
    case Compression::kNone: break;
  }
  if (size > 0) out.assign(in.data, in.data + in.size);
}

uint32_t crc32_of(ByteSpan bytes, uint32_t crc) {
  // zlib takes a uInt length: feed a large span in pieces
  while (bytes.size > 0) {
    const auto n = static_cast<uInt>(std::min<size_t>(bytes.size, 1u << 30));
    crc = static_cast<uint32_t>(::crc32(crc, bytes.data, n));
    bytes.data += n;
    bytes.size -= n;
  }
  return crc;
}

}  // namespace teleop::bag::mcap
