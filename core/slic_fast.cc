#include "core/slic_fast.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cstring>
#include <stdexcept>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// x86-64 with GCC/Clang: an AVX2 variant of the assignment, chosen at run time. It performs the same IEEE
// operations in the same order as the SSE2 and scalar code (no FMA), so the result does not depend on the CPU.
#if defined(__SSE2__) && defined(__GNUC__) && defined(__x86_64__)
#define SACFUSE_SLIC_AVX2 1
#include <immintrin.h>
#endif

namespace sacfuse {

struct FastSlicWorkspace::Buffers {
  struct Run {
    int32_t x0, x1, label;  // columns [x0, x1) of one row carry `label`
  };
  std::vector<Run> runs;
  std::vector<int32_t> row_begin, parent, final_root, id;
  std::vector<int64_t> size;
  std::vector<float> rows;     // one row of L, a, b and distances
  std::vector<float> spatial;  // per centre: the spatial term of its window's columns
  std::vector<int32_t> order, active;
};

FastSlicWorkspace::FastSlicWorkspace() : buffers_(std::make_unique<Buffers>()) {}
FastSlicWorkspace::~FastSlicWorkspace() = default;
FastSlicWorkspace::FastSlicWorkspace(FastSlicWorkspace&&) noexcept = default;
FastSlicWorkspace& FastSlicWorkspace::operator=(FastSlicWorkspace&&) noexcept = default;

namespace {

using Buffers = FastSlicWorkspace::Buffers;
using Run = Buffers::Run;

struct Centre {
  float l = 0, a = 0, b = 0, e = 0;  // colour (and extra channel)
  float x = 0, y = 0;                 // pixel indices (column, row) within the block
};

// A centre's search window [cx - S, cx + S) x [cy - S, cy + S) (cx, cy: its truncated position), clipped.
struct Window {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// End (exclusive) of the run of labels equal to lr[x] that starts at x, within [x, w).
inline int RunEnd(const int32_t* lr, int x, int w) {
  const int32_t k = lr[x];
  int i = x + 1;
#if defined(__SSE2__)
  const __m128i vk = _mm_set1_epi32(k);
  for (; i + 4 <= w; i += 4) {
    const __m128i eq = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(lr + i)), vk);
    const int mask = _mm_movemask_ps(_mm_castsi128_ps(eq));
    if (mask != 0xF) return i + __builtin_ctz(static_cast<unsigned>(~mask));
  }
#endif
  while (i < w && lr[i] == k) ++i;
  return i;
}

inline const uint8_t* LabRow(const FastSlicInput& in, int y) { return in.lab + static_cast<size_t>(y) * in.lab_stride; }
inline const float* ExtraRow(const FastSlicInput& in, int y) {
  return in.extra == nullptr ? nullptr : in.extra + static_cast<size_t>(y) * in.extra_stride;
}

// Squared gradient magnitude summed over channels (central differences, replicated border).
float Gradient(const FastSlicInput& in, int x, int y) {
  const int xl = std::max(x - 1, 0), xr = std::min(x + 1, in.width - 1);
  const int yu = std::max(y - 1, 0), yd = std::min(y + 1, in.height - 1);
  const uint8_t *row = LabRow(in, y), *up = LabRow(in, yu), *down = LabRow(in, yd);
  float g = 0.0f;
  for (int c = 0; c < 3; ++c) {
    const float gx = static_cast<float>(row[3 * xr + c]) - static_cast<float>(row[3 * xl + c]);
    const float gy = static_cast<float>(down[3 * x + c]) - static_cast<float>(up[3 * x + c]);
    g += gx * gx + gy * gy;
  }
  if (in.extra != nullptr) {
    const float gx = ExtraRow(in, y)[xr] - ExtraRow(in, y)[xl];
    const float gy = ExtraRow(in, yd)[x] - ExtraRow(in, yu)[x];
    g += gx * gx + gy * gy;
  }
  return g;
}

Centre CentreAt(const FastSlicInput& in, int x, int y) {
  const uint8_t* lab = LabRow(in, y) + 3 * x;
  Centre c;
  c.l = lab[0];
  c.a = lab[1];
  c.b = lab[2];
  c.e = in.extra == nullptr ? 0.0f : ExtraRow(in, y)[x];
  c.x = static_cast<float>(x);
  c.y = static_cast<float>(y);
  return c;
}

// Seeds on a regular grid: round(w / S) x round(h / S) cells (at least one), each seed at its cell's centre,
// optionally moved to the lowest-gradient pixel of its 3x3 neighbourhood (first minimum in row-major order).
std::vector<Centre> Seeds(const FastSlicInput& in, int s, bool perturb) {
  const int nx = std::max(1, (2 * in.width + s) / (2 * s));
  const int ny = std::max(1, (2 * in.height + s) / (2 * s));
  std::vector<Centre> seeds;
  seeds.reserve(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j) {
    const int y = static_cast<int>((2 * static_cast<int64_t>(j) + 1) * in.height / (2 * ny));
    for (int i = 0; i < nx; ++i) {
      const int x = static_cast<int>((2 * static_cast<int64_t>(i) + 1) * in.width / (2 * nx));
      int bx = x, by = y;
      if (perturb) {
        float best = Gradient(in, x, y);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= in.width || yy >= in.height) continue;
            const float g = Gradient(in, xx, yy);
            if (g < best) {
              best = g;
              bx = xx;
              by = yy;
            }
          }
        }
      }
      seeds.push_back(CentreAt(in, bx, by));
    }
  }
  return seeds;
}

// --- Assignment kernels. For one row segment of a centre's window they keep, per pixel, the nearest centre so
// far (strict <: ties keep the earlier, lower-index centre). d = ((dl^2 + da^2) + db^2) + (spatial + row_spatial)
// [+ de^2], evaluated in this order by the vector bodies and the scalar tail alike, so every pixel gets
// bit-identical distances whichever kernel runs.
template <bool kExtra>
inline void AssignScalar(int i, int n, const float* l, const float* a, const float* b, const float* e,
                         const float* spatial, float row_spatial, const Centre& c, int32_t k, float* dist,
                         int32_t* label) {
  for (; i < n; ++i) {
    const float dl = l[i] - c.l, da = a[i] - c.a, db = b[i] - c.b;
    float d = ((dl * dl + da * da) + db * db) + (spatial[i] + row_spatial);
    if (kExtra) {
      const float de = e[i] - c.e;
      d += de * de;
    }
    if (d < dist[i]) {
      dist[i] = d;
      label[i] = k;
    }
  }
}

template <bool kExtra>
inline void AssignRow(int n, const float* l, const float* a, const float* b, const float* e, const float* spatial,
                      float row_spatial, const Centre& c, int32_t k, float* dist, int32_t* label) {
  int i = 0;
#if defined(__SSE2__)
  const __m128 vl = _mm_set1_ps(c.l), va = _mm_set1_ps(c.a), vb = _mm_set1_ps(c.b);
  const __m128 ve = _mm_set1_ps(c.e), vrow = _mm_set1_ps(row_spatial);
  const __m128i vk = _mm_set1_epi32(k);
  for (; i + 4 <= n; i += 4) {
    const __m128 dl = _mm_sub_ps(_mm_loadu_ps(l + i), vl);
    const __m128 da = _mm_sub_ps(_mm_loadu_ps(a + i), va);
    const __m128 db = _mm_sub_ps(_mm_loadu_ps(b + i), vb);
    __m128 d = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(dl, dl), _mm_mul_ps(da, da)), _mm_mul_ps(db, db)),
                          _mm_add_ps(_mm_loadu_ps(spatial + i), vrow));
    if (kExtra) {
      const __m128 de = _mm_sub_ps(_mm_loadu_ps(e + i), ve);
      d = _mm_add_ps(d, _mm_mul_ps(de, de));
    }
    const __m128 old = _mm_loadu_ps(dist + i);
    const __m128i closer = _mm_castps_si128(_mm_cmplt_ps(d, old));
    _mm_storeu_ps(dist + i, _mm_min_ps(d, old));  // d < old ? d : old
    __m128i* lp = reinterpret_cast<__m128i*>(label + i);
    const __m128i old_label = _mm_loadu_si128(lp);
    _mm_storeu_si128(lp, _mm_or_si128(_mm_and_si128(closer, vk), _mm_andnot_si128(closer, old_label)));
  }
#endif
  AssignScalar<kExtra>(i, n, l, a, b, e, spatial, row_spatial, c, k, dist, label);
}

#if defined(SACFUSE_SLIC_AVX2)
template <bool kExtra>
__attribute__((target("avx2"))) inline void AssignRowAvx2(int n, const float* l, const float* a, const float* b,
                                                          const float* e, const float* spatial, float row_spatial,
                                                          const Centre& c, int32_t k, float* dist,
                                                          int32_t* label) {
  int i = 0;
  const __m256 vl = _mm256_set1_ps(c.l), va = _mm256_set1_ps(c.a), vb = _mm256_set1_ps(c.b);
  const __m256 ve = _mm256_set1_ps(c.e), vrow = _mm256_set1_ps(row_spatial);
  const __m256 vk = _mm256_castsi256_ps(_mm256_set1_epi32(k));
  for (; i + 8 <= n; i += 8) {
    const __m256 dl = _mm256_sub_ps(_mm256_loadu_ps(l + i), vl);
    const __m256 da = _mm256_sub_ps(_mm256_loadu_ps(a + i), va);
    const __m256 db = _mm256_sub_ps(_mm256_loadu_ps(b + i), vb);
    __m256 d = _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dl, dl), _mm256_mul_ps(da, da)), _mm256_mul_ps(db, db)),
        _mm256_add_ps(_mm256_loadu_ps(spatial + i), vrow));
    if (kExtra) {
      const __m256 de = _mm256_sub_ps(_mm256_loadu_ps(e + i), ve);
      d = _mm256_add_ps(d, _mm256_mul_ps(de, de));
    }
    const __m256 old = _mm256_loadu_ps(dist + i);
    const __m256 closer = _mm256_cmp_ps(d, old, _CMP_LT_OQ);
    _mm256_storeu_ps(dist + i, _mm256_min_ps(d, old));  // d < old ? d : old
    float* lp = reinterpret_cast<float*>(label + i);   // labels are moved as raw bits
    _mm256_storeu_ps(lp, _mm256_blendv_ps(_mm256_loadu_ps(lp), vk, closer));
  }
  AssignScalar<kExtra>(i, n, l, a, b, e, spatial, row_spatial, c, k, dist, label);
}
#endif

// Per-centre sums of one update, added pixel by pixel into two copies (even and odd columns) so that neighbouring
// pixels of one cluster do not wait for each other's store; flushed into 64-bit totals before the 32-bit colour
// sums could overflow. Integer sums are exact, so the totals do not depend on the order of the additions.
struct alignas(16) PixelSum {
  int32_t l = 0, a = 0, b = 0, n = 0;  // colour sums, pixel count
  int64_t x = 0, y = 0;                // coordinate sums
};
struct Sum {
  int64_t l = 0, a = 0, b = 0, n = 0, x = 0, y = 0;
  double e = 0;  // extra channel
};
struct Sums {
  std::vector<PixelSum> even, odd;
  std::vector<double> e_even, e_odd;
  std::vector<Sum> total;
  void Reset(size_t n, bool extra) {
    even.assign(n, PixelSum());
    odd.assign(n, PixelSum());
    e_even.assign(extra ? n : 0, 0.0);
    e_odd.assign(extra ? n : 0, 0.0);
    total.assign(n, Sum());
  }
  void Flush() {
    for (size_t k = 0; k < total.size(); ++k) {
      Sum& t = total[k];
      const PixelSum& p = even[k];
      const PixelSum& q = odd[k];
      t.l += static_cast<int64_t>(p.l) + q.l;
      t.a += static_cast<int64_t>(p.a) + q.a;
      t.b += static_cast<int64_t>(p.b) + q.b;
      t.n += static_cast<int64_t>(p.n) + q.n;
      t.x += p.x + q.x;
      t.y += p.y + q.y;
      if (!e_even.empty()) t.e += e_even[k] + e_odd[k];
    }
    std::fill(even.begin(), even.end(), PixelSum());
    std::fill(odd.begin(), odd.end(), PixelSum());
    std::fill(e_even.begin(), e_even.end(), 0.0);
    std::fill(e_odd.begin(), e_odd.end(), 0.0);
  }
};

// Adds the pixels of one row to the sums of their centres.
template <bool kExtra>
inline void AccumulateRow(const int32_t* lr, const uint8_t* lab, const float* e, int w, int y, Sums* sums) {
  PixelSum* even = sums->even.data();
  PixelSum* odd = sums->odd.data();
  int x = 0;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  const __m128i step = _mm_set_epi64x(0, 2);
  __m128i xy_even = _mm_set_epi64x(y, 0), xy_odd = _mm_set_epi64x(y, 1);
  const auto add = [&](PixelSum* s, int col, __m128i xy) {
    uint32_t v;  // L, a, b of `col` and one byte of the next pixel, replaced by the count 1
    std::memcpy(&v, lab + 3 * col, 4);
    v = (v & 0x00FFFFFFu) | 0x01000000u;
    const __m128i colour = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(static_cast<int>(v)), zero), zero);
    __m128i* p = reinterpret_cast<__m128i*>(s + lr[col]);
    _mm_store_si128(p, _mm_add_epi32(_mm_load_si128(p), colour));
    _mm_store_si128(p + 1, _mm_add_epi64(_mm_load_si128(p + 1), xy));
  };
  for (; x + 2 < w; x += 2) {  // x + 1 < w - 1: the 4-byte reads stay inside the row
    add(even, x, xy_even);
    add(odd, x + 1, xy_odd);
    xy_even = _mm_add_epi64(xy_even, step);
    xy_odd = _mm_add_epi64(xy_odd, step);
  }
#endif
  for (; x < w; ++x) {
    PixelSum& s = ((x & 1) != 0 ? odd : even)[lr[x]];
    s.l += lab[3 * x];
    s.a += lab[3 * x + 1];
    s.b += lab[3 * x + 2];
    s.n += 1;
    s.x += x;
    s.y += y;
  }
  if (kExtra) {
    double* e_even = sums->e_even.data();
    double* e_odd = sums->e_odd.data();
    for (x = 0; x < w; ++x) ((x & 1) != 0 ? e_odd : e_even)[lr[x]] += e[x];
  }
}

// What one round does besides assigning.
enum class RoundOutput {
  kSums,  // accumulate the centre update
  kRuns,  // last round: collect the label runs for the connectivity pass
};

// One assignment round, row by row: each row is converted to float once, swept by every centre whose window
// covers it (in increasing centre index, so ties resolve as in centre-by-centre SLIC), then, while it is still in
// cache, summed into the centre update or cut into runs. Labels persist in `labels` between rounds: a pixel no
// moved window reaches keeps its previous label. `windows`/`order` (centres sorted by window top) and the spatial
// tables (2S floats per centre) are prepared by the caller.
template <bool kExtra, bool kAvx2>
__attribute__((always_inline)) inline void RoundRows(const FastSlicInput& in, const std::vector<Centre>& centres,
                                                     const std::vector<Window>& windows, int s,
                                                     float spatial_weight, RoundOutput output, int32_t* labels,
                                                     size_t label_stride, Buffers* buf, Sums* sums) {
  const int w = in.width;
  const size_t table = 2 * static_cast<size_t>(s);
  float* l = buf->rows.data();
  float* a = l + w;
  float* b = a + w;
  float* dist = b + w;
  // Rows after which the 32-bit colour sums are flushed: no sum can exceed 255 * w * flush_rows < 2^31 before.
  const int flush_rows = std::max(1, static_cast<int>(INT_MAX / (255 * static_cast<int64_t>(w) + 255)));
  std::vector<int32_t>& active = buf->active;  // centres covering the current row, ascending
  active.clear();
  size_t next = 0;  // into buf->order
  for (int y = 0; y < in.height; ++y) {
    active.erase(std::remove_if(active.begin(), active.end(),
                                [&](int32_t k) { return windows[static_cast<size_t>(k)].y1 <= y; }),
                 active.end());
    while (next < buf->order.size() && windows[static_cast<size_t>(buf->order[next])].y0 == y) {
      const int32_t k = buf->order[next++];
      active.insert(std::upper_bound(active.begin(), active.end(), k), k);
    }
    const uint8_t* lab = LabRow(in, y);
    for (int x = 0; x < w; ++x) {
      l[x] = lab[3 * x];
      a[x] = lab[3 * x + 1];
      b[x] = lab[3 * x + 2];
    }
    std::fill(dist, dist + w, FLT_MAX);
    const float* e = ExtraRow(in, y);
    int32_t* lr = labels + static_cast<size_t>(y) * label_stride;
    for (const int32_t k : active) {
      const Centre& c = centres[static_cast<size_t>(k)];
      const Window& win = windows[static_cast<size_t>(k)];
      const float dy = static_cast<float>(y) - c.y;
      const int x0 = win.x0;
      const float* spatial = &buf->spatial[static_cast<size_t>(k) * table];
      if constexpr (kAvx2) {
#if defined(SACFUSE_SLIC_AVX2)
        AssignRowAvx2<kExtra>(win.x1 - x0, l + x0, a + x0, b + x0, kExtra ? e + x0 : nullptr, spatial,
                              spatial_weight * dy * dy, c, k, dist + x0, lr + x0);
#endif
      } else {
        AssignRow<kExtra>(win.x1 - x0, l + x0, a + x0, b + x0, kExtra ? e + x0 : nullptr, spatial,
                          spatial_weight * dy * dy, c, k, dist + x0, lr + x0);
      }
    }
    if (output == RoundOutput::kRuns) {
      buf->row_begin[static_cast<size_t>(y)] = static_cast<int32_t>(buf->runs.size());
      for (int x = 0; x < w;) {
        const int x1 = RunEnd(lr, x, w);
        buf->runs.push_back({x, x1, lr[x]});
        x = x1;
      }
      continue;
    }
    AccumulateRow<kExtra>(lr, lab, e, w, y, sums);
    if ((y + 1) % flush_rows == 0) sums->Flush();
  }
}

template <bool kExtra>
void RoundDefault(const FastSlicInput& in, const std::vector<Centre>& centres, const std::vector<Window>& windows,
                  int s, float spatial_weight, RoundOutput output, int32_t* labels, size_t label_stride,
                  Buffers* buf, Sums* sums) {
  RoundRows<kExtra, false>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
}

#if defined(SACFUSE_SLIC_AVX2)
template <bool kExtra>
__attribute__((target("avx2"))) void RoundAvx2(const FastSlicInput& in, const std::vector<Centre>& centres,
                                               const std::vector<Window>& windows, int s, float spatial_weight,
                                               RoundOutput output, int32_t* labels, size_t label_stride,
                                               Buffers* buf, Sums* sums) {
  RoundRows<kExtra, true>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
}
#endif

// One round: windows, spatial tables and row order of the centres, then the row sweep with the widest vectors
// the CPU has.
void Round(const FastSlicInput& in, const std::vector<Centre>& centres, int s, float spatial_weight,
           RoundOutput output, int32_t* labels, size_t label_stride, Buffers* buf, Sums* sums) {
  const size_t table = 2 * static_cast<size_t>(s);
  std::vector<Window> windows(centres.size());
  buf->spatial.resize(table * centres.size());
  buf->order.clear();
  for (size_t k = 0; k < centres.size(); ++k) {
    const Centre& c = centres[k];
    const int cx = static_cast<int>(c.x), cy = static_cast<int>(c.y);
    Window& win = windows[k];
    win.x0 = std::max(0, cx - s);
    win.x1 = std::min(in.width, cx + s);
    win.y0 = std::max(0, cy - s);
    win.y1 = std::min(in.height, cy + s);
    if (win.empty()) continue;
    float* spatial = &buf->spatial[k * table];
    for (int i = 0; i < win.x1 - win.x0; ++i) {
      const float dx = static_cast<float>(win.x0 + i) - c.x;
      spatial[i] = spatial_weight * dx * dx;
    }
    buf->order.push_back(static_cast<int32_t>(k));
  }
  std::stable_sort(buf->order.begin(), buf->order.end(), [&](int32_t p, int32_t q) {
    return windows[static_cast<size_t>(p)].y0 < windows[static_cast<size_t>(q)].y0;
  });
  buf->rows.resize(4 * static_cast<size_t>(in.width));
  if (output == RoundOutput::kRuns) {
    buf->runs.clear();
    buf->row_begin.resize(static_cast<size_t>(in.height) + 1);
  }
#if defined(SACFUSE_SLIC_AVX2)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    if (in.extra != nullptr) {
      RoundAvx2<true>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
    } else {
      RoundAvx2<false>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
    }
  } else
#endif
  {
    if (in.extra != nullptr) {
      RoundDefault<true>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
    } else {
      RoundDefault<false>(in, centres, windows, s, spatial_weight, output, labels, label_stride, buf, sums);
    }
  }
  if (output == RoundOutput::kRuns) {
    buf->row_begin[static_cast<size_t>(in.height)] = static_cast<int32_t>(buf->runs.size());
  }
}

// New centres: the means of the sums. Centres that lost all their pixels stay where they were.
void UpdateCentres(Sums* sums, std::vector<Centre>* centres) {
  sums->Flush();
  for (size_t k = 0; k < centres->size(); ++k) {
    const Sum& s = sums->total[k];
    if (s.n == 0) continue;
    const double inv = 1.0 / static_cast<double>(s.n);
    Centre& c = (*centres)[k];
    c.l = static_cast<float>(static_cast<double>(s.l) * inv);
    c.a = static_cast<float>(static_cast<double>(s.a) * inv);
    c.b = static_cast<float>(static_cast<double>(s.b) * inv);
    c.e = static_cast<float>(s.e * inv);
    c.x = static_cast<float>(static_cast<double>(s.x) * inv);
    c.y = static_cast<float>(static_cast<double>(s.y) * inv);
  }
}

// Connectivity enforcement and final numbering on the horizontal label runs of the last round (buf->runs,
// buf->row_begin). Runs of adjacent rows that overlap and share a label are joined (union-find; each set's root
// is its first run in row-major order). Components smaller than `min_size` take the final label of the component
// left of (at column 0: above) their first pixel, which comes earlier in row-major order and is therefore already
// final. Writes dense labels in order of first appearance into `out`.
int EnforceConnectivity(int w, int h, double min_size, int32_t* out, size_t out_stride, Buffers* buf) {
  const std::vector<Run>& runs = buf->runs;
  const std::vector<int32_t>& row_begin = buf->row_begin;
  const size_t num_runs = runs.size();
  std::vector<int32_t>& parent = buf->parent;
  parent.resize(num_runs);
  for (size_t i = 0; i < num_runs; ++i) parent[i] = static_cast<int32_t>(i);
  const auto find = [&parent](int32_t a) {
    while (parent[static_cast<size_t>(a)] != a) {
      parent[static_cast<size_t>(a)] = parent[static_cast<size_t>(parent[static_cast<size_t>(a)])];
      a = parent[static_cast<size_t>(a)];
    }
    return a;
  };
  for (int y = 1; y < h; ++y) {
    // Runs tile each row, so walking both rows by run ends visits exactly the overlapping pairs.
    int32_t i = row_begin[static_cast<size_t>(y)], j = row_begin[static_cast<size_t>(y) - 1];
    const int32_t i_end = row_begin[static_cast<size_t>(y) + 1], j_end = row_begin[static_cast<size_t>(y)];
    while (i < i_end && j < j_end) {
      const Run& ri = runs[static_cast<size_t>(i)];
      const Run& rj = runs[static_cast<size_t>(j)];
      if (ri.label == rj.label) {
        const int32_t a = find(i), b = find(j);
        if (a < b) {
          parent[static_cast<size_t>(b)] = a;
        } else if (b < a) {
          parent[static_cast<size_t>(a)] = b;
        }
      }
      if (ri.x1 < rj.x1) {
        ++i;
      } else if (rj.x1 < ri.x1) {
        ++j;
      } else {
        ++i;
        ++j;
      }
    }
  }
  // Flatten: parents precede their children, so one forward pass gives every run its root.
  std::vector<int64_t>& size = buf->size;
  size.assign(num_runs, 0);
  for (size_t i = 0; i < num_runs; ++i) {
    parent[i] = parent[static_cast<size_t>(parent[i])];
    size[static_cast<size_t>(parent[i])] += runs[i].x1 - runs[i].x0;
  }
  std::vector<int32_t>& final_root = buf->final_root;
  final_root.assign(num_runs, -1);
  bool first_is_small = false;
  for (int y = 0; y < h; ++y) {
    for (int32_t i = row_begin[static_cast<size_t>(y)]; i < row_begin[static_cast<size_t>(y) + 1]; ++i) {
      if (parent[static_cast<size_t>(i)] != i) continue;
      if (static_cast<double>(size[static_cast<size_t>(i)]) >= min_size) {
        final_root[static_cast<size_t>(i)] = i;
      } else if (runs[static_cast<size_t>(i)].x0 > 0) {
        final_root[static_cast<size_t>(i)] = final_root[static_cast<size_t>(parent[static_cast<size_t>(i) - 1])];
      } else if (y > 0) {
        final_root[static_cast<size_t>(i)] =
            final_root[static_cast<size_t>(parent[static_cast<size_t>(row_begin[static_cast<size_t>(y) - 1])])];
      } else {
        final_root[static_cast<size_t>(i)] = i;  // the top-left component: nothing earlier to merge into
        first_is_small = true;
      }
    }
  }
  if (first_is_small) {
    // Merge it (and what was merged into it) into the component right of its first run, else below it.
    int32_t neighbour = -1;
    if (row_begin[1] > 1) {
      neighbour = 1;
    } else if (h > 1) {
      neighbour = row_begin[1];
    }
    if (neighbour >= 0) {
      const int32_t target = final_root[static_cast<size_t>(parent[static_cast<size_t>(neighbour)])];
      if (target != 0) {
        for (int32_t& f : final_root) {
          if (f == 0) f = target;
        }
      }
    }
  }
  // Dense labels in order of first appearance, written run by run.
  std::vector<int32_t>& id = buf->id;
  id.assign(num_runs, -1);
  int32_t count = 0;
  for (int y = 0; y < h; ++y) {
    int32_t* lr = out + static_cast<size_t>(y) * out_stride;
    for (int32_t i = row_begin[static_cast<size_t>(y)]; i < row_begin[static_cast<size_t>(y) + 1]; ++i) {
      const int32_t f = final_root[static_cast<size_t>(parent[static_cast<size_t>(i)])];
      int32_t& label = id[static_cast<size_t>(f)];
      if (label < 0) label = count++;
      const Run& r = runs[static_cast<size_t>(i)];
      std::fill(lr + r.x0, lr + r.x1, label);
    }
  }
  return count;
}

}  // namespace

int FastSlicEnforceConnectivity(int width, int height, const int32_t* labels, size_t label_stride, double min_size,
                                int32_t* out, size_t out_stride) {
  if (width < 1 || height < 1 || labels == nullptr || out == nullptr || label_stride < static_cast<size_t>(width) ||
      out_stride < static_cast<size_t>(width)) {
    throw std::invalid_argument("FastSlicEnforceConnectivity: bad geometry");
  }
  FastSlicWorkspace workspace;
  Buffers& buf = workspace.buffers();
  buf.row_begin.resize(static_cast<size_t>(height) + 1);
  for (int y = 0; y < height; ++y) {
    buf.row_begin[static_cast<size_t>(y)] = static_cast<int32_t>(buf.runs.size());
    const int32_t* lr = labels + static_cast<size_t>(y) * label_stride;
    for (int x = 0; x < width;) {
      const int x1 = RunEnd(lr, x, width);
      buf.runs.push_back({x, x1, lr[x]});
      x = x1;
    }
  }
  buf.row_begin[static_cast<size_t>(height)] = static_cast<int32_t>(buf.runs.size());
  return EnforceConnectivity(width, height, min_size, out, out_stride, &buf);
}

int FastSlicSegment(const FastSlicInput& in, const FastSlicParams& params, int32_t* labels, size_t label_stride,
                    FastSlicWorkspace* workspace) {
  if (in.width < 1 || in.height < 1 || in.lab == nullptr || labels == nullptr ||
      in.lab_stride < 3 * static_cast<size_t>(in.width) || label_stride < static_cast<size_t>(in.width) ||
      (in.extra != nullptr && in.extra_stride < static_cast<size_t>(in.width))) {
    throw std::invalid_argument("FastSlicSegment: bad input geometry");
  }
  if (params.region_size_px < 2 || params.iterations < 1 || !(params.ruler > 0.0f) ||
      params.min_fragment_percent < 0 || params.min_fragment_percent > 100) {
    throw std::invalid_argument("FastSlicSegment: bad parameters");
  }
  FastSlicWorkspace local;
  Buffers& buf = (workspace != nullptr ? workspace : &local)->buffers();
  const int s = params.region_size_px;
  std::vector<Centre> centres = Seeds(in, s, params.perturb_seeds);
  const float spatial_weight = (params.ruler / static_cast<float>(s)) * (params.ruler / static_cast<float>(s));

  // Every pixel lies in some seed's window (seed spacing < 2S), so the first round labels all of them.
  for (int y = 0; y < in.height; ++y) {
    int32_t* row = labels + static_cast<size_t>(y) * label_stride;
    std::fill(row, row + in.width, 0);
  }
  Sums sums;
  for (int it = 0; it < params.iterations; ++it) {
    const bool last = it + 1 == params.iterations;
    if (!last) sums.Reset(centres.size(), in.extra != nullptr);
    Round(in, centres, s, spatial_weight, last ? RoundOutput::kRuns : RoundOutput::kSums, labels, label_stride,
          &buf, &sums);
    if (!last) UpdateCentres(&sums, &centres);
  }
  const double mean_region = static_cast<double>(in.width) * in.height / static_cast<double>(centres.size());
  return EnforceConnectivity(in.width, in.height, mean_region * params.min_fragment_percent / 100.0, labels,
                             label_stride, &buf);
}

}  // namespace sacfuse
