#pragma once
// Streaming LAS/LAZ writer: points go to disk in chunks, never the whole cloud in memory.
//
// The file is written under a temporary name in the same folder, the header (counts, points by return, bounds
// from the stored integers) is patched at Close(), the data are fsynced, and only then is the file renamed to
// its final path. A writer destroyed without Close() (an exception, a crash) removes its temporary file, so a
// complete-looking file at the final path is always complete. Follows every rule of
// ../shared/reference/jobs-and-las.md part B.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/point.h"
#include "io/las_types.h"

namespace sacfuse {

class LasReader;

struct LasWriterOptions {
  // 4: LAS 1.4 with point format 7 (default). 2: LAS 1.2 with point format 3.
  int version_minor = 4;
  // Quantisation step, metres, all three axes. Must be 10^k x {1, 0.5, 0.25}.
  double scale_m = 0.001;
  // Offset, metres. When unset it is taken from the first point written, snapped down to a multiple of
  // 1000 m, so UTM-sized coordinates fit int32 (+-2147 km at 1 mm). Tiles of one job pass one shared offset.
  std::optional<Eigen::Vector3d> offset;
  std::string system_identifier = "sacfuse";
  std::string generating_software = "sacfuse";  // the CLI sets "sacfuse <version>"
  // Extra VLRs written after the header (e.g. the CRS; issue 5 fills them).
  std::vector<LasVlr> vlrs;
  uint16_t global_encoding_extra_bits = 0;  // e.g. 0x10 (WKT) when a WKT VLR is given for LAS 1.4
  // Point data record format; unset: 7 for LAS 1.4, 3 for LAS 1.2. LAS 1.2 takes 0-3, LAS 1.4 takes 0-3 and 6-8
  // (waveform formats 4, 5, 9, 10 are not written). Fields a format lacks must be zero in the points written.
  std::optional<int> point_format;
  // Per-axis quantisation step overriding scale_m (round trips of third-party files); each 10^k x {1, 0.5, 0.25}.
  std::optional<Eigen::Vector3d> scale_xyz;
  // Write LAZ (LASzip-compressed; io/laz_chunk_writer.h): point format id with bit 7 set, a "laszip encoded" VLR,
  // 50,000 points a chunk (memory bounded by one chunk), the chunk table after the last chunk, EVLRs after it.
  // Point formats 0-3 and 6-8 as for LAS. A "laszip encoded" VLR given in `vlrs` is never copied.
  bool compressed = false;
};

// A LAZ file's points ready to be appended (LasWriter::PrepareLazAppend): its full chunks, copied as stored when
// appended, and its last, shorter chunk decoded, checked and stored as the writer's records.
struct LazAppendPart {
  uint64_t full_chunks = 0;
  size_t tail_points = 0;                     // the last chunk's points
  std::vector<uint8_t> tail_records;          // ... as the writer's records, one after another
  std::array<int32_t, 3> tail_min = {};       // their stored integers' bounds (when tail_points > 0)
  std::array<int32_t, 3> tail_max = {};
  std::array<uint64_t, 15> tail_returns = {};    // their returns
  std::array<int32_t, 3> stored_min = {};     // the header's bounds as stored integers
  std::array<int32_t, 3> stored_max = {};
  std::array<uint64_t, 15> copied_returns = {};  // the header's returns less the tail's: the full chunks'
};

class LasWriter : public PointSink {
 public:
  // Throws sacfuse::Error when the temporary file cannot be created or the options break a LAS rule.
  LasWriter(const std::string& path, const LasWriterOptions& options);
  ~LasWriter() override;  // removes the temporary file unless Close() succeeded
  LasWriter(const LasWriter&) = delete;
  LasWriter& operator=(const LasWriter&) = delete;

  // Fused points: point source ID = view_index + 1, RGB scaled from 8 to 16 bit, return 1 of 1.
  void Write(const FusedPoint* points, size_t count) override;
  // General points (reference clouds, round trips of third-party files), every field as given.
  // Both throw sacfuse::Error naming the file and the point for a value the format cannot hold (a coordinate
  // outside int32 after quantisation, view index >= 65535, classification > 31 in PDRF 0-3, a field the format
  // lacks...); nothing is clamped, and a rejected chunk is not written at all (the writer stays usable).
  void WritePoints(const LasPoint* points, size_t count);
  // Appends every point of `reader` (rewound first) without decoding most of them, when it is a LAZ file with
  // this writer's compressed layout (the same "laszip encoded" VLR: point format, record length, items, chunk
  // size), scale and offset: its full chunks are copied as stored, the points of its last, shorter chunk go
  // through WritePoints. Copied chunks land before records still buffered, so the file's point order is not the
  // order of the calls (the points are the same). Counts, bounds and returns of the copied chunks come from
  // `reader`'s header. Returns false, having written nothing, when `reader` does not qualify (then Read its
  // points and WritePoints them).
  bool AppendLaz(LasReader& reader);
  // AppendLaz in two steps, so that the files of a merge can be made ready on several threads while the writer
  // appends earlier ones in order. PrepareLazAppend checks `reader`'s layout against this writer's, decodes its
  // last, shorter chunk and stores those points as this writer's records (the checks and encoding WritePoints
  // does; a point the format cannot hold throws InputError naming `reader`'s file and the point); it reads only
  // what is fixed once set (the writer's layout, and its offset, given in the options or taken from the first
  // points written), so with an offset in the options it may run on any thread while another appends. nullopt,
  // having written nothing, when `reader` does not qualify. AppendLaz(reader, part) then copies `reader`'s full
  // chunks (from its start) and the prepared records: the same file as AppendLaz(reader).
  std::optional<LazAppendPart> PrepareLazAppend(LasReader& reader) const;
  void AppendLaz(LasReader& reader, const LazAppendPart& part);
  // Patches the header, fsyncs, renames into place. Throws on I/O errors (and leaves no file at the path).
  void Close();

  uint64_t num_points() const;
  const std::string& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sacfuse
