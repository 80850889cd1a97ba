#include "tools/bench/quality_bench_table.h"

#include <algorithm>
#include <cmath>

namespace sacfuse::bench {
namespace {

bool SameGroup(const RowSpec& a, const RowSpec& b) {
  return a.section == b.section && a.scene == b.scene && a.error_scale == b.error_scale;
}

// Running means of every metric column; NaN values are left out of their column.
class MetricMeans {
 public:
  void Add(const RowMetrics& m) {
    const double values[kColumns] = {m.f1_2gsd_pct, m.f1_5gsd_pct, m.accuracy_2gsd_pct,
                                     m.completeness_2gsd_pct, m.mean_abs_distance_m, static_cast<double>(m.points),
                                     m.redundancy, m.wall_s, m.peak_rss_mib, m.dsm_nmad_m,
                                     m.dsm_completeness_pct};
    for (int i = 0; i < kColumns; ++i) {
      if (std::isfinite(values[i])) {
        sum_[i] += values[i];
        ++count_[i];
      }
    }
  }
  RowMetrics Mean() const {
    double v[kColumns];
    for (int i = 0; i < kColumns; ++i) v[i] = count_[i] > 0 ? sum_[i] / count_[i] : kNoValue;
    RowMetrics m;
    m.f1_2gsd_pct = v[0];
    m.f1_5gsd_pct = v[1];
    m.accuracy_2gsd_pct = v[2];
    m.completeness_2gsd_pct = v[3];
    m.mean_abs_distance_m = v[4];
    m.points = std::isfinite(v[5]) ? static_cast<uint64_t>(std::llround(v[5])) : 0;
    m.redundancy = v[6];
    m.wall_s = v[7];
    m.peak_rss_mib = v[8];
    m.dsm_nmad_m = v[9];
    m.dsm_completeness_pct = v[10];
    return m;
  }

 private:
  static constexpr int kColumns = 11;
  double sum_[kColumns] = {};
  int count_[kColumns] = {};
};

double MeanOf(const std::vector<double>& values) {
  double sum = 0;
  int n = 0;
  for (const double v : values) {
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  }
  return n > 0 ? sum / n : kNoValue;
}

}  // namespace

double GapClosed(double f1_sac, double f1_best_other, double f1_ceiling) {
  if (!std::isfinite(f1_sac) || !std::isfinite(f1_best_other) || !std::isfinite(f1_ceiling)) return kNoValue;
  const double gap = f1_ceiling - f1_best_other;
  if (!(gap > 0)) return kNoValue;
  return (f1_sac - f1_best_other) / gap;
}

int RankOf(double value, const std::vector<double>& values) {
  int rank = 1;
  for (const double v : values) {
    if (std::isfinite(v) && v > value) ++rank;
  }
  return rank;
}

std::vector<GroupSummary> SummariseGroups(const std::vector<BenchRow>& rows) {
  std::vector<GroupSummary> out;
  std::vector<const RowSpec*> keys;
  for (const BenchRow& r : rows) {
    if (std::none_of(keys.begin(), keys.end(), [&](const RowSpec* k) { return SameGroup(*k, r.spec); })) {
      keys.push_back(&r.spec);
    }
  }
  for (const RowSpec* key : keys) {
    GroupSummary g;
    g.section = key->section;
    g.scene = key->scene;
    g.error_scale = key->error_scale;
    std::vector<double> f2, f5;
    const BenchRow* sac = nullptr;
    for (const BenchRow& r : rows) {
      if (!SameGroup(*key, r.spec) || !r.result.ok()) continue;
      if (r.spec.is_ceiling) {
        g.ceiling_f1_2gsd = r.result.metrics.f1_2gsd_pct;
        continue;
      }
      f2.push_back(r.result.metrics.f1_2gsd_pct);
      f5.push_back(r.result.metrics.f1_5gsd_pct);
      if (r.spec.is_sac) {
        sac = &r;
      } else if (std::isfinite(r.result.metrics.f1_2gsd_pct) &&
                 (!std::isfinite(g.best_other_f1_2gsd) || r.result.metrics.f1_2gsd_pct > g.best_other_f1_2gsd)) {
        g.best_other_f1_2gsd = r.result.metrics.f1_2gsd_pct;
        g.best_other = r.spec.name;
      }
    }
    g.ranked = static_cast<int>(f2.size());
    if (sac != nullptr) {
      g.sac_f1_2gsd = sac->result.metrics.f1_2gsd_pct;
      g.sac_rank_2gsd = RankOf(sac->result.metrics.f1_2gsd_pct, f2);
      g.sac_rank_5gsd = RankOf(sac->result.metrics.f1_5gsd_pct, f5);
    }
    g.gap_closed = GapClosed(g.sac_f1_2gsd, g.best_other_f1_2gsd, g.ceiling_f1_2gsd);
    out.push_back(g);
  }
  return out;
}

std::vector<ScaleAverage> AverageOverBlocks(const std::vector<BenchRow>& rows,
                                            const std::vector<GroupSummary>& summaries) {
  std::vector<ScaleAverage> out;
  for (const BenchRow& r : rows) {
    if (r.spec.section != "main") continue;
    if (std::none_of(out.begin(), out.end(), [&](const ScaleAverage& a) { return a.error_scale == r.spec.error_scale; })) {
      ScaleAverage a;
      a.error_scale = r.spec.error_scale;
      out.push_back(a);
    }
  }
  for (ScaleAverage& a : out) {
    std::vector<std::pair<std::string, MetricMeans>> means;
    for (const BenchRow& r : rows) {
      if (r.spec.section != "main" || r.spec.error_scale != a.error_scale) continue;
      auto it = std::find_if(means.begin(), means.end(), [&](const auto& m) { return m.first == r.spec.name; });
      if (it == means.end()) {
        means.emplace_back(r.spec.name, MetricMeans());
        a.rows.push_back({r.spec.name, 0, {}});
        it = means.end() - 1;
      }
      if (!r.result.ok()) continue;
      it->second.Add(r.result.metrics);
      ++a.rows[it - means.begin()].blocks;
      if (std::find(a.scenes.begin(), a.scenes.end(), r.spec.scene) == a.scenes.end()) a.scenes.push_back(r.spec.scene);
    }
    for (size_t i = 0; i < means.size(); ++i) a.rows[i].mean = means[i].second.Mean();
    std::vector<double> gaps, rank2, rank5;
    for (const GroupSummary& g : summaries) {
      if (g.section != "main" || g.error_scale != a.error_scale) continue;
      gaps.push_back(g.gap_closed);
      if (g.sac_rank_2gsd > 0) {
        rank2.push_back(g.sac_rank_2gsd);
        rank5.push_back(g.sac_rank_5gsd);
      }
    }
    a.gap_closed = MeanOf(gaps);
    a.sac_rank_2gsd = MeanOf(rank2);
    a.sac_rank_5gsd = MeanOf(rank5);
  }
  return out;
}

}  // namespace sacfuse::bench
