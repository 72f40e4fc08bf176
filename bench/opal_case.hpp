// The inverse-opal benchmark case of docs/opal.md, shared by bench_compress and bench_static: a
// force-biased packing of 15 nm particles (porosity 0.38, periodic x, y) in the 300 x 259.8 x
// 413 nm box, tiled 4 x 4 (about 186,000 particles) and made into the FCC opal (pores 138 nm at
// 150 nm spacing, [111] along z, porosity 0.75, two substrate layers, bonds within 1.75 d):
// about 54,000 particles.
#pragma once

#include <fmt/format.h>
#include <malloc.h>

#include <chrono>
#include <string>

#include "packlab/core/random.hpp"
#include "packlab/generate/fba.hpp"
#include "packlab/generate/opal.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::bench {

inline double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// In use: the arena's allocated chunks and the mmap'd ones. Large arrays are mmap'd until glibc's
// dynamic threshold rises (each mmap'd block freed raises it), so uordblks alone counted them or
// not by the history of the process: 98 bytes per bond on 2026-12-02, 34 on 2026-12-03 for the
// same engine, whose own accounting (Engine::memory) gives 97.
inline std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

inline Packing tile(const Packing& p, int n) {
  Packing out;
  out.box = p.box;
  out.box.length = {p.box.length.x * n, p.box.length.y * n, p.box.length.z};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (std::size_t q = 0; q < p.size(); ++q)
        out.add(p.position[q] + Vec3{i * p.box.length.x, j * p.box.length.y, 0.0}, p.radius[q], p.type[q]);
  return out;
}

inline Packing make_opal(const Packing& particles, int threads) {
  generate::OpalOptions oo;
  oo.fcc.diameter = 138e-9;
  oo.fcc.spacing_ratio = 1.087;
  oo.threads = threads;
  generate::OpalSummary summary;
  Packing model = generate::build_opal(particles, oo, &summary);
  fmt::print("opal: {} particles ({} substrate), {} bonds, porosity {:.3f}\n", summary.particles, summary.substrate,
             summary.bonds, summary.porosity);
  return model;
}

inline Packing default_packing(int threads) {
  const double d = 15e-9;
  Box box;
  box.lo = {0, 0, 0};
  box.length = {300e-9, 259.81e-9, 412.95e-9};
  box.periodic = {true, true, false};
  generate::FbaParams fp;
  fp.target_porosity = 0.38;
  fp.threads = threads;
  generate::SizeClasses classes;
  const long count = generate::fba_count_for_volume(box.volume(), fp.target_porosity, d, classes);
  Random rng(2);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> radii = generate::fba_class_radii(count, classes, rng);
  generate::FbaResult packed = generate::fba_pack(box, radii, fp, rng);
  fmt::print("FBA packing of {} particles: {} iterations, {:.1f} s\n", count, packed.status.iteration, since(t0));
  return packed.packing;
}

// A bonded model from FILE as it is, a particle packing from FILE tiled and made into the opal,
// or ("-") the default case.
inline Packing opal_case(const std::string& file, int tiles, int threads) {
  const Packing input = file == "-" ? default_packing(threads) : io::read_packing(file);
  return input.bonds.empty() ? make_opal(tile(input, tiles), threads) : input;
}

}  // namespace packlab::bench
