#pragma once
// A point cloud file being written, whatever its layout: LAS or LAZ (io/las_writer.h) or COPC (io/copc_writer.h).
// Jobs write the fused cloud and the tile files through this, the layout chosen once by the options.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/point.h"
#include "io/las_types.h"
#include "io/las_writer.h"
#include "io/copc_writer.h"

namespace sacfuse {

class LasReader;

class PointCloudWriter : public PointSink {
 public:
  // Every field as given (LasWriter::WritePoints).
  virtual void WritePoints(const LasPoint* points, size_t count) = 0;
  // Appending the points of `reader` by copying its LAZ chunks when its layout is this writer's, in two steps
  // (LasWriter::PrepareLazAppend, AppendLaz): the first may run on other threads while this writer appends;
  // nullopt, having written nothing, when it cannot (then read the points and WritePoints them).
  virtual std::optional<LazAppendPart> PrepareLazAppend(LasReader& reader) const = 0;
  virtual void AppendLaz(LasReader& reader, const LazAppendPart& part) = 0;
  // Finishes the file (written under a temporary name, renamed into place); throws on I/O errors.
  virtual void Close() = 0;
  virtual uint64_t num_points() const = 0;
};

struct CloudFileOptions {
  LasWriterOptions las;
  std::optional<CopcOptions> copc;  // set: a COPC file (las: LAS 1.4, point format 6-8)
};

std::unique_ptr<PointCloudWriter> OpenPointCloudWriter(const std::string& path, const CloudFileOptions& options);

}  // namespace sacfuse
