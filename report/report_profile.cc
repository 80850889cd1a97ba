#include "report/report_profile.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace sacfuse {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Sliding minimum over [i - r, i + r] of `n` values read at in[i * stride], written to out[i * stride].
void SlidingMin(const float* in, float* out, int n, size_t stride, int r) {
  std::deque<int> window;  // indices with increasing values
  int next = 0;
  for (int i = 0; i < n; ++i) {
    const int hi = std::min(n - 1, i + r);
    for (; next <= hi; ++next) {
      while (!window.empty() && in[window.back() * stride] >= in[next * stride]) window.pop_back();
      window.push_back(next);
    }
    while (window.front() < i - r) window.pop_front();
    out[i * stride] = in[window.front() * stride];
  }
}

struct Crossing {
  int before = 0, after = 0;  // cells of the building on each side of the peak along the axis
  int cells() const { return before + after + 1; }
};

// Walks from (row, col) in steps (dr, dc) while the cells are at least `threshold` high; returns how many cells
// past the start belong to the building. Runs of up to `max_gap` empty cells and single low cells (noise) are
// bridged; two low cells in a row or a longer gap end the building.
int Walk(const TopGrid& g, int row, int col, int dr, int dc, float threshold, int max_gap) {
  int last_on = 0, gap = 0, low = 0;
  for (int k = 1;; ++k) {
    const int r = row + k * dr, c = col + k * dc;
    if (r < 0 || c < 0 || r >= g.height || c >= g.width) break;
    const float z = g.top_z[g.Index(r, c)];
    if (std::isnan(z)) {
      if (++gap > max_gap) break;
      continue;
    }
    if (z < threshold) {
      if (++low >= 2) break;
      continue;
    }
    last_on = k;
    gap = 0;
    low = 0;
  }
  return last_on;
}

// All 3x3 neighbours filled and their top z within `tolerance` of each other (a roof, not a crown or an edge).
bool IsFlat(const TopGrid& g, int row, int col, float tolerance) {
  if (row == 0 || col == 0 || row == g.height - 1 || col == g.width - 1) return false;
  float lo = kInf, hi = -kInf;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      const float z = g.top_z[g.Index(row + dr, col + dc)];
      if (std::isnan(z)) return false;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  return hi - lo <= tolerance;
}

// Filled-cell counts over rectangles in O(1) (a summed-area table).
class FillCounts {
 public:
  explicit FillCounts(const TopGrid& g) : w_(g.width + 1), sums_(static_cast<size_t>(g.width + 1) * (g.height + 1), 0) {
    for (int r = 0; r < g.height; ++r) {
      for (int c = 0; c < g.width; ++c) {
        At(r + 1, c + 1) = At(r, c + 1) + At(r + 1, c) - At(r, c) + (g.Empty(r, c) ? 0 : 1);
      }
    }
    h_ = g.height;
  }
  // Whether each of the four quadrants of the square of `radius` cells around (row, col) (clipped to the grid
  // counts as empty) has at least `min_fill` of its cells filled.
  bool Surrounded(int row, int col, int radius, double min_fill) const {
    const int w = w_ - 1;
    const auto filled = [&](int r0, int r1, int c0, int c1) {  // cells [r0, r1) x [c0, c1), clipped
      const int a = std::clamp(r0, 0, h_), b = std::clamp(r1, 0, h_), c = std::clamp(c0, 0, w), d = std::clamp(c1, 0, w);
      return At(b, d) - At(a, d) - At(b, c) + At(a, c);
    };
    const double need = min_fill * static_cast<double>(radius + 1) * (radius + 1);
    return filled(row - radius, row + 1, col - radius, col + 1) >= need &&
           filled(row - radius, row + 1, col, col + radius + 1) >= need &&
           filled(row, row + radius + 1, col - radius, col + 1) >= need &&
           filled(row, row + radius + 1, col, col + radius + 1) >= need;
  }

 private:
  int64_t At(int r, int c) const { return sums_[static_cast<size_t>(r) * w_ + c]; }
  int64_t& At(int r, int c) { return sums_[static_cast<size_t>(r) * w_ + c]; }
  int w_ = 0, h_ = 0;
  std::vector<int64_t> sums_;
};

}  // namespace

std::optional<double> ProfileStrip::Along(double x, double y) const {
  const Eigen::Vector2d d = end_xy - start_xy;
  const double length = d.norm();
  if (length <= 0.0) return std::nullopt;
  const Eigen::Vector2d u = d / length;
  const Eigen::Vector2d p(x - start_xy.x(), y - start_xy.y());
  const double s = p.dot(u);
  const double n = u.x() * p.y() - u.y() * p.x();
  if (s < 0.0 || s > length || std::abs(n) > half_width_m) return std::nullopt;
  return s;
}

Box2d ProfileStrip::Box() const {
  Box2d b;
  const Eigen::Vector2d d = end_xy - start_xy;
  const double length = d.norm();
  const Eigen::Vector2d n = length > 0 ? Eigen::Vector2d(-d.y() / length, d.x() / length) : Eigen::Vector2d(0, 0);
  for (const Eigen::Vector2d& p : {start_xy, end_xy}) {
    b.Extend(Eigen::Vector2d(p + half_width_m * n));
    b.Extend(Eigen::Vector2d(p - half_width_m * n));
  }
  b.min.array() -= half_width_m * (length > 0 ? 0.0 : 1.0);
  b.max.array() += half_width_m * (length > 0 ? 0.0 : 1.0);
  return b;
}

std::vector<float> LocalMinimum(const TopGrid& grid, int radius_cells) {
  const int w = grid.width, h = grid.height;
  std::vector<float> in(grid.num_cells()), rows(grid.num_cells()), out(grid.num_cells());
  for (size_t i = 0; i < in.size(); ++i) in[i] = std::isnan(grid.top_z[i]) ? kInf : grid.top_z[i];
  const int r = std::max(0, radius_cells);
  for (int row = 0; row < h; ++row) SlidingMin(&in[grid.Index(row, 0)], &rows[grid.Index(row, 0)], w, 1, r);
  for (int col = 0; col < w; ++col) SlidingMin(&rows[col], &out[col], h, static_cast<size_t>(w), r);
  for (float& v : out) {
    if (v == kInf) v = std::numeric_limits<float>::quiet_NaN();
  }
  return out;
}

std::optional<ProfileStrip> PickProfileStrip(const TopGrid& g, const StripPickOptions& o) {
  if (g.num_cells() == 0) return std::nullopt;
  const double cell = g.cell_m;
  const std::vector<float> ground = LocalMinimum(g, static_cast<int>(std::ceil(o.ground_radius_m / cell)));
  const float flat_tol = static_cast<float>(std::max(o.flat_tolerance_m, o.flat_slope * cell));
  const int radius = static_cast<int>(std::ceil(o.ground_radius_m / cell));
  const FillCounts fill(g);
  // Candidates in tiers: flat and surrounded by data, else flat, else any filled cell.
  long best[3] = {-1, -1, -1};
  float best_score[3] = {-kInf, -kInf, -kInf};
  bool use_within = !o.within.IsEmpty();
  if (use_within) {  // ignored when no filled cell lies inside
    use_within = false;
    for (int row = 0; row < g.height && !use_within; ++row) {
      for (int col = 0; col < g.width && !use_within; ++col) {
        use_within = !g.Empty(row, col) && o.within.Contains({g.CellCenterX(col), g.CellCenterY(row)});
      }
    }
  }
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      const size_t i = g.Index(row, col);
      if (std::isnan(g.top_z[i])) continue;
      if (use_within && !o.within.Contains({g.CellCenterX(col), g.CellCenterY(row)})) continue;
      const float score = g.top_z[i] - ground[i];
      if (score > best_score[2]) {
        best_score[2] = score;
        best[2] = static_cast<long>(i);
      }
      if (score <= best_score[1] && score <= best_score[0]) continue;
      if (!IsFlat(g, row, col, flat_tol)) continue;
      if (score > best_score[1]) {
        best_score[1] = score;
        best[1] = static_cast<long>(i);
      }
      if (score > best_score[0] && fill.Surrounded(row, col, radius, o.min_fill)) {
        best_score[0] = score;
        best[0] = static_cast<long>(i);
      }
    }
  }
  const int tier = best[0] >= 0 ? 0 : best[1] >= 0 ? 1 : 2;
  const long best_cell = best[tier];
  const float best_relief = best_score[tier];
  if (best_cell < 0) return std::nullopt;
  const int row = static_cast<int>(best_cell / g.width), col = static_cast<int>(best_cell % g.width);
  const float threshold = ground[best_cell] + 0.5f * best_relief;
  // Along x: columns; along y (north): rows decrease.
  const int max_gap = std::max(3, static_cast<int>(std::ceil(o.max_gap_m / cell)));
  Crossing along_x{Walk(g, row, col, 0, -1, threshold, max_gap), Walk(g, row, col, 0, 1, threshold, max_gap)};
  Crossing along_y{Walk(g, row, col, 1, 0, threshold, max_gap), Walk(g, row, col, -1, 0, threshold, max_gap)};
  const bool use_x = along_x.cells() <= along_y.cells();
  const Crossing& cross = use_x ? along_x : along_y;
  const Eigen::Vector2d dir = use_x ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d peak(g.CellCenterX(col), g.CellCenterY(row));

  const double crossing_m = cross.cells() * cell;
  const double margin = std::max(o.margin_m, 0.5 * crossing_m);
  double s0 = -(cross.before + 0.5) * cell - margin;
  double s1 = (cross.after + 0.5) * cell + margin;
  if (s1 - s0 > o.max_length_m) {
    s0 = -0.5 * o.max_length_m;
    s1 = 0.5 * o.max_length_m;
  }
  if (s1 - s0 < o.min_length_m) {
    const double grow = 0.5 * (o.min_length_m - (s1 - s0));
    s0 -= grow;
    s1 += grow;
  }
  // Within the grid.
  const double lo = use_x ? g.x_min - peak.x() : (g.y_max - g.height * cell) - peak.y();
  const double hi = use_x ? g.x_min + g.width * cell - peak.x() : g.y_max - peak.y();
  s0 = std::max(s0, lo);
  s1 = std::min(s1, hi);

  ProfileStrip strip;
  strip.start_xy = peak + s0 * dir;
  strip.end_xy = peak + s1 * dir;
  strip.half_width_m = o.half_width_m;
  strip.relief_m = best_relief;
  strip.peak_xy = peak;
  // Height range of the top surface along the centreline (+-1 cell across).
  float z_lo = kInf, z_hi = -kInf;
  const int k0 = static_cast<int>(std::floor(s0 / cell)), k1 = static_cast<int>(std::ceil(s1 / cell));
  for (int k = k0; k <= k1; ++k) {
    for (int across = -1; across <= 1; ++across) {
      const int r = use_x ? row + across : row - k;
      const int c = use_x ? col + k : col + across;
      if (r < 0 || c < 0 || r >= g.height || c >= g.width) continue;
      const float z = g.top_z[g.Index(r, c)];
      if (std::isnan(z)) continue;
      z_lo = std::min(z_lo, z);
      z_hi = std::max(z_hi, z);
    }
  }
  const double pad = std::max(2.0, 0.15 * (z_hi - z_lo));
  strip.z_min_m = z_lo - pad;
  strip.z_max_m = z_hi + pad;
  return strip;
}

ProfileSample::ProfileSample(size_t capacity, uint64_t seed) : capacity_(capacity), rng_(seed) {
  points_.reserve(std::min<size_t>(capacity, 1 << 16));
}

void ProfileSample::Add(const ProfilePoint& p) {
  ++seen_;
  if (points_.size() < capacity_) {
    points_.push_back(p);
    return;
  }
  if (capacity_ == 0) return;
  const uint64_t j = std::uniform_int_distribution<uint64_t>(0, seen_ - 1)(rng_);
  if (j < capacity_) points_[j] = p;
}

}  // namespace sacfuse
