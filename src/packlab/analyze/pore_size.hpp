// Pore-size distribution by the exclusion probability (Torquato, Lu & Rubinstein 1990, as
// used in doh-elastic-properties §2.3) and the degree of heterogeneity from its fit (eq. 6).
//
// Test points are drawn uniformly in the box; for each, the distance to the nearest particle
// surface delta(x) = max(0, min_i |x - c_i| - r_i) over every particle and periodic image.
// That is the distance to the union of the spheres, so overlapping (soft-sphere) packings
// need no special treatment and nothing assumes hard spheres. Along open axes points closer
// than `wall_margin` to a wall are not drawn (the space beyond a wall is unknown, not empty).
//
// Definitions (PoreDefinition):
//   pore_space  P(r_P > r) = fraction of the points outside every particle whose distance
//               exceeds r: Torquato's cumulative pore-size distribution F(r), F(0) = 1.
//               This is the default and what eq. 6 is fitted to.
//   all_points  the same fraction over all points (those inside a particle count as 0):
//               the exclusion probability E_V(r0 + r); at r = 0 it is the porosity.
//
// Sample size and confidence: the points are independent, so the empirical P is a binomial
// fraction at every r (std_error = sqrt(P(1-P)/n)) and, uniformly in r, lies within
// eps = sqrt(ln(2/alpha) / (2 n)) of the exact P with probability 1 - alpha
// (Dvoretzky-Kiefer-Wolfowitz-Massart). Without an explicit `points`, n is chosen so that
// eps equals `band` (default 0.005 at 95 %: n = 73,778 pore points).
//
// Random numbers: the seed is drawn once from the packlab::Random passed to compute(); point
// k gets its own stream (SplitMix64 of seed and k), so results do not depend on the number
// of threads. Several packings (realizations) accumulate; their points are pooled with equal
// numbers of points per packing, which averages their distributions.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "packlab/analyze/fits.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/core/random.hpp"

namespace packlab::analyze {

enum class PoreDefinition { pore_space, all_points };
PoreDefinition pore_definition_from_name(const std::string& name);  // "pore_space" | "all_points"
std::string pore_definition_name(PoreDefinition definition);

struct PoreSizeParams {
  long points = 0;           // counted points per packing (pore points for pore_space); 0 = from band
  double band = 0.005;       // target half-width of the uniform confidence band on P
  double confidence = 0.95;  // of that band
  PoreDefinition definition = PoreDefinition::pore_space;
  double wall_margin = -1.0;  // [m] along open axes; < 0 = one mean particle diameter
  int threads = 0;            // OpenMP threads; 0 = all
};

// Counted points needed for a uniform band of half-width `band` at `confidence` (DKW).
long points_for_band(double band, double confidence);
// Half-width of the uniform band for n counted points.
double band_for_points(long n, double confidence);

// Distance from a point to the nearest particle surface (0 inside any particle), with
// periodic images; linked cells searched in growing shells until no unvisited cell can hold
// a closer surface. Built once per packing; the query is thread-safe.
class SurfaceDistance {
 public:
  explicit SurfaceDistance(const Packing& packing);
  double operator()(const Vec3& point) const;

 private:
  std::array<bool, 3> periodic_{};
  Vec3 lo_, length_, cell_size_;
  std::array<int, 3> cells_{1, 1, 1};
  double r_max_ = 0.0, h_min_ = 0.0;
  std::vector<int> cell_start_;
  std::vector<double> x_, y_, z_, r_;  // particles sorted by cell
};

class PoreSize {
 public:
  explicit PoreSize(PoreSizeParams params = {});

  void compute(const Packing& packing, Random& rng, bool reset = true);

  struct Curve {
    std::vector<double> r;                    // [m]
    std::vector<double> probability;          // P(r_P > r)
    std::vector<double> std_error;            // binomial, pointwise
    std::vector<double> band_low, band_high;  // uniform band at params.confidence, clipped to [0, 1]
  };
  // On `points` equally spaced r from 0 to the largest distance; frame -1 = all pooled.
  Curve curve(int points = 201, int frame = -1) const;
  // P(r_P > r) of the pooled points (or of one frame).
  double probability(double r, int frame = -1) const;
  // Sorted counted distances [m] (pore points only for pore_space).
  const std::vector<double>& distances(int frame = -1) const;

  int frames() const;
  long counted_points(int frame = -1) const;  // n of the estimate
  long drawn_points(int frame = -1) const;    // all points drawn (inside particles too)
  // Fraction of drawn points outside every particle (the overlap-aware porosity).
  double porosity(int frame = -1) const;
  double porosity_std_error(int frame = -1) const;
  double band(int frame = -1) const;         // uniform band half-width for counted_points
  double mean_radius(int frame = -1) const;  // number mean of the radii [m]
  long target_points() const { return target_; }
  const PoreSizeParams& params() const { return params_; }

 private:
  void require_computed() const;
  PoreSizeParams params_;
  long target_;
  struct Frame {
    std::vector<double> distances;  // sorted
    long drawn = 0, outside = 0;
    double mean_radius = 0.0;
  };
  std::vector<Frame> frames_;
  Frame pooled_;
};

// Fit of eq. 6, P(r_P > r) = 1 - erf((r/r0 - b)/(a sqrt 2)), to the pore_space distribution.
struct DohFitOptions {
  double r0 = 0.0;     // [m] length unit of eq. 6; 0 = mean particle radius
  double x_min = 0.0;  // fit range in r/r0
  double x_max = 0.0;  // 0 = where P falls to p_min
  double p_min = 1e-3;
  int grid = 100;  // equally spaced points in [x_min, x_max] at which P is fitted
};

// a_err, b_err: standard errors from the finite number of test points (sandwich covariance
// with the binomial covariance of the empirical distribution); a_ls_err, b_ls_err: the
// textbook least-squares errors, which treat the correlated grid values as independent and
// mostly measure how far eq. 6 is from the data's shape.
struct DohFit {
  ErfFit fit;       // a, b (in units of r0), standard errors, R^2, points
  double r0 = 0.0;  // [m]
  double x_min = 0.0, x_max = 0.0;
};

DohFit fit_degree_of_heterogeneity(const PoreSize& pores, const DohFitOptions& options = {}, int frame = -1);

}  // namespace packlab::analyze
