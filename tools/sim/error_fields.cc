#include "tools/sim/error_fields.h"

#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <tbb/parallel_for.h>

#include "tools/sim/sim_random.h"

namespace sacfuse::sim {

std::vector<float> CorrelatedGaussianField(int width, int height, double sigma_px, uint64_t key) {
  std::vector<float> field(static_cast<size_t>(width) * height);
  tbb::parallel_for(0, height, [&](int row) {
    for (int col = 0; col < width; ++col) {
      const size_t i = static_cast<size_t>(row) * width + col;
      field[i] = static_cast<float>(HashToNormal(HashCombine(key, i)));
    }
  });
  if (sigma_px < 0.3 || width < 2 || height < 2) return field;
  const int ksize = 2 * static_cast<int>(std::ceil(3.0 * sigma_px)) + 1;
  const cv::Mat kernel = cv::getGaussianKernel(ksize, sigma_px, CV_64F);
  const double norm_1d = std::sqrt(kernel.dot(kernel));
  cv::Mat mat(height, width, CV_32F, field.data());
  cv::Mat blurred;
  cv::sepFilter2D(mat, blurred, CV_32F, kernel, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT_101);
  blurred.convertTo(mat, CV_32F, 1.0 / (norm_1d * norm_1d));
  return field;
}

std::vector<CosineMode> DrawCosineModes(uint64_t key, int count, double max_cycles) {
  Rng rng(key);
  std::vector<CosineMode> modes(count);
  double total = 0.0;
  for (CosineMode& m : modes) {
    m.fu = rng.Uniform(-max_cycles, max_cycles);
    m.fv = rng.Uniform(-max_cycles, max_cycles);
    m.phase = rng.Uniform(0.0, 2.0 * M_PI);
    m.weight = rng.Uniform(0.3, 1.0);
    total += m.weight;
  }
  for (CosineMode& m : modes) m.weight /= total;
  return modes;
}

double EvalCosineModes(const std::vector<CosineMode>& modes, double u, double v) {
  double b = 0.0;
  for (const CosineMode& m : modes) b += m.weight * std::cos(2.0 * M_PI * (m.fu * u + m.fv * v) + m.phase);
  return b;
}

double InverseNormalCdf(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  if (p <= 0.0) return -1e300;
  if (p >= 1.0) return 1e300;
  const double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  if (p > 1.0 - low) {
    const double q = std::sqrt(-2.0 * std::log(1.0 - p));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

}  // namespace sacfuse::sim
