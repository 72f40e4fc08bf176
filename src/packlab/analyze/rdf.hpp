// Radial distribution functions of sphere centres (scrm-bimodal-packs.txt §2, §4):
//  - the second-order intensity (Ripley's K) function, eq. (2), with the toroidal edge
//    correction in periodic boxes (every periodic image counts), and Ripley's isotropic weights
//    (the fraction of the sphere of radius r_ij around x_i inside the box) or minus-sampling
//    (only centres farther than r_max from every open face) along open axes;
//  - g(r) from K by the central difference, eq. (14_1): g(r_n) = [K(r_n + dr/2) - K(r_n - dr/2)]
//    / (4 pi r_n^2 dr) on bins centred at r_n = n dr;
//  - partial K_km and g_km, eqs. (5)-(6), for every pair of size classes (particles with equal
//    radii form a class, largest first), reported against r and the scaled R_km = (r - a_k)/a_m + 1;
//  - the contact value g_km(sigma+) by the right difference, eq. (14_2), over [sigma, sigma + dr)
//    with sigma = a_k + a_m;
//  - the shell count I(r) of eq. (18): the mean number of centres in the bin around a centre;
//  - window histograms p(n_h): the fraction of windows |x - x_i| < R_h a_k (centred on each
//    particle i of class k) holding n_h other centres.
// Distances are binned in units of the reference radius a (the largest class radius of each
// realization), so realizations at slightly different radii average peak on peak. Several
// realizations are averaged with accumulate()/add(). Like freud: parameters in the
// constructor, compute() fills the results, reading before computing is an error.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::analyze {

enum class EdgeCorrection { automatic, toroidal, ripley, minus_sampling };
EdgeCorrection edge_correction_from_name(const std::string& name);  // InputError for unknown names
std::string edge_correction_name(EdgeCorrection e);

struct RdfParams {
  double dr = 0.01;             // bin width, in units of the reference radius a
  double r_max = 8.0;           // largest distance, in units of a
  double window_radius = 2.5;   // histogram window radius R_h, in units of the centre's radius
  EdgeCorrection edge = EdgeCorrection::automatic;  // automatic: toroidal when every axis is
                                                    // periodic, else Ripley's weights
  int threads = 0;              // OpenMP threads; 0 = all
  void validate() const;
};

class Rdf {
 public:
  explicit Rdf(const RdfParams& params = {});

  void compute(const Packing& packing);     // forgets earlier realizations
  void accumulate(const Packing& packing);  // adds one realization to the average
  void add(const Rdf& other);               // merges another accumulation (same params, classes)
  void reset();

  const RdfParams& params() const { return params_; }
  int realizations() const;
  int classes() const;
  // Per class: radius a_k (of the first realization) and mean number of particles.
  const std::vector<double>& class_radius() const;
  double reference_radius() const;  // a = class_radius()[0]
  std::size_t bins() const;
  // Bin centres R_n = n dr (n = 1..bins) in units of a.
  std::vector<double> reduced_r() const;
  // Total (all pairs): K(R_n + dr/2) / a^3, g(R_n), I(R_n).
  std::vector<double> k_function() const { return k_function(-1, -1); }
  std::vector<double> g() const { return g(-1, -1); }
  std::vector<double> shell_count() const { return shell_count(-1, -1); }
  // Partial, class k around class m (k, m in [0, classes)); -1, -1 = all pairs.
  std::vector<double> k_function(int k, int m) const;
  std::vector<double> g(int k, int m) const;
  std::vector<double> shell_count(int k, int m) const;
  // g_km(sigma+) with sigma = a_k + a_m, right difference over one bin.
  double contact_value(int k, int m) const;
  // Positions (R, in units of a) of local maxima of g_km beyond contact, first first: maxima of
  // g smoothed over +-2 bins that are the largest within +-0.15 a and above 1.
  std::vector<double> peaks(int k, int m, std::size_t count = 4) const;
  // Window histogram: p[n] = fraction of windows around class-k centres (k = -1: all) with n others.
  std::vector<double> window_histogram(int k = -1) const;
  long windows(int k = -1) const;

 private:
  void require_computed() const;
  std::size_t pair_index(int k, int m) const;  // ordered pairs; index classes*classes = total
  RdfParams params_;
  int realizations_ = 0;
  std::vector<double> class_radius_;
  std::vector<double> mean_count_;
  std::size_t bins_ = 0;
  // Sums over realizations of normalised increments (see rdf.cpp).
  std::vector<std::vector<double>> dk_;       // per ordered pair + total: dK per bin / a^3
  std::vector<std::vector<double>> di_;       // per ordered pair + total: counts per centre
  std::vector<double> contact_dk_;            // per ordered pair + total
  std::vector<std::vector<long>> window_hist_;  // per class + total
};

// Fraction of the surface of the sphere of radius r centred at p that lies in the box, counting
// only open axes (periodic axes never cut): Ripley's isotropic weight is 1 / this fraction.
// Exact for 0 or only whole-face cuts through the centre; otherwise a graded Gauss-Legendre
// quadrature over z accurate to about 1e-7.
double sphere_fraction_in_box(const Box& box, const Vec3& p, double r);

}  // namespace packlab::analyze
