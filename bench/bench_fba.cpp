// Force-biased algorithm and inverse-opal builder (docs/opal-build.md).
//  1. FBA: N equal spheres (default 50,000) to porosity 0.38, periodic along x, y, walls along z
//     (the paper's setting), tolerance 1e-3: iterations, time, particle-iterations/s, the
//     verified max overlap.
//  2. Builder: that packing with FCC [111] pores of ratio D/d = 10 (box sized to 3 x 3 x 1 pore
//     lattice periods + substrate) and a 1 d titania coating: time, particles, bonds, mean
//     coordination, bytes of the model per particle and per bond, and the peak resident memory.
// usage: bench_fba [RATIO] [SEED]
// last line: packlab fba+opal N=... fba_s=... opal_s=... bytes_per_bond=...
#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"

using namespace packlab;
using namespace packlab::generate;

namespace {

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kB
}

}  // namespace

int main(int argc, char** argv) {
  const double ratio = argc > 1 ? std::atof(argv[1]) : 10.0;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  // Box: 3 x 3 x 1 periods of the [111] pore lattice (touching pores of diameter ratio x d) plus
  // a two-diameter substrate slab; unit particle diameter.
  FccPores fcc;
  fcc.diameter = ratio;
  const Vec3 per = fcc_pore_period(fcc);
  Box box;
  box.length = {3 * per.x, 3 * per.y, per.z + 2.0};
  box.periodic = {true, true, false};
  SizeClasses mono;
  const long n = fba_count_for_volume(box.volume(), 0.38, 1.0, mono);
  Random rng(seed);
  FbaParams fp;
  const double rss0 = peak_rss_mb();
  const auto t0 = std::chrono::steady_clock::now();
  const FbaResult fba = fba_pack(box, fba_class_radii(n, mono, rng), fp, rng);
  const double fba_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rss_fba = peak_rss_mb();
  fmt::print("fba: N={} box={:.2f}x{:.2f}x{:.2f} d periodic=xy porosity={:.6f} stop={} iterations={} time={:.2f} s "
             "rate={:.3g} particle-iterations/s max_overlap={:.3g} (verified {:.3g}, tolerance {:g}) peak_rss={:.0f} MB\n",
             n, box.length.x, box.length.y, box.length.z, 1.0 - fba.packing.volume_fraction(),
             fba_stop_name(fba.status.stop), fba.status.iteration, fba_s,
             static_cast<double>(fba.status.iteration) * static_cast<double>(n) / fba_s, fba.status.max_overlap,
             fba.verified_max_overlap, fp.tolerance, rss_fba);

  double opal0_s = 0;
  long bonds0 = 0;
  for (double coating : {0.0, 1.0}) {
    OpalOptions o;
    o.fcc = fcc;
    o.coating_thickness = coating;
    OpalSummary s;
    const auto t1 = std::chrono::steady_clock::now();
    const Packing model = build_opal(fba.packing, o, &s);
    const double opal_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    // Bytes held by the model: position 24 + radius 8 + type 4 + fixed 1 per particle;
    // i, j 8 + image 12 + material 4 + rest length 8 + state 4 per bond.
    const double bytes_particle = 37.0, bytes_bond = 36.0;
    const double model_mb = (bytes_particle * static_cast<double>(model.size()) +
                             bytes_bond * static_cast<double>(model.bonds.size())) / 1048576.0;
    fmt::print("opal: ratio D/d={:g} coating={:g} d: {} -> {} particles ({} silica, {} titania, {} substrate), {} bonds "
               "({} silica, {} titania, {} substrate, {} periodic), CN={:.3f}, porosity={:.4f}, density={:.1f} kg/m^3, "
               "{} pores, time={:.3f} s ({:.3g} us/particle, {:.3g} us/bond), model={:.1f} MB ({:.0f} B/particle + "
               "{:.0f} B/bond), peak_rss={:.0f} MB (start {:.0f} MB)\n",
               ratio, coating, s.input_particles, s.particles, s.structural, s.coating, s.substrate, s.bonds,
               s.bonds_by_material[0], s.bonds_by_material[1], s.bonds_by_material[2], s.periodic_bonds,
               s.mean_coordination, s.porosity, s.density, s.pores, opal_s,
               1e6 * opal_s / static_cast<double>(s.input_particles), 1e6 * opal_s / static_cast<double>(s.bonds),
               model_mb, bytes_particle, bytes_bond, peak_rss_mb(), rss0);
    if (coating == 0.0) {
      opal0_s = opal_s;
      bonds0 = s.bonds;
    }
  }
  fmt::print("packlab fba+opal N={} fba_s={:.3f} fba_rate={:.4g} opal_s={:.3f} bonds={} bytes_per_bond=36\n", n, fba_s,
             static_cast<double>(fba.status.iteration) * static_cast<double>(n) / fba_s, opal0_s, bonds0);
  return 0;
}
