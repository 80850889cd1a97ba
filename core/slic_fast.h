#pragma once
// A fast single-threaded SLIC (Achanta et al., TPAMI 2012) for one block of a view: sacfuse's own implementation
// behind SuperpixelOptions::algorithm = "fast". It is the original algorithm -- seeds on a regular grid of
// region_size_px, optionally moved to the lowest-gradient pixel of their 3x3 neighbourhood; k-means restricted to
// each centre's 2S x 2S window for `iterations` rounds; connectivity enforcement -- with the work kept cheap:
//   - distance = |Lab - Lab_k|^2 (+ (extra - extra_k)^2) + (ruler / S)^2 * |xy - xy_k|^2, squared, no sqrt; the
//     distance of OpenCV's SLIC (not SLICO), so `ruler` means the same;
//   - a round walks the block row by row: a row is converted to float once and swept by every centre whose window
//     covers it (in centre order, so ties resolve as in centre-by-centre SLIC) with branch-free SSE2/AVX2 code
//     and per-centre tables of the spatial term; while the row is in cache it is added to the centre sums
//     (exact integers, two interleaved copies so that neighbouring pixels do not wait on each other's store),
//     or, in the last round, cut into label runs. Memory: the output labels, one row of scratch, O(centres) and
//     the runs;
//   - connectivity works on those horizontal runs joined by union-find instead of a per-pixel flood fill.
// Everything is sequential in a fixed order with the same IEEE operations on every CPU (no FMA), so the result
// depends only on the inputs.
#include <cstddef>
#include <cstdint>
#include <memory>

namespace sacfuse {

struct FastSlicParams {
  int region_size_px = 16;  // S: seed spacing and half-size of a centre's search window, pixels. >= 2
  float ruler = 10.0f;      // compactness m: spatial distances are weighted by (m / S)^2. > 0
  int iterations = 4;       // assignment + update rounds. >= 1
  bool perturb_seeds = true;  // move each seed to the lowest-gradient pixel of its 3x3 neighbourhood
  // Connected fragments smaller than this percentage of the mean region (block area / number of seeds) are
  // merged into an adjacent cluster. [0, 100]
  int min_fragment_percent = 25;
};

struct FastSlicInput {
  int width = 0, height = 0;
  // 8-bit Lab (or any 3 channels), interleaved, row r starts at lab + r * lab_stride bytes.
  const uint8_t* lab = nullptr;
  size_t lab_stride = 0;
  // Optional extra channel (sacfuse: the weighted depth), row r at extra + r * extra_stride floats; nullptr = none.
  const float* extra = nullptr;
  size_t extra_stride = 0;
};

// Scratch buffers of FastSlicSegment (row buffers, spatial tables, label runs, union-find arrays), reusable across
// calls of one thread so that consecutive blocks do not pay for fresh pages. The result never depends on it.
class FastSlicWorkspace {
 public:
  FastSlicWorkspace();
  ~FastSlicWorkspace();
  FastSlicWorkspace(FastSlicWorkspace&&) noexcept;
  FastSlicWorkspace& operator=(FastSlicWorkspace&&) noexcept;
  struct Buffers;  // defined in slic_fast.cc
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

// Segments the block and writes labels[r * label_stride + c] for every pixel. Returns the number of clusters n:
// labels are dense in [0, n), numbered in order of first appearance in row-major order, and every cluster is
// 4-connected. Fragments are merged deterministically into the cluster of the pixel left of (or, at column 0,
// above) their first pixel; a small fragment at the block's top-left pixel is merged into the cluster right of
// (or below) its first run. Width and height must be >= 1; a block smaller than S in a direction gets one seed
// in that direction.
// `workspace` may be null (temporary buffers).
int FastSlicSegment(const FastSlicInput& input, const FastSlicParams& params, int32_t* labels, size_t label_stride,
                    FastSlicWorkspace* workspace = nullptr);

// The connectivity pass of FastSlicSegment on its own (for tests and other label rasters): 4-connected components
// of equal labels; components below `min_size` pixels are merged as described above; dense labels in order of
// first appearance go to `out` (which may be `labels` itself). Returns their number.
int FastSlicEnforceConnectivity(int width, int height, const int32_t* labels, size_t label_stride, double min_size,
                                int32_t* out, size_t out_stride);

}  // namespace sacfuse
