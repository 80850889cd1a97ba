// EvaluateLasFiles: the file front end of eval.h.
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/geo_mask_io.h"
#include "io/las_reader.h"
#include "tools/eval/eval.h"

namespace sacfuse {
namespace {

// Streams the coordinates (and point source IDs) of a LAS file; every failure becomes an InputError naming it.
void ReadLasCoordinates(const std::string& path, std::vector<Eigen::Vector3d>* xyz, std::vector<uint16_t>* ids) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "no such LAS file");
  try {
    LasReader reader(path);
    const uint64_t count = reader.header().point_count;
    xyz->reserve(static_cast<size_t>(count));
    if (ids != nullptr) ids->reserve(static_cast<size_t>(count));
    std::vector<LasPoint> chunk;
    while (reader.Read(&chunk, 1 << 16) > 0) {
      for (const LasPoint& p : chunk) {
        xyz->push_back(p.xyz);
        if (ids != nullptr) ids->push_back(p.point_source_id);
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read LAS file: ") + e.what());
  }
}

}  // namespace

EvalReport EvaluateLasFiles(const std::string& result_las, const std::string& reference_las,
                            const EvalOptions& options) {
  ValidateEvalOptions(options);
  std::vector<Eigen::Vector3d> reference, result;
  std::vector<uint16_t> ids;
  ReadLasCoordinates(reference_las, &reference, nullptr);
  if (reference.empty()) throw InputError(reference_las, "the reference LAS file holds no points");
  ReadLasCoordinates(result_las, &result, &ids);
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
  return EvaluateClouds(result, ids, reference, has_mask ? &mask : nullptr, options);
}

}  // namespace sacfuse
