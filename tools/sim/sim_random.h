#pragma once
// Seeded random numbers for the simulator. Two kinds:
//  - counter-based hashes: a value is a pure function of its key (seed, stream, view, pixel...), so results do
//    not depend on thread scheduling or on the order in which views are generated;
//  - Rng: a small sequential generator (SplitMix64) for scene layout and per-view parameters. Our own
//    distributions (not <random>'s) keep outputs identical across standard libraries.
#include <cmath>
#include <cstdint>

namespace sacfuse::sim {

inline uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline uint64_t HashCombine(uint64_t a, uint64_t b) { return SplitMix64(a ^ (SplitMix64(b) + 0x632be59bd9b4e019ULL)); }
inline uint64_t Hash3(uint64_t a, uint64_t b, uint64_t c) { return HashCombine(HashCombine(a, b), c); }
inline uint64_t Hash4(uint64_t a, uint64_t b, uint64_t c, uint64_t d) { return HashCombine(Hash3(a, b, c), d); }

// Uniform in [0, 1) from 53 bits of a hash.
inline double HashToUnit(uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// Standard normal from a key (Box-Muller on two derived uniforms).
inline double HashToNormal(uint64_t key) {
  const double u1 = 1.0 - HashToUnit(SplitMix64(key));  // (0, 1]
  const double u2 = HashToUnit(SplitMix64(key ^ 0xa5a5a5a5a5a5a5a5ULL));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(SplitMix64(seed)) {}
  uint64_t Next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return SplitMix64(state_);
  }
  double Uniform() { return HashToUnit(Next()); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  int UniformInt(int lo, int hi_inclusive) {
    return lo + static_cast<int>(Uniform() * (hi_inclusive - lo + 1));
  }
  bool Bernoulli(double p) { return Uniform() < p; }
  double Normal() { return HashToNormal(Next()); }
  double Normal(double mean, double sigma) { return mean + sigma * Normal(); }
  // Poisson: Knuth's product method for small means, rounded normal approximation beyond 50.
  int Poisson(double mean) {
    if (mean <= 0.0) return 0;
    if (mean > 50.0) {
      const double v = std::round(Normal(mean, std::sqrt(mean)));
      return v < 0.0 ? 0 : static_cast<int>(v);
    }
    const double limit = std::exp(-mean);
    double p = 1.0;
    int k = 0;
    do {
      ++k;
      p *= Uniform();
    } while (p > limit);
    return k - 1;
  }

 private:
  uint64_t state_;
};

// Stream ids: one independent random stream per purpose.
enum class Stream : uint64_t {
  kLayout = 1,
  kTexture = 2,
  kPose = 3,
  kStereoNoise = 4,
  kBias = 5,
  kBlunder = 6,
  kDropout = 7,
  kSparse = 8,
  kReference = 9,
  kKeypoint = 10,
};

inline uint64_t StreamKey(uint64_t seed, Stream stream, uint64_t item = 0) {
  return Hash3(seed, static_cast<uint64_t>(stream), item);
}

}  // namespace sacfuse::sim
