#pragma once
// One chunk of LAZ point data (LASzip compressed data format, "chunks"): the chunk's first record is stored raw
// and initialises every item codec; the following records are coded either point-wise (compressor 2: one
// arithmetic stream for all items of point formats 0-3) or layered (compressor 3, point formats 6-8: the point
// count, the byte size of each layer, then the layers, a layer whose field never changed being left out).
// Private to io/.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "io/laz_arithmetic.h"
#include "io/laz_vlr.h"

namespace sacfuse::laz {

struct ItemCodecs;  // the codecs of the VLR's items (laz_chunk_codec.cc)

class ChunkEncoder {
 public:
  // `vlr` must be supported for the record layout (LazVlr::Unsupported() == "").
  ChunkEncoder(const LazVlr& vlr, size_t record_length);
  ~ChunkEncoder();
  // Appends one chunk of `count` >= 1 records to *out.
  void Encode(const uint8_t* records, size_t count, std::vector<uint8_t>* out);

 private:
  bool layered_;
  size_t record_length_;
  std::unique_ptr<ItemCodecs> items_;
  std::vector<std::vector<uint8_t>> layer_bytes_;
};

class ChunkDecoder {
 public:
  ChunkDecoder(const LazVlr& vlr, size_t record_length);
  ~ChunkDecoder();
  // Starts a chunk of `count` >= 1 points from its bytes (which must stay valid while it is decoded). Throws
  // laz::DataError when the chunk's framing is inconsistent.
  void Start(const uint8_t* data, size_t size, uint64_t count);
  // The next record of the chunk; throws laz::DataError on corrupt data.
  void Next(uint8_t* record);

 private:
  bool layered_;
  size_t record_length_;
  std::unique_ptr<ItemCodecs> items_;
  std::vector<uint8_t> first_;
  Decoder pointwise_;
  std::vector<Decoder> layers_;
  uint64_t count_ = 0;
  uint64_t next_ = 0;
};

}  // namespace sacfuse::laz
