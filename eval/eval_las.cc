// EvaluateLasFiles: the file front end of eval.h.
#include <cmath>
#include <filesystem>
#include <functional>
#include <new>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/geo_mask_io.h"
#include "io/input_file.h"
#include "io/las_reader.h"
#include "eval/eval.h"

namespace sacfuse {
namespace {

// Streams the points of a LAS file in chunks to `chunk` (after the header is read, `on_count` receives the file's
// point count); every failure but a thrown InputError or bad_alloc becomes an InputError naming the file.
void ForEachLasChunk(const std::string& path, const std::function<void(uint64_t)>& on_count,
                     const std::function<void(const std::vector<LasPoint>&)>& chunk) {
  CheckInputFile(path, "LAS file");  // the one gate (io/input_file.h): missing, a FIFO, a folder, a link loop...
  try {
    LasReader reader(path);
    if (on_count) on_count(reader.header().point_count);
    std::vector<LasPoint> points;
    while (reader.Read(&points, 1 << 16) > 0) chunk(points);
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read LAS file: ") + e.what());
  }
}

// The coordinates (and point source IDs) of a LAS file: every `stride`-th point (the first, then every stride-th
// after it), stride = ceil(count / max_points) beyond max_points (0 = all); *count receives the file's count.
// Each chunk is copied in parallel into its places.
void ReadLasCoordinates(const std::string& path, std::vector<Eigen::Vector3d>* xyz, std::vector<uint16_t>* ids,
                        double max_points = 0, uint64_t* stride_out = nullptr, uint64_t* count_out = nullptr) {
  uint64_t stride = 1, index = 0;
  ForEachLasChunk(
      path,
      [&](uint64_t count) {
        stride = max_points > 0 && count > max_points ? static_cast<uint64_t>(std::ceil(count / max_points)) : 1;
        if (stride_out != nullptr) *stride_out = stride;
        if (count_out != nullptr) *count_out = count;
        xyz->reserve(static_cast<size_t>(count / stride + 1));
        if (ids != nullptr) ids->reserve(static_cast<size_t>(count / stride + 1));
      },
      [&](const std::vector<LasPoint>& chunk) {
        // Kept: the points whose index in the file is a multiple of the stride.
        const uint64_t first_kept = (index + stride - 1) / stride;
        const uint64_t end_kept = (index + chunk.size() + stride - 1) / stride;
        const size_t at = xyz->size();
        xyz->resize(at + static_cast<size_t>(end_kept - first_kept));
        if (ids != nullptr) ids->resize(xyz->size());
        tbb::parallel_for(tbb::blocked_range<uint64_t>(first_kept, end_kept, 4096),
                          [&](const tbb::blocked_range<uint64_t>& r) {
                            for (uint64_t k = r.begin(); k < r.end(); ++k) {
                              const LasPoint& p = chunk[static_cast<size_t>(k * stride - index)];
                              (*xyz)[at + static_cast<size_t>(k - first_kept)] = p.xyz;
                              if (ids != nullptr) (*ids)[at + static_cast<size_t>(k - first_kept)] = p.point_source_id;
                            }
                          });
        index += chunk.size();
      });
}

}  // namespace

EvalReport EvaluateLasFiles(const std::string& result_las, const std::string& reference_las,
                            const EvalOptions& options) {
  ValidateEvalOptions(options);
  std::vector<Eigen::Vector3d> reference, result;
  std::vector<uint16_t> ids;
  ReadLasCoordinates(reference_las, &reference, nullptr);
  if (reference.empty()) throw InputError(reference_las, "the reference LAS file holds no points");
  uint64_t stride = 1, in_file = 0;
  ReadLasCoordinates(result_las, &result, &ids, options.max_result_points, &stride, &in_file);
  GeoMask mask;
  const bool has_mask = !options.mask_path.empty();
  if (has_mask) {
    try {
      mask = ReadGeoMask(options.mask_path);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(options.mask_path, std::string("cannot read the evaluation mask: ") + e.what());
    }
  }
  // A thinned cloud understates completeness at thresholds near its point spacing, so completeness is measured
  // against every point, read again in chunks.
  ResultChunks all_points;
  if (stride > 1) {
    all_points = [&result_las](const std::function<void(const std::vector<Eigen::Vector3d>&)>& chunk) {
      std::vector<Eigen::Vector3d> xyz;
      ForEachLasChunk(result_las, {}, [&](const std::vector<LasPoint>& points) {
        xyz.resize(points.size());
        for (size_t i = 0; i < points.size(); ++i) xyz[i] = points[i].xyz;
        chunk(xyz);
      });
    };
  }
  EvalReport report = EvaluateClouds(result, ids, reference, has_mask ? &mask : nullptr, options, all_points);
  report.result_points_in_file = in_file;
  report.result_stride = stride;
  return report;
}

}  // namespace sacfuse
