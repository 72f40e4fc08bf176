// Analysis of a 10^5-particle packing: coordination (with rattlers), pore-size distribution
// by the exclusion probability (default sample size: 95 % band of half-width 0.005) with the
// eq. 6 fit, and the fabric tensor. Times each step and the whole.
// usage: bench_analyze [THREADS] [FILE]
//   FILE given: the packing is tiled 5 x 2 x 1 (a 10^4-particle anchor packing becomes 10^5);
//   without FILE: 10^5 random overlapping spheres at nominal volume fraction 0.6 (soft-sphere
//   like), seed 1.
// last line: packlab analyze N=... total_s=...
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "packlab/analyze/coordination.hpp"
#include "packlab/analyze/fabric.hpp"
#include "packlab/analyze/pore_size.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/generate/random.hpp"
#include "packlab/io/packing_io.hpp"

using namespace packlab;

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Packing tile(const Packing& p, int nx, int ny, int nz) {
  Packing out;
  out.box = p.box;
  out.box.length = {p.box.length.x * nx, p.box.length.y * ny, p.box.length.z * nz};
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        for (std::size_t q = 0; q < p.size(); ++q)
          out.add(p.position[q] + Vec3{i * p.box.length.x, j * p.box.length.y, k * p.box.length.z}, p.radius[q],
                  p.type[q]);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does (core/thread_wait.hpp)
  const int threads = argc > 1 ? std::atoi(argv[1]) : 0;
  Packing packing;
  std::string source;
  if (argc > 2) {
    packing = tile(io::read_packing(argv[2]), 5, 2, 1);
    source = fmt::format("{} tiled 5x2x1", argv[2]);
  } else {
    generate::RandomPackingParams rp;
    rp.particles = 100000;
    rp.volume_fraction = 0.6;
    Random rng(1);
    packing = generate::make_random_packing(rp, rng);
    source = "random overlapping spheres, nominal phi 0.6";
  }
  fmt::print("packing: {} ({} particles)\n", source, packing.size());

  const auto t_all = std::chrono::steady_clock::now();
  auto t = std::chrono::steady_clock::now();
  analyze::Coordination cn(0.01);
  cn.compute(packing);
  const double t_cn = since(t);
  fmt::print("coordination  {:.3f} s  mean {:.4f}, without {} rattlers {:.4f}\n", t_cn, cn.mean(), cn.rattler_count(),
             cn.mean_without_rattlers());

  t = std::chrono::steady_clock::now();
  analyze::PoreSizeParams pp;
  pp.threads = threads;
  analyze::PoreSize pores(pp);
  Random rng(1);
  pores.compute(packing, rng);
  const double t_pores = since(t);
  t = std::chrono::steady_clock::now();
  const analyze::DohFit doh = analyze::fit_degree_of_heterogeneity(pores);
  const double t_fit = since(t);
  fmt::print("pore size     {:.3f} s  {} pore points ({} drawn), porosity {:.4f}\n", t_pores, pores.counted_points(),
             pores.drawn_points(), pores.porosity());
  fmt::print("doh fit       {:.3f} s  a = {:.4f} +- {:.4f}, b = {:.4f} +- {:.4f}, R^2 = {:.5f}\n", t_fit, doh.fit.a,
             doh.fit.a_err, doh.fit.b, doh.fit.b_err, doh.fit.r2);

  t = std::chrono::steady_clock::now();
  analyze::Fabric fabric(0.01);
  fabric.compute(packing);
  const double t_fabric = since(t);
  fmt::print("fabric        {:.3f} s  anisotropy {:.4f} ({} contacts)\n", t_fabric, fabric.anisotropy(),
             fabric.contacts());
  fmt::print("packlab analyze N={} threads={} total_s={:.3f}\n", packing.size(), threads, since(t_all));
  return 0;
}
