#include "core/coregistration.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include "core/box2d.h"
#include "core/depth_normals.h"
#include "core/median.h"
#include "core/option_check.h"
#include "core/sac_view.h"
#include "core/view_neighbors.h"

namespace sacfuse {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// A pair needs this many residuals to count: fewer say nothing reliable about two poses.
constexpr size_t kMinPairResiduals = 50;
// Prior weight (in residuals of one metre) holding each correction small where the data say nothing.
constexpr double kPriorWeight = 1.0;
// Levenberg-Marquardt: the diagonal of the normal equations is multiplied by 1 + kDamping.
constexpr double kDamping = 1.0;
// Radius of the plane fits giving the neighbours' normals, decimated pixels.
constexpr int kNormalRadiusPx = 1;

// The sums of one pair (a, b) of one pass: the normal equations' blocks of both views' six unknowns.
struct PairSums {
  uint32_t a = 0, b = 0;
  Matrix6d aa = Matrix6d::Zero(), ab = Matrix6d::Zero(), bb = Matrix6d::Zero();
  Vector6d ga = Vector6d::Zero(), gb = Vector6d::Zero();
  size_t n = 0;
  double weighted_ss = 0.0, ss = 0.0;  // sum of w r^2 and of r^2, m^2
};

// One view during the solve, in the block's local frame (world minus `origin`, so sums stay exact).
struct ViewState {
  const CoregistrationInput* input = nullptr;
  SacView sac;                                  // current pose, decimated depth
  Rigid3d correction;                           // local'_from_local, accumulated over the steps
  LazyPlaneFitNormals normals;                  // world normals at the first pose (rotate with `correction`)
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  // centroid of the samples at the current pose
  double radius_m = 1.0;                        // rms distance of the samples from the pivot
  size_t samples = 0;
  int sample_step = 1;                          // samples: every sample_step-th decimated pixel
};

SacView DecimatedSacView(const CoregistrationInput& in, const Rigid3d& cam_from_local) {
  View v = in.view;
  v.cam_from_world = cam_from_local;
  SacView sac = MakeSacView(v, &in.depth, nullptr, nullptr);
  sac.depth_camera = in.depth_camera;
  return sac;
}

template <typename F>
void ForEachSample(const ViewState& s, F&& f) {
  const DepthMap& depth = *s.sac.depth;
  for (int row = s.sample_step / 2; row < depth.height; row += s.sample_step) {
    for (int col = s.sample_step / 2; col < depth.width; col += s.sample_step) {
      const float z = depth.at(row, col);
      if (!IsValidDepth(z)) continue;
      f(s.sac.world_from_cam * s.sac.depth_camera.Unproject(col + 0.5, row + 0.5, z), static_cast<double>(z));
    }
  }
}

void UpdatePivot(ViewState* s) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  size_t n = 0;
  ForEachSample(*s, [&](const Eigen::Vector3d& x, double) { sum += x, ++n; });
  s->samples = n;
  if (n == 0) return;
  s->pivot = sum / static_cast<double>(n);
  double ss = 0.0;
  ForEachSample(*s, [&](const Eigen::Vector3d& x, double) { ss += (x - s->pivot).squaredNorm(); });
  s->radius_m = std::max(1.0, std::sqrt(ss / static_cast<double>(n)));
}

// m's upper triangle += w u u^T, each entry as Eigen's selfadjointView<Upper>().rankUpdate(u, w) computes it
// ((w u_i) u_j), but inlined: the library's call was an eighth of the stage's time.
inline void AddRankOneUpper(const Vector6d& u, double w, Matrix6d* m) {
  for (int i = 0; i < 6; ++i) {
    const double wu = w * u[i];
    for (int j = 0; j <= i; ++j) (*m)(j, i) += wu * u[j];
  }
}

// Point-to-plane residuals of view a's samples against each neighbour, summed per pair.
std::vector<PairSums> PairsOfView(const std::vector<ViewState>& states, uint32_t a,
                                  const std::vector<uint32_t>& neighbors, const CoregistrationOptions& o) {
  const ViewState& sa = states[a];
  std::vector<PairSums> sums(neighbors.size());
  std::vector<Eigen::Matrix3d> normal_rotation(neighbors.size());
  for (size_t i = 0; i < neighbors.size(); ++i) {
    sums[i].a = a;
    sums[i].b = neighbors[i];
    normal_rotation[i] = states[neighbors[i]].correction.rotation.toRotationMatrix();
  }
  // The samples first, then one neighbour at a time, in three passes: where every sample lands in the neighbour
  // (its depth there), the neighbour's normals at those pixels, then the sums. A pass's reads do not depend on one
  // another, so their cache misses overlap; sample-major order with one residual at a time waited for most of
  // them. Each pair's sums still add its residuals in sample order, so the result is the same.
  struct Sample {
    Eigen::Vector3d x;
    double window_m, huber_m;
  };
  std::vector<Sample> samples;
  samples.reserve(sa.samples);
  const double gsd_per_depth = 1.0 / sa.input->view.camera.fx;
  ForEachSample(sa, [&](const Eigen::Vector3d& x, double z) {
    const double gsd = z * gsd_per_depth;
    samples.push_back({x, o.max_residual_gsd * gsd, o.huber_gsd * gsd});
  });
  struct Hit {
    const Sample* sample;
    int row, col;
    float depth_m;
    Eigen::Vector3f normal;
  };
  std::vector<Hit> hits;
  hits.reserve(samples.size());
  for (size_t i = 0; i < neighbors.size(); ++i) {
    const ViewState& sb = states[neighbors[i]];
    hits.clear();
    for (const Sample& sample : samples) {
      const DepthLookup at = LookupDepth(sb.sac, sample.x);
      if (at.inside && IsValidDepth(at.stored_depth_m)) {
        hits.push_back({&sample, at.row, at.col, at.stored_depth_m, Eigen::Vector3f::Zero()});
      }
    }
    for (Hit& hit : hits) hit.normal = sb.normals.At(hit.row, hit.col);
    PairSums& p = sums[i];
    for (const Hit& hit : hits) {
      const Eigen::Vector3f& nf = hit.normal;
      if (nf[0] == 0.0f && nf[1] == 0.0f && nf[2] == 0.0f) continue;
      const Eigen::Vector3d& x = hit.sample->x;
      const Eigen::Vector3d n = normal_rotation[i] * nf.cast<double>();
      const Eigen::Vector3d xb =
          sb.sac.world_from_cam * sb.sac.depth_camera.Unproject(hit.col + 0.5, hit.row + 0.5, hit.depth_m);
      const double r = n.dot(x - xb);
      if (std::abs(r) > hit.sample->window_m) continue;
      const double w = std::abs(r) <= hit.sample->huber_m ? 1.0 : hit.sample->huber_m / std::abs(r);
      Vector6d ja, jb;
      ja << (x - sa.pivot).cross(n), n;
      jb << -(xb - sb.pivot).cross(n), -n;
      AddRankOneUpper(ja, w, &p.aa);
      AddRankOneUpper(jb, w, &p.bb);
      p.ab.noalias() += (w * ja) * jb.transpose();
      p.ga += (w * r) * ja;
      p.gb += (w * r) * jb;
      ++p.n;
      p.weighted_ss += w * r * r;
      p.ss += r * r;
    }
  }
  std::vector<PairSums> kept;
  for (PairSums& p : sums) {
    if (p.n < kMinPairResiduals) continue;
    p.aa = p.aa.selfadjointView<Eigen::Upper>();
    p.bb = p.bb.selfadjointView<Eigen::Upper>();
    kept.push_back(p);
  }
  return kept;
}

// Buffers of the iterations, reused: fresh ones every iteration cost page faults on the calling thread, a serial
// share of the stage (issue 48).
struct IterationBuffers {
  std::vector<std::vector<PairSums>> per_view;
  std::vector<PairSums> pairs;
  std::vector<Eigen::Triplet<double>> triplets;
};

// Every view's pairs, in view order (deterministic for any thread count), into buffers->pairs.
const std::vector<PairSums>& AllPairs(const std::vector<ViewState>& states,
                                      const std::vector<std::vector<uint32_t>>& nbrs, const CoregistrationOptions& o,
                                      IterationBuffers* buffers) {
  std::vector<std::vector<PairSums>>& per_view = buffers->per_view;
  per_view.resize(states.size());
  tbb::parallel_for(size_t{0}, states.size(), [&](size_t a) {
    per_view[a].clear();
    if (states[a].samples > 0) per_view[a] = PairsOfView(states, static_cast<uint32_t>(a), nbrs[a], o);
  });
  std::vector<size_t> first(states.size() + 1, 0);
  for (size_t a = 0; a < states.size(); ++a) first[a + 1] = first[a] + per_view[a].size();
  buffers->pairs.resize(first.back());
  tbb::parallel_for(size_t{0}, states.size(), [&](size_t a) {
    std::copy(per_view[a].begin(), per_view[a].end(), buffers->pairs.begin() + static_cast<std::ptrdiff_t>(first[a]));
  });
  return buffers->pairs;
}

// The 36 entries of block (row_view, col_view) = m, row by row, at `t`.
void SetBlock(Eigen::Triplet<double>* t, uint32_t row_view, uint32_t col_view, const Matrix6d& m) {
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) *t++ = Eigen::Triplet<double>(6 * row_view + i, 6 * col_view + j, m(i, j));
  }
}

// The damped, datum-constrained step: minimises the linearised cost plus prior and damping with the mean rotation
// and the mean translation of the step held at zero (exactly, through the constraint's six columns).
Eigen::VectorXd SolveStep(const std::vector<ViewState>& states, const std::vector<PairSums>& pairs,
                          std::vector<Eigen::Triplet<double>>* triplet_buffer) {
  const int n = static_cast<int>(states.size()) * 6;
  // Each pair's four blocks in the pair's place of the list (the order the matrix sums duplicates in), in parallel.
  std::vector<Eigen::Triplet<double>>& triplets = *triplet_buffer;
  constexpr size_t kPerPair = 4 * 36;
  triplets.resize(pairs.size() * kPerPair);
  tbb::parallel_for(size_t{0}, pairs.size(), [&](size_t k) {
    const PairSums& p = pairs[k];
    Eigen::Triplet<double>* t = triplets.data() + k * kPerPair;
    SetBlock(t, p.a, p.a, p.aa);
    SetBlock(t + 36, p.b, p.b, p.bb);
    SetBlock(t + 72, p.a, p.b, p.ab);
    SetBlock(t + 108, p.b, p.a, p.ab.transpose());
  });
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  for (const PairSums& p : pairs) {
    g.segment<6>(6 * p.a) += p.ga;
    g.segment<6>(6 * p.b) += p.gb;
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd diagonal = normal.diagonal();
  for (size_t k = 0; k < states.size(); ++k) {
    const double r2 = states[k].radius_m * states[k].radius_m;
    for (int j = 0; j < 6; ++j) {
      const int i = static_cast<int>(6 * k) + j;
      diagonal[i] = (1.0 + kDamping) * (diagonal[i] + kPriorWeight * (j < 3 ? r2 : 1.0));
    }
  }
  for (int i = 0; i < n; ++i) normal.coeffRef(i, i) = diagonal[i];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  Eigen::MatrixXd constraint = Eigen::MatrixXd::Zero(n, 6);  // columns: mean of each unknown
  for (size_t k = 0; k < states.size(); ++k) constraint.block<6, 6>(6 * k, 0).setIdentity();
  const Eigen::VectorXd free = solver.solve(-g);
  const Eigen::MatrixXd y = solver.solve(constraint);
  const Eigen::Matrix<double, 6, 6> cy = constraint.transpose() * y;
  return free - y * cy.ldlt().solve(constraint.transpose() * free);
}

Eigen::Quaterniond RotationOf(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-18) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

CoregistrationIteration Summarise(const std::vector<PairSums>& pairs) {
  CoregistrationIteration it;
  double wss = 0.0;
  for (const PairSums& p : pairs) it.residuals += p.n, wss += p.weighted_ss;
  it.weighted_rms_m = it.residuals > 0 ? std::sqrt(wss / static_cast<double>(it.residuals)) : 0.0;
  return it;
}

// Per view: residuals with the view on either side and their rms.
void ViewResiduals(const std::vector<PairSums>& pairs, std::vector<ViewCorrection>* views, bool after) {
  std::vector<double> ss(views->size(), 0.0);
  std::vector<size_t> n(views->size(), 0);
  for (const PairSums& p : pairs) {
    for (uint32_t k : {p.a, p.b}) ss[k] += p.ss, n[k] += p.n;
  }
  for (size_t k = 0; k < views->size(); ++k) {
    const double rms = n[k] > 0 ? std::sqrt(ss[k] / static_cast<double>(n[k])) : 0.0;
    (after ? (*views)[k].residuals_after : (*views)[k].residuals_before) = n[k];
    (after ? (*views)[k].rms_after_m : (*views)[k].rms_before_m) = rms;
  }
}

}  // namespace

void ValidateCoregistrationOptions(const CoregistrationOptions& o) {
  OptionChecker c;
  c.InRange("CoregistrationOptions.max_pixels_per_view", o.max_pixels_per_view, 1000, 100000000);
  c.InRange("CoregistrationOptions.samples_per_view", o.samples_per_view, 100, 100000000);
  c.InRange("CoregistrationOptions.iterations", o.iterations, 1, 50);
  c.InRange("CoregistrationOptions.max_neighbor_views", o.max_neighbor_views, 1, 256);
  c.InRange("CoregistrationOptions.max_view_angle_deg", o.max_view_angle_deg, 0.0, 180.0);
  c.Greater("CoregistrationOptions.huber_gsd", o.huber_gsd, 0.0);
  c.Greater("CoregistrationOptions.max_residual_gsd", o.max_residual_gsd, 0.0);
  c.ThrowIfFailed("co-registration options");
}

int CoregistrationDecimation(int width, int height, int max_pixels) {
  int k = 1;
  while (static_cast<int64_t>(width / k) * (height / k) > max_pixels) k += 2;
  return k;
}

std::vector<int> DecimatedRows(int height, int k) {
  std::vector<int> rows;
  for (int r = 0; r < height / k; ++r) rows.push_back(k * r + (k - 1) / 2);
  return rows;
}

DepthMap DecimateDepthRows(const DepthMap& rows, int k) {
  DepthMap out(rows.width / k, rows.height, 1, 0.0f);
  const int offset = (k - 1) / 2;
  for (int r = 0; r < out.height; ++r) {
    for (int c = 0; c < out.width; ++c) out.at(r, c) = rows.at(r, k * c + offset);
  }
  return out;
}

DepthMap DecimateDepth(const DepthMap& depth, int k) {
  const std::vector<int> rows = DecimatedRows(depth.height, k);
  DepthMap picked(depth.width, static_cast<int>(rows.size()), 1, 0.0f);
  for (size_t r = 0; r < rows.size(); ++r) {
    std::copy_n(&depth.at(rows[r], 0), depth.width, &picked.at(static_cast<int>(r), 0));
  }
  return DecimateDepthRows(picked, k);
}

CoregistrationResult Coregister(const std::vector<CoregistrationInput>& inputs, const CoregistrationOptions& o) {
  ValidateCoregistrationOptions(o);
  CoregistrationResult result;
  const size_t nviews = inputs.size();
  result.views.resize(nviews);
  if (nviews == 0) return result;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const auto& in : inputs) origin += in.view.CenterInWorld() / static_cast<double>(nviews);
  const Rigid3d local_from_world{Eigen::Quaterniond::Identity(), -origin};

  std::vector<ViewState> states(nviews);
  std::vector<Box2d> boxes(nviews);
  std::vector<Eigen::Vector3d> directions(nviews);
  tbb::parallel_for(size_t{0}, nviews, [&](size_t k) {
    ViewState& s = states[k];
    s.input = &inputs[k];
    s.sac = DecimatedSacView(inputs[k], inputs[k].view.cam_from_world * local_from_world.Inverse());
    const size_t pixels = inputs[k].depth.num_pixels();
    s.sample_step = std::max(1, static_cast<int>(std::floor(std::sqrt(
                                    static_cast<double>(pixels) / static_cast<double>(o.samples_per_view)))));
    s.normals = LazyPlaneFitNormals(s.sac, kNormalRadiusPx);
    UpdatePivot(&s);
    ForEachSample(s, [&](const Eigen::Vector3d& x, double) { boxes[k].Extend(Eigen::Vector2d(x.x(), x.y())); });
    directions[k] = s.sac.view.ViewDirectionInWorld();
    result.views[k].samples = s.samples;
  });
  const std::vector<Eigen::Vector3d> pivot0 = [&] {
    std::vector<Eigen::Vector3d> p;
    for (const ViewState& s : states) p.push_back(s.pivot);
    return p;
  }();
  const std::vector<std::vector<uint32_t>> nbrs = NeighborsFromFootprints(
      boxes, directions, NeighborViewOptions{o.max_neighbor_views, o.max_view_angle_deg, 0.05});

  IterationBuffers buffers;
  for (int it = 0; it <= o.iterations; ++it) {
    const std::vector<PairSums>& pairs = AllPairs(states, nbrs, o, &buffers);
    CoregistrationIteration summary = Summarise(pairs);
    if (it == 0) result.pairs = pairs.size(), ViewResiduals(pairs, &result.views, false);
    if (it == o.iterations) {  // residuals after the last step: reported, not solved
      ViewResiduals(pairs, &result.views, true);
      result.iterations.push_back(summary);
      break;
    }
    const Eigen::VectorXd x = SolveStep(states, pairs, &buffers.triplets);
    std::vector<double> step_deg(nviews), step_m(nviews);
    for (size_t k = 0; k < nviews; ++k) {
      ViewState& s = states[k];
      const Eigen::Vector3d w = x.segment<3>(6 * k), t = x.segment<3>(6 * k + 3);
      const Eigen::Quaterniond q = RotationOf(w);
      const Rigid3d step{q, s.pivot + t - q * s.pivot};  // X' = q (X - P) + P + t
      s.correction = step * s.correction;
      s.sac = DecimatedSacView(*s.input, s.sac.view.cam_from_world * step.Inverse());
      step_deg[k] = w.norm() * 180.0 / M_PI;
      step_m[k] = t.norm();
    }
    tbb::parallel_for(size_t{0}, nviews, [&](size_t k) { UpdatePivot(&states[k]); });
    summary.median_step_deg = UpperMedianInPlace(&step_deg);
    summary.median_step_m = UpperMedianInPlace(&step_m);
    result.iterations.push_back(summary);
  }
  for (size_t k = 0; k < nviews; ++k) {
    const ViewState& s = states[k];
    ViewCorrection& v = result.views[k];
    v.cam_from_world = s.sac.view.cam_from_world * local_from_world;
    v.rotation_deg = Eigen::AngleAxisd(s.correction.rotation).angle() * 180.0 / M_PI;
    v.shift_m = s.correction * pivot0[k] - pivot0[k];
  }
  std::vector<double> rot, shift, before, after;
  for (const ViewCorrection& v : result.views) {
    rot.push_back(v.rotation_deg);
    shift.push_back(v.shift_m.norm());
    before.push_back(v.rms_before_m);
    after.push_back(v.rms_after_m);
  }
  CoregistrationSummary& sum = result.summary;
  sum.median_rotation_deg = UpperMedianInPlace(&rot);
  sum.max_rotation_deg = *std::max_element(rot.begin(), rot.end());
  sum.median_shift_m = UpperMedianInPlace(&shift);
  sum.max_shift_m = *std::max_element(shift.begin(), shift.end());
  sum.median_rms_before_m = UpperMedianInPlace(&before);
  sum.median_rms_after_m = UpperMedianInPlace(&after);
  return result;
}

}  // namespace sacfuse
