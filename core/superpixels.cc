#include "core/superpixels.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <sstream>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/slic.hpp>

#include "core/error.h"
#include "core/slic_fast.h"

namespace sacfuse {
namespace {

// OpenCV's default for enforceLabelConnectivity: fragments below 25% of a region are merged.
constexpr int kMinElementPercent = 25;
// Bumped whenever the segmentation changes for the same options (invalidates cached files).
constexpr char kAlgorithmVersion[] = "sacfuse.superpixels.v1";
// Version of our own SLIC (algorithm "fast"), hashed only for that algorithm: bump it when FastSlicSegment's
// output changes.
constexpr char kFastSlicVersion[] = "sacfuse.slic_fast.v1";

struct Block {
  cv::Rect rect;  // in depth-raster pixels
};

// Edges 0 = e0 < e1 < ... < ek = n of blocks of `block` pixels; a trailing remainder below `min_block` joins
// the previous block.
std::vector<int> BlockEdges(int n, int block, int min_block) {
  std::vector<int> edges{0};
  const int full = n / block;
  if (full == 0) {
    edges.push_back(n);
    return edges;
  }
  for (int i = 1; i <= full; ++i) edges.push_back(i * block);
  const int rest = n - full * block;
  if (rest > 0) {
    if (rest < min_block) {
      edges.back() = n;
    } else {
      edges.push_back(n);
    }
  }
  return edges;
}

int SlicAlgorithm(const std::string& name) {
  if (name == "slic") return cv::ximgproc::SLIC;
  if (name == "mslic") return cv::ximgproc::MSLIC;
  return cv::ximgproc::SLICO;
}

void ValidateInputs(const RgbImage& image, const DepthMap& depth) {
  if (depth.width <= 0 || depth.height <= 0) throw Error("ComputeSuperpixels: empty depth map");
  if (depth.channels != 1 || depth.data.size() != depth.num_pixels()) {
    throw Error("ComputeSuperpixels: depth map must have 1 channel and width*height values");
  }
  if (image.width <= 0 || image.height <= 0) throw Error("ComputeSuperpixels: empty colour image");
  if ((image.channels != 3 && image.channels != 1) ||
      image.data.size() != image.num_pixels() * static_cast<size_t>(image.channels)) {
    throw Error("ComputeSuperpixels: colour image must have 3 (RGB) or 1 channel and width*height*channels values");
  }
  // Same aspect ratio up to the rounding of one pixel per dimension.
  const double sx = static_cast<double>(image.width) / depth.width;
  const double sy = static_cast<double>(image.height) / depth.height;
  const double mismatch = std::abs(static_cast<double>(image.width) * depth.height -
                                   static_cast<double>(image.height) * depth.width);
  if (mismatch > std::max(sx, sy) * (depth.width + depth.height) + 1.0) {
    std::ostringstream os;
    os << "ComputeSuperpixels: colour image " << image.width << "x" << image.height
       << " does not have the aspect ratio of the depth map " << depth.width << "x" << depth.height;
    throw Error(os.str());
  }
}

// The block's RGB pixels on the depth grid.
cv::Mat BlockRgb(const RgbImage& image, const DepthMap& depth, const cv::Rect& r) {
  cv::Mat full(image.height, image.width, CV_8UC(image.channels), const_cast<uint8_t*>(image.data.data()));
  cv::Mat rgb;
  if (image.width == depth.width && image.height == depth.height) {
    rgb = full(r);
  } else {
    // Source window covering the block exactly when the scale is an integer, to within one source pixel
    // otherwise.
    const auto lo = [](int v, int num, int den) { return static_cast<int>(static_cast<int64_t>(v) * num / den); };
    const auto hi = [](int v, int num, int den) {
      return static_cast<int>((static_cast<int64_t>(v) * num + den - 1) / den);
    };
    const int c0 = lo(r.x, image.width, depth.width);
    const int c1 = std::max(c0 + 1, std::min(image.width, hi(r.x + r.width, image.width, depth.width)));
    const int r0 = lo(r.y, image.height, depth.height);
    const int r1 = std::max(r0 + 1, std::min(image.height, hi(r.y + r.height, image.height, depth.height)));
    const cv::Mat src = full(cv::Rect(c0, r0, c1 - c0, r1 - r0));
    const bool shrink = src.cols >= r.width && src.rows >= r.height;
    cv::resize(src, rgb, r.size(), 0, 0, shrink ? cv::INTER_AREA : cv::INTER_LINEAR);
  }
  if (image.channels == 1) {
    cv::Mat colour;
    cv::cvtColor(rgb, colour, cv::COLOR_GRAY2RGB);
    return colour;
  }
  return rgb;
}

// Scratch space of one worker thread, reused block after block (fresh pages cost more than the work on them).
struct BlockScratch {
  FastSlicWorkspace slic;
  cv::Mat lab;
  std::vector<float> values;
  std::vector<uint32_t> keys;
  std::vector<size_t> offset, fill;
};

// The k-th smallest (0-based) of n >= 1 positive floats given as their bit patterns (which order like the
// floats), by radix selection on 8-bit digits from the highest bit in which they differ. Reorders `keys`.
uint32_t SelectPositiveBits(uint32_t* keys, size_t n, size_t k) {
  uint32_t lo = keys[0], hi = keys[0];
  for (size_t i = 1; i < n; ++i) {
    lo = std::min(lo, keys[i]);
    hi = std::max(hi, keys[i]);
  }
  if (lo == hi) return lo;
  const int top = 31 - __builtin_clz(lo ^ hi);  // bits above `top` are equal in all keys
  int shift = top >= 7 ? top - 7 : 0;
  uint32_t histogram[256];
  for (;;) {
    std::fill(histogram, histogram + 256, 0u);
    for (size_t i = 0; i < n; ++i) ++histogram[(keys[i] >> shift) & 0xFFu];
    uint32_t digit = 0;
    size_t below = 0;
    while (below + histogram[digit] <= k) below += histogram[digit++];
    k -= below;
    size_t m = 0;  // keep the keys with that digit (branch-free compaction)
    for (size_t i = 0; i < n; ++i) {
      const uint32_t key = keys[i];
      keys[m] = key;
      m += ((key >> shift) & 0xFFu) == digit ? 1 : 0;
    }
    n = m;
    if (shift == 0 || n == 1) return keys[0];
    shift = shift >= 8 ? shift - 8 : 0;  // the remaining varying bits fit in the low byte once shift is 0
  }
}

// Median of n >= 1 valid (positive, finite) depths: the middle value, or the mean of the two middle values for
// an even count. Exact order statistics, so equal to sorting; `values` is left unchanged.
float MedianOfValidDepths(const float* values, size_t n, std::vector<uint32_t>* scratch) {
  if (scratch->size() < n) scratch->resize(n);
  uint32_t* keys = scratch->data();
  std::memcpy(keys, values, n * sizeof(float));
  const size_t mid = n / 2;
  const uint32_t upper_bits = SelectPositiveBits(keys, n, mid);
  float upper;
  std::memcpy(&upper, &upper_bits, sizeof(float));
  if (n % 2 == 1) return upper;
  // The value ranked mid - 1: the largest one below `upper`, unless `upper` itself occurs below rank mid.
  size_t below = 0;
  float largest_below = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    const float v = values[i];
    if (v < upper) {
      ++below;
      largest_below = std::max(largest_below, v);
    }
  }
  const double lower = below == mid ? static_cast<double>(largest_below) : static_cast<double>(upper);
  return static_cast<float>(0.5 * (lower + static_cast<double>(upper)));
}

// The extra SLIC channel of a block when depth_weight > 0 (else empty): depth_weight * (depth - median valid
// depth of the block), 0 (= the median) for invalid depths.
cv::Mat BlockDepthChannel(const DepthMap& depth, const cv::Rect& r, const SuperpixelOptions& options) {
  if (options.depth_weight <= 0.0f) return cv::Mat();
  std::vector<float> valid;
  valid.reserve(static_cast<size_t>(r.area()));
  for (int row = r.y; row < r.y + r.height; ++row) {
    for (int col = r.x; col < r.x + r.width; ++col) {
      const float d = depth.at(row, col);
      if (IsValidDepth(d)) valid.push_back(d);
    }
  }
  std::vector<uint32_t> scratch;
  const double reference = valid.empty() ? 0.0 : MedianOfValidDepths(valid.data(), valid.size(), &scratch);
  cv::Mat depth_channel(r.height, r.width, CV_32F);
  for (int row = 0; row < r.height; ++row) {
    float* out = depth_channel.ptr<float>(row);
    for (int col = 0; col < r.width; ++col) {
      const float d = depth.at(r.y + row, r.x + col);
      out[col] = IsValidDepth(d) ? static_cast<float>(options.depth_weight * (d - reference)) : 0.0f;
    }
  }
  return depth_channel;
}

// The block's 8-bit Lab image (CV_8UC3) on the depth grid, into `lab` (its buffer is reused when large enough).
void BlockLab(const RgbImage& image, const DepthMap& depth, const cv::Rect& r, cv::Mat* lab) {
  cv::cvtColor(BlockRgb(image, depth, r), *lab, cv::COLOR_RGB2Lab);
}

// OpenCV SLIC input channels of a block: 8-bit Lab, plus the weighted depth when depth_weight > 0.
std::vector<cv::Mat> BlockChannels(const RgbImage& image, const DepthMap& depth, const cv::Rect& r,
                                   const SuperpixelOptions& options) {
  std::vector<cv::Mat> channels;
  cv::Mat lab;
  BlockLab(image, depth, r, &lab);
  cv::split(lab, channels);
  cv::Mat depth_channel = BlockDepthChannel(depth, r, options);
  if (depth_channel.empty()) return channels;
  for (cv::Mat& c : channels) c.convertTo(c, CV_32F);
  channels.push_back(depth_channel);
  return channels;
}

// Raw SLIC labels of one block (CV_32S, arbitrary non-negative ids).
cv::Mat SegmentBlock(const RgbImage& image, const DepthMap& depth, const cv::Rect& r,
                     const SuperpixelOptions& options) {
  if (r.width < options.region_size_px || r.height < options.region_size_px) {
    return cv::Mat(r.size(), CV_32S, cv::Scalar(0));  // too small for SLIC seeds: one cluster
  }
  const std::vector<cv::Mat> channels = BlockChannels(image, depth, r, options);
  cv::Mat labels;
  // Single-threaded arena: OpenCV's SLIC reduces float sums with TBB, whose split order (and so the rounding)
  // would otherwise depend on the number of threads.
  tbb::task_arena arena(1);
  arena.execute([&] {
    cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic = cv::ximgproc::createSuperpixelSLIC(
        channels, SlicAlgorithm(options.algorithm), options.region_size_px, options.ruler);
    slic->iterate(options.iterations);
    // MSLIC already enforces connectivity (13%) inside every iteration.
    if (options.algorithm != "mslic") slic->enforceLabelConnectivity(kMinElementPercent);
    slic->getLabels(labels);
  });
  return labels;
}

// Per-pixel nodes ("pixels", the paper's Section III.B without III.C): every pixel of block `r` its own cluster,
// labels in row-major order; returns the number of clusters.
int32_t SegmentBlockPixels(const cv::Rect& r, int raster_width, int32_t* out_labels) {
  int32_t next = 0;
  for (int row = r.y; row < r.y + r.height; ++row) {
    int32_t* lab = out_labels + static_cast<size_t>(row) * raster_width;
    for (int col = r.x; col < r.x + r.width; ++col) lab[col] = next++;
  }
  return next;
}

// Our own SLIC ("fast") on block `r`: writes block-local dense labels (first-appearance order) straight into
// `out_labels` (the global row-major raster) and returns the number of clusters.
int32_t SegmentBlockFast(const RgbImage& image, const DepthMap& depth, const cv::Rect& r,
                         const SuperpixelOptions& options, int32_t* out_labels, BlockScratch* scratch) {
  const size_t stride = static_cast<size_t>(depth.width);
  int32_t* block_labels = out_labels + static_cast<size_t>(r.y) * stride + r.x;
  if (r.width < options.region_size_px || r.height < options.region_size_px) {
    for (int row = 0; row < r.height; ++row) {
      std::fill(block_labels + row * stride, block_labels + row * stride + r.width, 0);
    }
    return 1;  // too small for SLIC seeds: one cluster (as for the OpenCV algorithms)
  }
  cv::Mat& lab = scratch->lab;
  BlockLab(image, depth, r, &lab);
  const cv::Mat depth_channel = BlockDepthChannel(depth, r, options);
  FastSlicInput input;
  input.width = r.width;
  input.height = r.height;
  input.lab = lab.ptr<uint8_t>(0);
  input.lab_stride = lab.step[0];
  if (!depth_channel.empty()) {
    input.extra = depth_channel.ptr<float>(0);
    input.extra_stride = depth_channel.step[0] / sizeof(float);
  }
  FastSlicParams params;
  params.region_size_px = options.region_size_px;
  params.ruler = options.ruler;
  params.iterations = options.iterations;
  params.min_fragment_percent = kMinElementPercent;
  return FastSlicSegment(input, params, block_labels, stride, &scratch->slic);
}

// OpenCV SLIC on block `r`: writes block-local dense labels (first-appearance order) into `out_labels` (the
// global row-major raster) and returns the number of clusters.
int32_t SegmentBlockOpenCv(const RgbImage& image, const DepthMap& depth, const cv::Rect& r,
                           const SuperpixelOptions& options, int32_t* out_labels) {
  cv::Mat raw;
  try {
    raw = SegmentBlock(image, depth, r, options);
  } catch (const cv::Exception& e) {
    std::ostringstream os;
    os << "ComputeSuperpixels: OpenCV failed on block x=" << r.x << " y=" << r.y << " " << r.width << "x"
       << r.height << ": " << e.what();
    throw Error(os.str());
  }
  double min_label = 0, max_label = 0;
  cv::minMaxLoc(raw, &min_label, &max_label);
  if (min_label < 0 || raw.rows != r.height || raw.cols != r.width) {
    throw Error("ComputeSuperpixels: SLIC returned invalid labels");
  }
  std::vector<int32_t> remap(static_cast<size_t>(max_label) + 1, -1);
  int32_t count = 0;
  const size_t stride = static_cast<size_t>(depth.width);
  for (int row = 0; row < r.height; ++row) {
    const int32_t* in = raw.ptr<int32_t>(row);
    int32_t* out = out_labels + static_cast<size_t>(r.y + row) * stride + r.x;
    for (int col = 0; col < r.width; ++col) {
      int32_t& local = remap[static_cast<size_t>(in[col])];
      if (local < 0) local = count++;
      out[col] = local;
    }
  }
  return count;
}

// Statistics of the `count` clusters of block `r`, whose block-local dense labels are in `labels` (the global
// row-major raster).
std::vector<SuperpixelCluster> BlockClusterStats(const DepthMap& depth, const cv::Rect& r, const int32_t* labels,
                                                 int32_t count, const SuperpixelOptions& options,
                                                 BlockScratch* scratch) {
  // Integer sums pixel by pixel, into two copies (even and odd columns) so that neighbouring pixels of one cluster
  // do not wait for each other's store. Exact, so the centroids are the same doubles as summing pixel centres
  // (c + 0.5) one by one.
  struct Counts {
    int64_t col = 0, row = 0;
    uint32_t pixels = 0, valid = 0;
  };
  std::vector<Counts> even(static_cast<size_t>(count)), odd(static_cast<size_t>(count));
  const size_t stride = static_cast<size_t>(depth.width);
  for (int row = 0; row < r.height; ++row) {
    const int32_t* lab = labels + static_cast<size_t>(r.y + row) * stride + r.x;
    const float* d = &depth.data[static_cast<size_t>(r.y + row) * stride + r.x];
    for (int col = 0; col < r.width; ++col) {
      const int32_t k = lab[col];
      if (k < 0 || k >= count) throw Error("ComputeSuperpixels: label out of range");
      Counts& c = ((col & 1) != 0 ? odd : even)[static_cast<size_t>(k)];
      c.col += col;
      c.row += row;
      c.pixels += 1;
      c.valid += IsValidDepth(d[col]) ? 1u : 0u;
    }
  }
  struct Sums {
    double col = 0, row = 0;
    uint32_t pixels = 0, valid = 0;
  };
  std::vector<Sums> sums(static_cast<size_t>(count));
  for (size_t i = 0; i < sums.size(); ++i) {
    Sums& s = sums[i];
    s.pixels = even[i].pixels + odd[i].pixels;
    s.valid = even[i].valid + odd[i].valid;
    s.col = s.pixels * (r.x + 0.5) + static_cast<double>(even[i].col + odd[i].col);
    s.row = s.pixels * (r.y + 0.5) + static_cast<double>(even[i].row + odd[i].row);
  }
  // Valid depths grouped by cluster (in row-major order), then per-cluster medians.
  std::vector<size_t>& offset = scratch->offset;
  offset.assign(sums.size() + 1, 0);
  for (size_t i = 0; i < sums.size(); ++i) offset[i + 1] = offset[i] + sums[i].valid;
  std::vector<float>& values = scratch->values;
  values.resize(offset.back());
  std::vector<size_t>& fill = scratch->fill;
  fill.assign(offset.begin(), offset.end() - 1);
  for (int row = 0; row < r.height; ++row) {
    const int32_t* lab = labels + static_cast<size_t>(r.y + row) * stride + r.x;
    const float* d = &depth.data[static_cast<size_t>(r.y + row) * stride + r.x];
    for (int col = 0; col < r.width; ++col) {
      if (IsValidDepth(d[col])) values[fill[static_cast<size_t>(lab[col])]++] = d[col];
    }
  }
  std::vector<SuperpixelCluster> clusters(sums.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    SuperpixelCluster& c = clusters[i];
    c.pixel_count = sums[i].pixels;
    c.valid_count = sums[i].valid;
    c.centroid_col = static_cast<float>(sums[i].col / sums[i].pixels);
    c.centroid_row = static_cast<float>(sums[i].row / sums[i].pixels);
    // A one-pixel cluster ("pixels") has its pixel's depth whatever min_valid_pixels says.
    const uint32_t min_valid = options.algorithm == "pixels" ? 1u : static_cast<uint32_t>(options.min_valid_pixels);
    if (c.valid_count > 0 && c.valid_count >= min_valid) {
      c.depth_m = MedianOfValidDepths(values.data() + offset[i], c.valid_count, &scratch->keys);
    }
  }
  return clusters;
}

// Segments block `r`, writes block-local dense labels (first-appearance order) into `out_labels` (the global
// row-major raster) and returns the block's clusters.
// `scratch` is the calling thread's.
std::vector<SuperpixelCluster> ProcessBlock(const RgbImage& image, const DepthMap& depth, const cv::Rect& r,
                                            const SuperpixelOptions& options, int32_t* out_labels,
                                            BlockScratch* scratch) {
  const int32_t count = options.algorithm == "pixels" ? SegmentBlockPixels(r, depth.width, out_labels)
                        : options.algorithm == "fast"
                            ? SegmentBlockFast(image, depth, r, options, out_labels, scratch)
                            : SegmentBlockOpenCv(image, depth, r, options, out_labels);
  return BlockClusterStats(depth, r, out_labels, count, options, scratch);
}

// FNV-1a 64 over a fixed little-endian encoding.
class Fnv1a {
 public:
  void Bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      hash_ ^= p[i];
      hash_ *= 1099511628211ull;
    }
  }
  void U32(uint32_t v) {
    const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                                static_cast<unsigned char>(v >> 16), static_cast<unsigned char>(v >> 24)};
    Bytes(b, 4);
  }
  void I32(int32_t v) { U32(static_cast<uint32_t>(v)); }
  void F32(float v) {
    if (v == 0.0f) v = 0.0f;  // -0 == +0
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    U32(bits);
  }
  void Str(const std::string& s) {
    U32(static_cast<uint32_t>(s.size()));
    Bytes(s.data(), s.size());
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

template <typename T>
std::string Rule(const std::string& field, const T& value, const std::string& rule) {
  std::ostringstream os;
  os << "SuperpixelOptions." << field << " = " << value << ": " << rule;
  return os.str();
}

}  // namespace

// OpenCV builds its RGB -> Lab tables lazily on the first conversion, without a lock: views segmented at once
// (jobs/view_batches.h) each built them and one copy leaked (~3.5 MB, LeakSanitizer). So the first conversion of
// the process runs once, before any other (std::call_once blocks the other callers until it is done).
void PrepareSuperpixelTables() {
  static std::once_flag once;
  std::call_once(once, [] {
    cv::Mat lab;
    cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(0, 0, 0)), lab, cv::COLOR_RGB2Lab);
  });
}

void ValidateSuperpixelOptions(const SuperpixelOptions& o) {
  std::vector<std::string> errors;
  if (o.region_size_px < 2 || o.region_size_px > 128) {
    errors.push_back(Rule("region_size_px", o.region_size_px, "must be in [2, 128]"));
  }
  if (!(o.ruler > 0.0f) || !std::isfinite(o.ruler)) errors.push_back(Rule("ruler", o.ruler, "must be > 0"));
  if (o.iterations < 1 || o.iterations > 100) {
    errors.push_back(Rule("iterations", o.iterations, "must be in [1, 100]"));
  }
  if (o.algorithm != "slic" && o.algorithm != "slico" && o.algorithm != "mslic" && o.algorithm != "fast" &&
      o.algorithm != "pixels") {
    errors.push_back(Rule("algorithm", o.algorithm, "must be one of slic, slico, mslic, fast, pixels"));
  }
  if (o.block_size_px < 2 * std::max(o.region_size_px, 1)) {
    errors.push_back(Rule("block_size_px", o.block_size_px,
                          "must be >= 2 * region_size_px (" + std::to_string(2 * o.region_size_px) + ")"));
  }
  if (!(o.depth_weight >= 0.0f) || !std::isfinite(o.depth_weight)) {
    errors.push_back(Rule("depth_weight", o.depth_weight, "must be >= 0"));
  }
  if (o.min_valid_pixels < 1) errors.push_back(Rule("min_valid_pixels", o.min_valid_pixels, "must be >= 1"));
  if (errors.empty()) return;
  std::string message = "superpixel options: invalid configuration";
  for (const std::string& e : errors) message += "\n  " + e;
  throw ConfigError(message);
}

SuperpixelMap ComputeSuperpixels(const RgbImage& image, const DepthMap& depth, const SuperpixelOptions& options,
                                 LabelPacking packing) {
  ValidateSuperpixelOptions(options);
  ValidateInputs(image, depth);
  PrepareSuperpixelTables();

  SuperpixelMap map;
  map.width = depth.width;
  map.height = depth.height;
  std::vector<int32_t> labels(depth.num_pixels(), 0);  // stored as SuperpixelLabels at the end

  const int min_block = 2 * options.region_size_px;
  const std::vector<int> xs = BlockEdges(depth.width, options.block_size_px, min_block);
  const std::vector<int> ys = BlockEdges(depth.height, options.block_size_px, min_block);
  std::vector<Block> blocks;
  for (size_t by = 0; by + 1 < ys.size(); ++by) {
    for (size_t bx = 0; bx + 1 < xs.size(); ++bx) {
      blocks.push_back({cv::Rect(xs[bx], ys[by], xs[bx + 1] - xs[bx], ys[by + 1] - ys[by])});
    }
  }

  std::vector<std::vector<SuperpixelCluster>> block_clusters(blocks.size());
  // Scratch space, one per worker thread, freed when this call returns.
  tbb::enumerable_thread_specific<BlockScratch> scratches;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    BlockScratch& scratch = scratches.local();
    for (size_t b = range.begin(); b != range.end(); ++b) {
      block_clusters[b] = ProcessBlock(image, depth, blocks[b].rect, options, labels.data(), &scratch);
    }
  });

  // Global numbering: row-major block order.
  std::vector<int32_t> first(blocks.size(), 0);
  size_t total = 0;
  for (size_t b = 0; b < blocks.size(); ++b) {
    first[b] = static_cast<int32_t>(total);
    total += block_clusters[b].size();
  }
  map.clusters.reserve(total);
  for (auto& clusters : block_clusters) {
    map.clusters.insert(map.clusters.end(), clusters.begin(), clusters.end());
    std::vector<SuperpixelCluster>().swap(clusters);
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      if (first[b] == 0) continue;
      const cv::Rect& r = blocks[b].rect;
      for (int row = r.y; row < r.y + r.height; ++row) {
        int32_t* out = labels.data() + static_cast<size_t>(row) * map.width + r.x;
        for (int col = 0; col < r.width; ++col) out[col] += first[b];
      }
    }
  });
  map.labels = packing == LabelPacking::kPacked ? SuperpixelLabels(map.width, map.height, labels)
                                                : SuperpixelLabels::Unpacked(map.width, map.height, std::move(labels));
  return map;
}

uint64_t SuperpixelOptionsHash(const SuperpixelOptions& o) {
  Fnv1a h;
  h.Str(kAlgorithmVersion);
  h.I32(o.region_size_px);
  h.F32(o.ruler);
  h.I32(o.iterations);
  h.Str(o.algorithm);
  h.I32(o.block_size_px);
  h.F32(o.depth_weight);
  h.I32(o.min_valid_pixels);
  if (o.algorithm == "fast") h.Str(kFastSlicVersion);  // other algorithms keep their (pinned) fingerprints
  return h.value();
}

}  // namespace sacfuse
