// Round trips of the LAZ building blocks on hand-made sequences: the range coder with bit, symbol and raw-bit
// codes (including carries and 32-bit raw values), the integer compressor at several widths and extremes, the
// chunk table, and whole chunks of every supported point format with changing fields, extra bytes and (for
// point formats 6-8) several scanner channels.
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "io/las_format.h"
#include "io/laz_arithmetic.h"
#include "io/laz_chunk_codec.h"
#include "io/laz_chunk_table.h"
#include "io/laz_integer.h"
#include "io/laz_vlr.h"

namespace sacfuse::laz {
namespace {

namespace lf = las_format;

TEST(LazArithmeticTest, SymbolsBitsAndRawBitsRoundTrip) {
  std::mt19937 rng(7);
  struct Step {
    int kind;  // 0 bit, 1 symbol (skewed), 2 raw bits
    uint32_t bits;
    uint32_t value;
  };
  std::vector<Step> steps;
  for (int i = 0; i < 200000; ++i) {
    const int kind = static_cast<int>(rng() % 3);
    if (kind == 0) {
      steps.push_back({0, 0, (rng() % 10) == 0 ? 1u : 0u});  // mostly zeros: long runs force carries
    } else if (kind == 1) {
      const uint32_t s = (rng() % 4 == 0) ? rng() % 300 : rng() % 3;
      steps.push_back({1, 0, s});
    } else {
      const uint32_t bits = 1 + rng() % 32;
      steps.push_back({2, bits, bits == 32 ? static_cast<uint32_t>(rng()) : static_cast<uint32_t>(rng()) & ((1u << bits) - 1)});
    }
  }
  std::vector<uint8_t> bytes = {0xAB};  // a stream may start after other data
  {
    BitModel bit;
    SymbolModel symbol(300);
    Encoder enc;
    enc.Start(&bytes);
    for (const Step& s : steps) {
      if (s.kind == 0) enc.Bit(bit, s.value);
      if (s.kind == 1) enc.Symbol(symbol, s.value);
      if (s.kind == 2) enc.Bits(s.bits, s.value);
    }
    enc.Finish();
  }
  EXPECT_EQ(bytes[0], 0xAB);
  EXPECT_LT(bytes.size(), steps.size() * 2);  // compressed: far below 32 bits a step
  BitModel bit;
  SymbolModel symbol(300);
  Decoder dec;
  dec.Start(bytes.data() + 1, bytes.size() - 1);
  size_t bad = 0;
  for (const Step& s : steps) {
    uint32_t got = 0;
    if (s.kind == 0) got = dec.Bit(bit);
    if (s.kind == 1) got = dec.Symbol(symbol);
    if (s.kind == 2) got = dec.Bits(s.bits);
    if (got != s.value && bad++ < 5) ADD_FAILURE() << "kind " << s.kind << ": " << got << " != " << s.value;
  }
  EXPECT_EQ(bad, 0u);
}

TEST(LazArithmeticTest, CarryIntoEarlierBytesIsExact) {
  // A skewed bit model coding long runs of ones keeps adding to the base: carries ripple through 0xFF bytes.
  std::vector<uint8_t> bytes;
  std::vector<uint32_t> seq;
  for (int i = 0; i < 50000; ++i) seq.push_back(i % 97 == 0 ? 0u : 1u);
  BitModel m;
  Encoder enc;
  enc.Start(&bytes);
  for (uint32_t b : seq) enc.Bit(m, b);
  enc.Finish();
  BitModel m2;
  Decoder dec;
  dec.Start(bytes.data(), bytes.size());
  for (size_t i = 0; i < seq.size(); ++i) ASSERT_EQ(dec.Bit(m2), seq[i]) << i;
}

TEST(LazArithmeticTest, TruncatedStreamThrowsInsteadOfReadingOn) {
  std::vector<uint8_t> bytes;
  SymbolModel m(256);
  Encoder enc;
  enc.Start(&bytes);
  for (int i = 0; i < 10000; ++i) enc.Bits(32, 0x9E3779B9u * static_cast<uint32_t>(i));
  enc.Finish();
  Decoder dec;
  dec.Start(bytes.data(), bytes.size() / 2);
  EXPECT_THROW(
      {
        for (int i = 0; i < 10000; ++i) dec.Bits(32);
      },
      DataError);
}

TEST(LazIntegerTest, RoundTripsAtSeveralWidthsAndExtremes) {
  const int32_t kMin = std::numeric_limits<int32_t>::min();
  const int32_t kMax = std::numeric_limits<int32_t>::max();
  struct Case {
    uint32_t bits;
    std::vector<std::pair<int32_t, int32_t>> pred_real;
  };
  std::vector<Case> cases = {
      {32, {{0, 0}, {0, 1}, {0, -1}, {kMax, kMin}, {kMin, kMax}, {0, kMin}, {5, kMax}, {-7, 300}, {1000, -1000}}},
      {16, {{0, 65535}, {65535, 0}, {30000, 30001}, {100, 99}, {0, 32768}, {40000, 7}}},
      {8, {{0, 255}, {255, 0}, {128, 127}, {3, 3}}},
  };
  std::mt19937 rng(3);
  for (Case& c : cases) {
    for (int i = 0; i < 5000; ++i) {
      const uint32_t mask = c.bits == 32 ? 0xFFFFFFFFu : (1u << c.bits) - 1;
      const int32_t pred = static_cast<int32_t>(rng() & mask);
      const int32_t real = static_cast<int32_t>((i % 2 ? rng() : pred + rng() % 50) & mask);
      c.pred_real.push_back({pred, real});
    }
    std::vector<uint8_t> bytes;
    IntegerCodec enc_ic(c.bits, 3);
    Encoder enc;
    enc.Start(&bytes);
    for (size_t i = 0; i < c.pred_real.size(); ++i) {
      enc_ic.Code(enc, c.pred_real[i].first, c.pred_real[i].second, static_cast<uint32_t>(i % 3));
    }
    enc.Finish();
    IntegerCodec dec_ic(c.bits, 3);
    Decoder dec;
    dec.Start(bytes.data(), bytes.size());
    for (size_t i = 0; i < c.pred_real.size(); ++i) {
      const int32_t got = dec_ic.Code(dec, c.pred_real[i].first, 0, static_cast<uint32_t>(i % 3));
      ASSERT_EQ(got, c.pred_real[i].second) << "bits " << c.bits << " step " << i;
    }
  }
}

TEST(LazChunkTableTest, RoundTripsFixedAndVariable) {
  std::vector<ChunkEntry> chunks = {{50000, 123456}, {50000, 98765}, {17, 400}, {1, 0x7FFFFFFF}, {3, 5}};
  for (bool variable : {false, true}) {
    const std::vector<uint8_t> bytes = EncodeChunkTable(chunks, variable);
    ASSERT_GE(bytes.size(), kChunkTableHeaderSize);
    EXPECT_EQ(lf::GetU32(&bytes[0]), 0u);
    EXPECT_EQ(lf::GetU32(&bytes[4]), chunks.size());
    const auto got = DecodeChunkTable(bytes.data() + 8, bytes.size() - 8, 5, variable);
    for (size_t i = 0; i < chunks.size(); ++i) {
      EXPECT_EQ(got[i].bytes, chunks[i].bytes);
      EXPECT_EQ(got[i].points, variable ? chunks[i].points : 0u);
    }
  }
  EXPECT_EQ(EncodeChunkTable({}, false).size(), kChunkTableHeaderSize);
}

// Records of point format `pdrf` with `extra` extra bytes whose fields change in the ways the codecs model.
std::vector<uint8_t> MakeRecords(int pdrf, size_t extra, size_t n, size_t length, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> records(n * length, 0);
  double t = 300000.0;
  int32_t x = 1000000, y = -2000000, z = 5000;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = &records[i * length];
    x += static_cast<int32_t>(rng() % 200) - 100;
    y += static_cast<int32_t>(rng() % 21) - 10;
    z = (i % 50 == 0) ? static_cast<int32_t>(rng()) : z + static_cast<int32_t>(rng() % 7) - 3;
    lf::PutI32(p, i % 1000 == 999 ? std::numeric_limits<int32_t>::min() : x);
    lf::PutI32(p + 4, y);
    lf::PutI32(p + 8, z);
    lf::PutU16(p + 12, static_cast<uint16_t>(i % 7 == 0 ? rng() : 1000 + i % 3));
    const uint32_t nret = 1 + (i / 3) % (pdrf >= 6 ? 15 : 7);
    const uint32_t r = 1 + i % nret;
    if (i % 11 == 0) t += (rng() % 2) ? 1e6 : 0.0;  // jumps to other sequences
    if (i % 3 == 0) t += 0.00001 * (1 + rng() % 4);
    const double time = (i % 29 == 0) ? -0.0 : t;
    if (pdrf < 6) {
      p[14] = static_cast<uint8_t>(r | (nret << 3) | ((i / 40) % 2) << 6 | ((i % 97 == 0) ? 0x80 : 0));
      p[15] = static_cast<uint8_t>((i / 100) % 32 | ((i % 13 == 0) ? 0x20 : 0));
      p[16] = static_cast<uint8_t>(static_cast<int8_t>(static_cast<int>(i % 61) - 30));
      p[17] = static_cast<uint8_t>(i / 500);
      lf::PutU16(p + 18, static_cast<uint16_t>(1 + i / 700));
      if (lf::HasGpsTime(pdrf)) lf::PutF64(p + 20, time);
      if (lf::HasRgb(pdrf)) {
        uint8_t* c = p + (pdrf == 2 ? 20 : 28);
        const uint16_t v = static_cast<uint16_t>(i % 5 == 0 ? rng() : 256 * (i % 256));
        lf::PutU16(c, v);
        lf::PutU16(c + 2, i % 3 == 0 ? v : static_cast<uint16_t>(v + 513));
        lf::PutU16(c + 4, static_cast<uint16_t>(rng() % 65536));
      }
    } else {
      p[14] = static_cast<uint8_t>(r | (nret << 4));
      const uint32_t channel = (i / 7) % 4 == 3 ? (i % 4) : (i / 300) % 2;
      p[15] = static_cast<uint8_t>((i % 17 == 0 ? 0x5 : 0) | channel << 4 | ((i / 40) % 2) << 6);
      p[16] = static_cast<uint8_t>((i / 100) % 256);
      p[17] = static_cast<uint8_t>(i / 500);
      lf::PutU16(p + 18, static_cast<uint16_t>(static_cast<int16_t>(static_cast<int>(i % 5001) - 2500)));
      lf::PutU16(p + 20, static_cast<uint16_t>(1 + i / 700));
      lf::PutF64(p + 22, time);
      if (pdrf >= 7) {
        for (int c = 0; c < 3; ++c) lf::PutU16(p + 30 + 2 * c, static_cast<uint16_t>(i % 9 == 0 ? rng() : 4096 * c));
      }
      if (pdrf == 8) lf::PutU16(p + 36, static_cast<uint16_t>(i % 4 == 0 ? rng() : 77));
    }
    for (size_t e = 0; e < extra; ++e) p[length - extra + e] = static_cast<uint8_t>(e == 0 ? i : rng() % 3);
  }
  return records;
}

TEST(LazChunkCodecTest, EveryFormatRoundTripsThroughOneChunk) {
  for (int pdrf : {0, 1, 2, 3, 6, 7, 8}) {
    for (size_t extra : {size_t{0}, size_t{3}}) {
      for (size_t n : {size_t{1}, size_t{2}, size_t{5000}}) {
        SCOPED_TRACE("PDRF " + std::to_string(pdrf) + " extra " + std::to_string(extra) + " n " + std::to_string(n));
        const size_t length = lf::BaseRecordSize(pdrf) + extra;
        const LazVlr vlr = LazVlr::ForFormat(pdrf, static_cast<uint16_t>(extra));
        ASSERT_EQ(vlr.Unsupported(pdrf, length), "");
        const std::vector<uint8_t> records = MakeRecords(pdrf, extra, n, length, 11 + pdrf);
        std::vector<uint8_t> chunk = {1, 2, 3};
        ChunkEncoder enc(vlr, length);
        enc.Encode(records.data(), n, &chunk);
        if (n == 5000) EXPECT_LT(chunk.size(), records.size() / 2);
        ChunkDecoder dec(vlr, length);
        dec.Start(chunk.data() + 3, chunk.size() - 3, n);
        std::vector<uint8_t> got(length);
        for (size_t i = 0; i < n; ++i) {
          dec.Next(got.data());
          ASSERT_EQ(0, std::memcmp(got.data(), &records[i * length], length)) << "record " << i;
        }
        EXPECT_THROW(dec.Next(got.data()), DataError);
        // The encoder is reusable: a second chunk gives the same bytes.
        std::vector<uint8_t> again = {1, 2, 3};
        enc.Encode(records.data(), n, &again);
        EXPECT_EQ(again, chunk);
      }
    }
  }
}

}  // namespace
}  // namespace sacfuse::laz
