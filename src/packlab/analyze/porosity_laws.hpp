// Porosity laws of porous ceramics (bpm-inverse-opals §4):
//   exponential   E(eps) = E0 exp(-b eps)      (eq. 22; eq. 24 with b = 2.99, eq. 26 for strength)
//   Wagh et al.   E(eps) = E0 (1 - eps)^m      (eq. 23; eq. 25 with m = 1.92)
// fitted by unweighted least squares on the linear scale (Levenberg-Marquardt, analyze/fits),
// started from the straight-line fit of log E. E0 is either fitted or held at a given value
// (the paper holds it at the pore-free modulus, 22.06 GPa, in eq. 24 and 25).
#pragma once

#include <string>
#include <vector>

namespace packlab::analyze {

enum class PorosityLaw { exponential, power };

PorosityLaw porosity_law_from_name(const std::string& name);  // "exponential" | "power"
std::string porosity_law_name(PorosityLaw law);

struct PorosityFit {
  PorosityLaw law = PorosityLaw::power;
  double e0 = 0.0, e0_err = 0.0;          // zero-porosity value (err 0 when held fixed)
  double exponent = 0.0, exponent_err = 0.0;  // b (exponential) or m (power)
  double rss = 0.0;                       // residual sum of squares
  double rms_relative = 0.0;              // sqrt(mean((y - fit)^2 / y^2))
  double r2 = 0.0;
  long points = 0;
  bool converged = false;
  double model(double porosity) const;
};

// InputError when sizes differ, fewer than 2 points (3 with E0 free), porosity outside [0, 1)
// or a value not positive. fixed_e0 > 0 holds E0.
PorosityFit fit_porosity_law(PorosityLaw law, const std::vector<double>& porosity, const std::vector<double>& value,
                             double fixed_e0 = 0.0);

}  // namespace packlab::analyze
