// The links of a bonded model linearized, and their stiffness assembled into a sparse symmetric
// matrix (see static_stiffness.hpp for the kinematics).
#include "packlab/mechanics/static_stiffness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "packlab/core/error.hpp"
#include "packlab/core/memory.hpp"

namespace packlab::mechanics {

namespace {

template <class Law>
concept HasPairTangent = requires(const dem::ContactGeometry& g, const typename Law::Params& p) {
  { Law::tangent(g, p) } -> std::same_as<dem::PairTangent>;
};
template <class Law>
concept HasBondTangent = requires(const dem::ContactGeometry& g, const typename Law::Params& p,
                                  const dem::BondLoad& l) {
  { Law::tangent(g, p) } -> std::same_as<dem::BondTangent>;
  { Law::failure_ratio(l, g, p) } -> std::same_as<double>;
};

// The geometry the laws read for a pair at rest whose j image sits at x_i + d.
dem::ContactGeometry rest_geometry(const Vec3& d, double radius_i, double radius_j) {
  dem::ContactGeometry g{};
  const double distance = norm(d);
  g.normal = d * (1.0 / distance);
  g.overlap = radius_i + radius_j - distance;
  g.branch_i = radius_i - 0.5 * g.overlap;
  g.branch_j = radius_j - 0.5 * g.overlap;
  g.radius_i = radius_i;
  g.radius_j = radius_j;
  return g;
}

void add_link(StaticLinks& links, int i, int j, const Vec3& d, const dem::ContactGeometry& g, const dem::BondTangent& k,
              int bond) {
  links.i.push_back(i);
  links.j.push_back(j);
  links.branch.push_back(d);
  links.branch_i.push_back(g.branch_i);
  links.branch_j.push_back(g.branch_j);
  links.stiffness.push_back(k);
  links.bond.push_back(bond);
  links.geometry.push_back(g);
}

// n x v as a matrix: N v = n x v.
std::array<double, 9> cross_matrix(const Vec3& n) { return {0.0, -n.z, n.y, n.z, 0.0, -n.x, -n.y, n.x, 0.0}; }

}  // namespace

std::size_t StaticLinks::bonds() const {
  return static_cast<std::size_t>(std::count_if(bond.begin(), bond.end(), [](int b) { return b >= 0; }));
}

StaticLinks linearize_links(const Packing& packing, const dem::EngineConfig& config, bool prestress) {
  // The engine validates the packing and the configuration and finds the touching pairs.
  const dem::Engine engine(packing, config);
  const dem::ContactForces touching = engine.contact_forces();
  StaticLinks links;
  const auto type_count = static_cast<int>(std::max<std::size_t>(1, config.types.size()));
  auto material = [&](int type) -> const dem::Material& {
    return config.types.size() == 1 ? config.types[0] : config.types[static_cast<std::size_t>(type)];
  };
  (void)type_count;
  // The engine's intact bonds in its list come in the packing's bond order, as the links do.
  std::vector<std::size_t> bond_entry;
  if (prestress)
    for (std::size_t c = 0; c < touching.size(); ++c)
      if (touching.kind[c] == dem::ContactForces::bond) bond_entry.push_back(c);
  // The tension of the engine's force on j along the link: N = -F . n.
  auto tension = [&](std::size_t c, const dem::ContactGeometry& g) { return -dot(touching.force[c], g.normal); };

  // Bonds (packing order), then the touching unbonded pairs.
  const Bonds& bonds = packing.bonds;
  dem::BondLaws::for_each([&](auto law) {
    using Law = typename decltype(law)::type;
    const auto* list = std::get_if<dem::BondMaterialList<Law>>(&config.bond_materials);
    if (!list) return;
    bool intact = false;
    for (int s : bonds.state) intact = intact || s == 0;
    if (!intact) return;
    if constexpr (!HasBondTangent<Law>) {
      fail_input(fmt::format("bond_law = {}: the static solver has no linearization of this bond law", Law::name));
    } else {
      for (std::size_t b = 0; b < bonds.size(); ++b) {
        if (bonds.state[b] != 0) continue;
        const auto i = static_cast<std::size_t>(bonds.i[b]), j = static_cast<std::size_t>(bonds.j[b]);
        const Vec3 d = packing.position[j] + packing.box.shift_vector(bonds.image[b]) - packing.position[i];
        if (!(norm(d) > 0.0))
          fail_input(fmt::format("bond {} joins particle {} to itself at zero distance: it has no direction", b, i));
        dem::ContactGeometry g = rest_geometry(d, packing.radius[i], packing.radius[j]);
        g.rest_length = bonds.rest_length[b];
        const auto& params = list->size() == 1 ? (*list)[0] : (*list)[static_cast<std::size_t>(bonds.material[b])];
        add_link(links, bonds.i[b], bonds.j[b], d, g, Law::tangent(g, params), static_cast<int>(b));
        if (prestress) {
          const std::size_t m = links.size() - 1;
          if (m >= bond_entry.size() || touching.i[bond_entry[m]] != bonds.i[b] ||
              touching.j[bond_entry[m]] != bonds.j[b])
            throw std::logic_error("linearize_links: the engine's bond forces are not in the packing's bond order");
          links.prestress.push_back(tension(bond_entry[m], g));
        }
      }
    }
  });

  if (touching.size() > 0) {
    const bool found = dem::ContactLaws::with_law(config.contact_law, [&](auto law) {
      using Law = typename decltype(law)::type;
      if constexpr (!HasPairTangent<Law>) {
        bool any = false;
        for (std::size_t c = 0; c < touching.size(); ++c) any = any || touching.kind[c] == dem::ContactForces::contact;
        if (any)
          fail_input(
              fmt::format("contact_law = {}: the static solver has no linearization of this contact law (the "
                          "model has touching unbonded pairs)",
                          Law::name));
      } else {
        for (std::size_t c = 0; c < touching.size(); ++c) {
          if (touching.kind[c] != dem::ContactForces::contact) continue;
          const auto i = static_cast<std::size_t>(touching.i[c]), j = static_cast<std::size_t>(touching.j[c]);
          const dem::ContactGeometry g = rest_geometry(touching.branch[c], packing.radius[i], packing.radius[j]);
          if (!(g.overlap > 0.0)) continue;  // laws with reach: only touching pairs are linearized
          const auto params = Law::mix(material(packing.type[i]), material(packing.type[j]), config.stiffness_rule);
          const dem::PairTangent t = Law::tangent(g, params);
          add_link(links, touching.i[c], touching.j[c], touching.branch[c], g, {t.normal, t.shear, 0.0, 0.0}, -1);
          if (prestress) links.prestress.push_back(tension(c, g));
        }
      }
    });
    if (!found) fail_input(fmt::format("contact_law = {}: unknown", config.contact_law));
  }
  return links;
}

std::array<std::array<double, 36>, 4> link_stiffness(const StaticLinks& links, std::size_t k) {
  const Vec3 n = links.branch[k] * (1.0 / norm(links.branch[k]));
  const dem::BondTangent& s = links.stiffness[k];
  const double nn[3] = {n.x, n.y, n.z};
  // D = k_n nn + k_s (1 - nn), D_theta = k_tor nn + k_bend (1 - nn).
  double D[9], Dt[9];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double p = nn[a] * nn[b], id = a == b ? 1.0 : 0.0;
      D[3 * a + b] = s.normal * p + s.shear * (id - p);
      Dt[3 * a + b] = s.torsion * p + s.bending * (id - p);
    }
  // B_i = [-1, b_i N], B_j = [1, b_j N] (3 x 6); R_i = [0, -1], R_j = [0, 1].
  const auto N = cross_matrix(n);
  double B[2][18];
  const double sign[2] = {-1.0, 1.0};
  const double arm[2] = {links.branch_i[k], links.branch_j[k]};
  for (int e = 0; e < 2; ++e)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 6; ++c)
        B[e][6 * a + c] = c < 3 ? (a == c ? sign[e] : 0.0) : arm[e] * N[static_cast<std::size_t>(3 * a + (c - 3))];
  std::array<std::array<double, 36>, 4> out{};
  for (int ea = 0; ea < 2; ++ea)
    for (int eb = 0; eb < 2; ++eb) {
      auto& K = out[static_cast<std::size_t>(2 * ea + eb)];
      // B_a^T D B_b. The rotation columns of B (b N) are normal to n, so D maps them to
      // k_s b N exactly: written so, not summed, because the sum leaves rounding of k_n b^2
      // eps where k_s is zero (a frictionless contact), rotation entries of ~1e-12 of the
      // others that the diagonal shift (assemble()) took for real ones; an N = 8000 BD gel
      // with a particle touched only by such contacts failed as not positive definite.
      double DB[18];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 6; ++c) {
          double v = 0.0;
          if (c < 3)
            for (int m = 0; m < 3; ++m) v += D[3 * a + m] * B[eb][6 * m + c];
          else
            v = s.shear * B[eb][6 * a + c];
          DB[6 * a + c] = v;
        }
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) {
          double v = 0.0;
          if (r < 3) {
            for (int m = 0; m < 3; ++m) v += B[ea][6 * m + r] * DB[6 * m + c];
          } else {  // the rotation rows: (b N)^T D = k_s (b N)^T likewise
            for (int m = 0; m < 3; ++m) v += B[ea][6 * m + r] * B[eb][6 * m + c];
            v *= s.shear;
          }
          K[static_cast<std::size_t>(6 * r + c)] = v;
        }
      // R_a^T D_theta R_b on the rotation block.
      const double rs = sign[ea] * sign[eb];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) K[static_cast<std::size_t>(6 * (r + 3) + c + 3)] += rs * Dt[3 * r + c];
    }
  // The pre-stress's geometric stiffness (static_stiffness.hpp): (N / L) [P -P; -P P] on the
  // translations, P = 1 - nn; symmetric like the rest.
  if (!links.prestress.empty() && links.prestress[k] != 0.0) {
    const double g = links.prestress[k] / norm(links.branch[k]);
    for (int ea = 0; ea < 2; ++ea)
      for (int eb = 0; eb < 2; ++eb) {
        auto& K = out[static_cast<std::size_t>(2 * ea + eb)];
        const double gs = sign[ea] * sign[eb] * g;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            K[static_cast<std::size_t>(6 * r + c)] += gs * ((r == c ? 1.0 : 0.0) - nn[r] * nn[c]);
      }
  }
  return out;
}

LinkResponse link_response(const StaticLinks& links, std::size_t k, std::span<const double> q,
                           const DisplacementGradient& gradient) {
  const auto i = static_cast<std::size_t>(links.i[k]), j = static_cast<std::size_t>(links.j[k]);
  const Vec3& d = links.branch[k];
  const Vec3 n = d * (1.0 / norm(d));
  const Vec3 ui{q[6 * i], q[6 * i + 1], q[6 * i + 2]}, ti{q[6 * i + 3], q[6 * i + 4], q[6 * i + 5]};
  const Vec3 uj{q[6 * j], q[6 * j + 1], q[6 * j + 2]}, tj{q[6 * j + 3], q[6 * j + 4], q[6 * j + 5]};
  const Vec3 affine{gradient[0][0] * d.x + gradient[0][1] * d.y + gradient[0][2] * d.z,
                    gradient[1][0] * d.x + gradient[1][1] * d.y + gradient[1][2] * d.z,
                    gradient[2][0] * d.x + gradient[2][1] * d.y + gradient[2][2] * d.z};
  const Vec3 du = uj - ui + links.branch_i[k] * cross(n, ti) + links.branch_j[k] * cross(n, tj) + affine;
  const Vec3 dtheta = tj - ti;
  const dem::BondTangent& s = links.stiffness[k];
  LinkResponse out;
  out.normal_displacement = dot(du, n);
  const Vec3 du_t = du - out.normal_displacement * n;
  const double theta_n = dot(dtheta, n);
  const Vec3 theta_t = dtheta - theta_n * n;
  out.force_on_j = -(s.normal * out.normal_displacement) * n - s.shear * du_t;
  out.moment_on_j = -(s.torsion * theta_n) * n - s.bending * theta_t;
  out.load.normal_force = s.normal * out.normal_displacement;
  out.load.shear_force = s.shear * norm(du_t);
  out.load.torsion = std::abs(s.torsion * theta_n);
  out.load.bending = s.bending * norm(theta_t);
  out.energy = 0.5 * (s.normal * out.normal_displacement * out.normal_displacement + s.shear * norm2(du_t) +
                      s.torsion * theta_n * theta_n + s.bending * norm2(theta_t));
  if (!links.prestress.empty() && links.prestress[k] != 0.0) {
    // The pre-force turning with the line of centres: the centres' relative displacement only.
    const Vec3 dx = uj - ui + affine;
    const Vec3 dx_t = dx - dot(dx, n) * n;
    const double g = links.prestress[k] / norm(d);
    out.geometric_force_on_j = -g * dx_t;
    out.force_on_j += out.geometric_force_on_j;
    out.energy += 0.5 * g * norm2(dx_t);
  }
  return out;
}

dem::ContactForces link_forces(const StaticLinks& links, std::span<const double> q,
                               const DisplacementGradient& gradient, std::span<const std::uint8_t> active) {
  dem::ContactForces out;
  for (std::size_t k = 0; k < links.size(); ++k) {
    if (!active.empty() && !active[k]) continue;
    out.i.push_back(links.i[k]);
    out.j.push_back(links.j[k]);
    out.kind.push_back(links.bond[k] >= 0 ? dem::ContactForces::bond : dem::ContactForces::contact);
    out.branch.push_back(links.branch[k]);
    out.force.push_back(link_response(links, k, q, gradient).force_on_j);
  }
  return out;
}

StiffnessAssembly::StiffnessAssembly(const StaticLinks& links, std::span<const std::uint8_t> prescribed)
    : links_(links), free_index_(prescribed.size(), -1) {
  for (std::size_t p = 0; p < prescribed.size(); ++p)
    if (!prescribed[p]) free_index_[p] = static_cast<int>(free_particles_++);
  if (6 * free_particles_ > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    fail_input(
        fmt::format("static solver: {} free particles is more than the sparse matrix's index range", free_particles_));
  // Neighbours with a larger free index, per free particle.
  std::vector<std::vector<int>> larger(free_particles_);
  for (std::size_t k = 0; k < links.size(); ++k) {
    const int a = free_index_[static_cast<std::size_t>(links.i[k])],
              b = free_index_[static_cast<std::size_t>(links.j[k])];
    if (a < 0 || b < 0 || a == b) continue;
    larger[static_cast<std::size_t>(std::min(a, b))].push_back(std::max(a, b));
  }
  neighbor_start_.assign(free_particles_ + 1, 0);
  for (std::size_t p = 0; p < free_particles_; ++p) {
    auto& l = larger[p];
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    neighbor_start_[p + 1] = neighbor_start_[p] + static_cast<int>(l.size());
  }
  neighbor_.reserve(static_cast<std::size_t>(neighbor_start_.back()));
  for (const auto& l : larger) neighbor_.insert(neighbor_.end(), l.begin(), l.end());
  release_memory(larger);
  link_block_.assign(links.size(), -1);
  for (std::size_t k = 0; k < links.size(); ++k) {
    const int a = free_index_[static_cast<std::size_t>(links.i[k])],
              b = free_index_[static_cast<std::size_t>(links.j[k])];
    if (a < 0 || b < 0 || a == b) continue;
    const auto lo = static_cast<std::size_t>(std::min(a, b));
    const auto first = neighbor_.begin() + neighbor_start_[lo], last = neighbor_.begin() + neighbor_start_[lo + 1];
    link_block_[k] = static_cast<int>(std::lower_bound(first, last, std::max(a, b)) - first);
  }
  // Compressed columns: column 6p + c holds rows 6p + c .. 6p + 5 (the diagonal block's lower
  // part), then the six rows of each larger neighbour.
  const std::size_t columns = 6 * free_particles_;
  column_start_.assign(columns + 1, 0);
  for (std::size_t p = 0; p < free_particles_; ++p) {
    const int m = neighbor_start_[p + 1] - neighbor_start_[p];
    for (int c = 0; c < 6; ++c) column_start_[6 * p + c + 1] = column_start_[6 * p + c] + (6 - c) + 6 * m;
  }
  row_.resize(static_cast<std::size_t>(column_start_.back()));
  for (std::size_t p = 0; p < free_particles_; ++p)
    for (int c = 0; c < 6; ++c) {
      int at = column_start_[6 * p + c];
      for (int r = c; r < 6; ++r) row_[static_cast<std::size_t>(at++)] = static_cast<int>(6 * p) + r;
      for (int m = neighbor_start_[p]; m < neighbor_start_[p + 1]; ++m)
        for (int r = 0; r < 6; ++r)
          row_[static_cast<std::size_t>(at++)] = 6 * neighbor_[static_cast<std::size_t>(m)] + r;
    }
  values_.assign(row_.size(), 0.0);
}

std::size_t StiffnessAssembly::bytes() const {
  return column_start_.size() * sizeof(int) + row_.size() * (sizeof(int) + sizeof(double)) +
         (neighbor_start_.size() + neighbor_.size() + link_block_.size() + free_index_.size()) * sizeof(int);
}

void StiffnessAssembly::add_link(std::size_t k, double scale) {
  auto diagonal_add = [&](std::size_t p, const std::array<double, 36>& K) {
    for (int c = 0; c < 6; ++c)
      for (int r = c; r < 6; ++r)
        values_[static_cast<std::size_t>(column_start_[6 * p + static_cast<std::size_t>(c)] + (r - c))] +=
            scale * K[static_cast<std::size_t>(6 * r + c)];
  };
  const int a = free_index_[static_cast<std::size_t>(links_.i[k])],
            b = free_index_[static_cast<std::size_t>(links_.j[k])];
  if (a < 0 && b < 0) return;
  const auto K = link_stiffness(links_, k);  // ii, ij, ji, jj
  if (a >= 0 && a == b) {
    // A particle bonded to its own periodic image: the four blocks act on one particle.
    std::array<double, 36> sum{};
    for (std::size_t e = 0; e < 36; ++e) sum[e] = K[0][e] + K[1][e] + K[2][e] + K[3][e];
    diagonal_add(static_cast<std::size_t>(a), sum);
    return;
  }
  if (a >= 0) diagonal_add(static_cast<std::size_t>(a), K[0]);
  if (b >= 0) diagonal_add(static_cast<std::size_t>(b), K[3]);
  if (a >= 0 && b >= 0) {
    // The block below the diagonal: rows of the larger index, columns of the smaller.
    const bool i_first = a < b;
    const auto col = static_cast<std::size_t>(std::min(a, b));
    const auto& block = i_first ? K[2] : K[1];  // (rows j, cols i) = K_ji, or (rows i, cols j) = K_ij
    for (int c = 0; c < 6; ++c) {
      const int start = column_start_[6 * col + static_cast<std::size_t>(c)] + (6 - c) + 6 * link_block_[k];
      for (int r = 0; r < 6; ++r)
        values_[static_cast<std::size_t>(start + r)] += scale * block[static_cast<std::size_t>(6 * r + c)];
    }
  }
}

LinkStiffness StiffnessAssembly::free_link_stiffness(std::size_t k) const {
  LinkStiffness out;
  const int ends[2] = {free_index_[static_cast<std::size_t>(links_.i[k])],
                       free_index_[static_cast<std::size_t>(links_.j[k])]};
  if (ends[0] < 0 && ends[1] < 0) return out;
  const auto K = link_stiffness(links_, k);  // ii, ij, ji, jj
  // Local dof l (0..11) of the link -> its row in `out` (a particle bonded to its own image
  // has one set of six).
  int slot[12];
  for (int e = 0; e < 2; ++e) {
    if (ends[e] < 0) {
      for (int c = 0; c < 6; ++c) slot[6 * e + c] = -1;
      continue;
    }
    const bool same = e == 1 && ends[0] == ends[1];
    for (int c = 0; c < 6; ++c) {
      if (same) {
        slot[6 + c] = slot[c];
        continue;
      }
      slot[6 * e + c] = out.size;
      out.unknown[static_cast<std::size_t>(out.size++)] = 6 * ends[e] + c;
    }
  }
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 12; ++c) {
      if (slot[r] < 0 || slot[c] < 0) continue;
      const auto& block = K[static_cast<std::size_t>(2 * (r / 6) + c / 6)];
      out.matrix[static_cast<std::size_t>(12 * slot[r] + slot[c])] +=
          block[static_cast<std::size_t>(6 * (r % 6) + c % 6)];
    }
  return out;
}

void StiffnessAssembly::assemble(std::span<const std::uint8_t> active, double regularization) {
  std::fill(values_.begin(), values_.end(), 0.0);
  for (std::size_t k = 0; k < links_.size(); ++k)
    if (active.empty() || active[k]) add_link(k, 1.0);
  // Translations and rotations have different units (N/m against N m/rad, ~r^2 apart): the
  // shift is relative to each entry, and to the mean of its kind for an entry that is zero (a
  // particle without links).
  double sum[2] = {0.0, 0.0};
  for (std::size_t col = 0; col < unknowns(); ++col)
    sum[col % 6 < 3 ? 0 : 1] += values_[static_cast<std::size_t>(column_start_[col])];
  const double per_kind = unknowns() > 0 ? static_cast<double>(unknowns() / 2) : 1.0;
  // A kind with no stiffness at all (rotations in a network of frictionless contacts only):
  // its entries are zero, and so are their rows (K is positive semi-definite), so any shift
  // makes them positive definite without touching the solution.
  const double mean[2] = {sum[0] > 0.0 ? sum[0] / per_kind : 1.0, sum[1] > 0.0 ? sum[1] / per_kind : 1.0};
  if (regularization > 0.0)
    for (std::size_t col = 0; col < unknowns(); ++col) {
      double& diagonal = values_[static_cast<std::size_t>(column_start_[col])];
      diagonal += regularization * (diagonal > 0.0 ? diagonal : mean[col % 6 < 3 ? 0 : 1]);
    }
}

std::vector<double> StiffnessAssembly::load(std::span<const double> q, const DisplacementGradient& gradient,
                                            std::span<const std::uint8_t> active) const {
  std::vector<double> f(unknowns(), 0.0);
  const bool affine = std::any_of(gradient.begin(), gradient.end(),
                                  [](const auto& row) { return row[0] != 0.0 || row[1] != 0.0 || row[2] != 0.0; });
  std::vector<double> local(q.size(), 0.0);
  for (std::size_t k = 0; k < links_.size(); ++k) {
    if (!active.empty() && !active[k]) continue;
    const auto pi = static_cast<std::size_t>(links_.i[k]), pj = static_cast<std::size_t>(links_.j[k]);
    const int a = free_index_[pi], b = free_index_[pj];
    if (a < 0 && b < 0) continue;
    const bool prescribed_end = a < 0 || b < 0;
    if (!prescribed_end && !affine) continue;
    // The link's generalized forces on its two ends from the prescribed displacements and the
    // affine strain alone (the free unknowns at zero): f = -K q_p - B^T D (H d).
    std::array<double, 12> qk{};
    for (int c = 0; c < 6; ++c) {
      if (a < 0) qk[static_cast<std::size_t>(c)] = q[6 * pi + static_cast<std::size_t>(c)];
      if (b < 0) qk[static_cast<std::size_t>(6 + c)] = q[6 * pj + static_cast<std::size_t>(c)];
    }
    // Through link_response: the generalized forces of a link are its force and torques.
    std::vector<double>& scratch = local;
    for (int c = 0; c < 6; ++c) {
      scratch[6 * pi + static_cast<std::size_t>(c)] = qk[static_cast<std::size_t>(c)];
      scratch[6 * pj + static_cast<std::size_t>(c)] = qk[static_cast<std::size_t>(6 + c)];
    }
    const LinkResponse r = link_response(links_, k, scratch, gradient);
    for (int c = 0; c < 6; ++c) {
      scratch[6 * pi + static_cast<std::size_t>(c)] = 0.0;
      scratch[6 * pj + static_cast<std::size_t>(c)] = 0.0;
    }
    const Vec3 n = links_.branch[k] * (1.0 / norm(links_.branch[k]));
    // The springs' force acts at the contact point; the pre-force's turn has no torque.
    const Vec3 spring = links_.prestress.empty() ? r.force_on_j : r.force_on_j - r.geometric_force_on_j;
    const Vec3 torque_j = -links_.branch_j[k] * cross(n, spring) + r.moment_on_j;
    const Vec3 torque_i = -links_.branch_i[k] * cross(n, spring) - r.moment_on_j;
    if (a >= 0) {
      const Vec3 fi = -r.force_on_j;
      const double g[6] = {fi.x, fi.y, fi.z, torque_i.x, torque_i.y, torque_i.z};
      for (int c = 0; c < 6; ++c) f[6 * static_cast<std::size_t>(a) + static_cast<std::size_t>(c)] += g[c];
    }
    if (b >= 0) {
      const Vec3& fj = r.force_on_j;
      const double g[6] = {fj.x, fj.y, fj.z, torque_j.x, torque_j.y, torque_j.z};
      for (int c = 0; c < 6; ++c) f[6 * static_cast<std::size_t>(b) + static_cast<std::size_t>(c)] += g[c];
    }
  }
  return f;
}

void StiffnessAssembly::scatter(std::span<const double> x, std::span<double> q) const {
  for (std::size_t p = 0; p < free_index_.size(); ++p) {
    const int a = free_index_[p];
    if (a < 0) continue;
    for (std::size_t c = 0; c < 6; ++c) q[6 * p + c] = x[6 * static_cast<std::size_t>(a) + c];
  }
}

}  // namespace packlab::mechanics
