// Analytic reference RDFs drawn beside measured ones (scrm-bimodal-packs.txt §4):
//  - well-stirred, eq. (10): g(r) = H(r - 2a);
//  - Willis, eq. (11)-(12): g(r) = H(r - 2a) [1 + g_c(c) g_r(r)], g_r(r) = cos(pi r / a) exp(2 (2 - r/a)),
//    with the contact part g_c(c) = g_PY(2a+, c) - 1 of eq. (13) (Kanaun's choice, the one the
//    paper calls "the Willis approximation"), or Willis's original 0.8006 (8c - 1)/c of eq. (12_1)
//    as printed in the seed (valid for c > 1/8);
//  - Percus–Yevick contact values: one size, eq. (13): g(2a+) = (1 + c/2) / (1 - c)^2; mixtures,
//    eqs. (21)-(22) (Lebowitz 1964): g_ij(sigma_ij) = 1/(1 - xi3) + (3/2) (d_i d_j / sigma_ij)
//    xi2 / (1 - xi3)^2, sigma_ij = (d_i + d_j)/2, xi_l = (pi/6) sum_k n_k d_k^l; eq. (23) is its dilute limit of one
//    class;
//  - partial Willis-type curves, eqs. (19)-(20), in the scaled R_ij = (r - a_i)/a_j + 1;
//  - the full Percus–Yevick g(r) of hard spheres (Wertheim 1963, Thiele 1963): Wertheim's direct
//    correlation function c(r) inside the core, the Ornstein–Zernike relation in Fourier space
//    for the indirect part gamma = h - c (continuous, so its transform converges fast) and one
//    numerical sine transform back: g = 1 + gamma + c, 0 inside the core.
#pragma once

#include <vector>

namespace packlab::analyze::reference {

double well_stirred(double r, double a);
// Willis's g_r(r) of eq. (12_2): 1 at r = 2a.
double willis_shape(double r_over_a);
double willis_contact_original(double c);  // eq. (12_1), g_c = g(2a+) - 1
double percus_yevick_contact(double c);    // eq. (13) + 1: g(2a+)
// Eq. (11) with g_c = percus_yevick_contact(c) - 1 (use_original = false) or eq. (12_1).
double willis(double r, double a, double c, bool use_original = false);
// Contact values g_ij(a_i + a_j) of a mixture: radii a_k and volume fractions c_k per class.
std::vector<std::vector<double>> percus_yevick_contact_mixture(const std::vector<double>& radius,
                                                               const std::vector<double>& volume_fraction);
// Eq. (23): g_12 at contact when class 2 (radius ratio lambda = a2/a1) is infinitely dilute in
// class 1 at volume fraction c.
double percus_yevick_contact_dilute(double c, double lambda);
// Eq. (20) with the contact value g_ij(sigma) of the pair: H(R - 2)[1 + (g_ij - 1) g_r(R)].
double willis_partial(double scaled_r, double contact_value);

// The Percus–Yevick total correlation h(R) = g(R) - 1 at R = r / a (contact at R = 2) of hard
// spheres of radius a at volume fraction c, computed as gamma + c for every R: inside the core
// (R < 2) the exact solution has h = -1, which the numbers reproduce to ~1e-6 (the test of the
// transform). One call evaluates many R at once (one transform grid per c).
std::vector<double> percus_yevick_total_correlation(const std::vector<double>& r_over_a, double c);
// g(R): 0 for R < 2, 1 + h above; g(2+) = (1 + c/2) / (1 - c)^2 (eq. 13).
std::vector<double> percus_yevick(const std::vector<double>& r_over_a, double c);

}  // namespace packlab::analyze::reference
