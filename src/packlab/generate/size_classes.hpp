// Size classes of a polydisperse packing, shared by the generators (LS, SCRM, FBA, opal).
#pragma once

#include <vector>

namespace packlab::generate {

// Size classes of a polydisperse packing: relative diameters and their number or volume
// fractions. One class by default.
struct SizeClasses {
  std::vector<double> sizes{1.0};  // relative diameters (any common scale)
  std::vector<double> fractions;   // one per class; empty = equal numbers
  bool volume_fractions = false;   // fractions are volume fractions (else number fractions)

  void validate() const;  // InputError naming the key
  // Number fraction of each class.
  std::vector<double> number_fractions() const;
  // Particles per class for n in total (largest-remainder rounding, sums to n).
  std::vector<long> counts(long n) const;

  // From the front ends' options: number or volume fractions (at most one given), validated.
  static SizeClasses from_options(const std::vector<double>& sizes, const std::vector<double>& number_fractions,
                                  const std::vector<double>& volume_fractions);
};

}  // namespace packlab::generate
