// Micro-benchmarks (Google Benchmark) of the kernels the end-to-end benchmarks spend their time
// in, each reported as a rate (items_per_second):
//   pair_kernel/contact/<law>, pair_kernel/bond/<law>  evaluate() of every registered contact
//       and bond law over a batch of touching (bonds: stretched or compressed) pairs (pair
//       evaluations/s);
//   neighbor_build/N         NeighborList::build on a random periodic packing (particles/s);
//   ls_event/N               Lubachevsky-Stillinger event-driven MD, one block of 20 events per
//                            particle at volume fraction 0.6 without growth (collisions/s, and
//                            events/s counting neighbour-list transfers);
//   shake_trial/<rule>       Shaker sweeps of a dense random packing (trial moves/s, moves/s);
//   engine_step/10000        dem::Engine::run(1), 1 thread, linear law (particle-steps/s);
//   openmp_fork_join, openmp_barrier  one parallel region, one barrier of two threads (real
//                            time each, with the program's wait policy).
// Fixed seeds throughout; the rates are per CPU second of the benchmark thread (Google
// Benchmark's default), so a machine loaded by other processes shows less in wall time.
// usage: bench_micro [--benchmark_filter=REGEX] [--benchmark_min_time=SECONDS] ...
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "packlab/core/neighbor_list.hpp"
#include "packlab/core/random.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/dem/bond/registry.hpp"
#include "packlab/dem/contact/registry.hpp"
#include "packlab/dem/engine.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/shake.hpp"

using namespace packlab;

namespace {

constexpr double dense_fraction = 0.6;

// One material with every property any law reads: 1 mm glass-like grains.
constexpr dem::Material material{.normal_stiffness = 1e5, .shear_stiffness = 2.5e4, .friction = 0.5,
                                 .density = 2500, .youngs_modulus = 7e10, .poisson_ratio = 0.25,
                                 .restitution = 0.5, .rolling_friction = 0.01, .work_of_adhesion = 0.05,
                                 .adhesion_range = 1e-5};

// A batch of interacting pairs of 1 mm grains: overlaps up to 0.5 % of the contact distance
// (bonds: +-0.5 %, stretched or compressed, rest length r_i + r_j), mm/s relative velocities,
// spins of order 1 rad/s, the time step of the linear law's global rule.
std::vector<dem::ContactGeometry> pair_batch(std::size_t pairs, bool bonded) {
  Random rng(11);
  std::vector<dem::ContactGeometry> batch(pairs);
  for (dem::ContactGeometry& g : batch) {
    g.radius_i = rng.uniform(0.8e-3, 1.2e-3);
    g.radius_j = rng.uniform(0.8e-3, 1.2e-3);
    const double sum = g.radius_i + g.radius_j;
    g.normal = rng.unit_vector();
    g.overlap = sum * (bonded ? rng.uniform(-0.005, 0.005) : rng.uniform(1e-4, 0.005));
    g.branch_i = g.radius_i - 0.5 * g.overlap;
    g.branch_j = g.radius_j - 0.5 * g.overlap;
    g.relative_velocity = 1e-3 * Vec3{rng.normal(), rng.normal(), rng.normal()};
    g.spin_i = Vec3{rng.normal(), rng.normal(), rng.normal()};
    g.spin_j = Vec3{rng.normal(), rng.normal(), rng.normal()};
    g.mean_spin = 0.5 * (g.spin_i + g.spin_j);
    g.relative_spin = g.spin_j - g.spin_i;
    const double mi = material.density * 4.0 / 3.0 * std::numbers::pi * std::pow(g.radius_i, 3);
    const double mj = material.density * 4.0 / 3.0 * std::numbers::pi * std::pow(g.radius_j, 3);
    g.effective_mass = mi * mj / (mi + mj);
    g.dt = 0.2 * std::sqrt(mi / material.normal_stiffness);
    g.rest_length = sum;
  }
  return batch;
}

// evaluate() over the batch, histories carried from pass to pass as in a run (shear springs
// load up to their Coulomb limit); the force sum keeps the work observable.
template <class Law, class Params, class History>
void run_pair_kernel(benchmark::State& state, bool bonded, const Params& params) {
  const std::vector<dem::ContactGeometry> batch = pair_batch(4096, bonded);
  std::vector<History> history(batch.size());
  for (auto _ : state) {
    Vec3 total{};
    for (std::size_t k = 0; k < batch.size(); ++k) total += Law::evaluate(batch[k], params, history[k]).force_on_j;
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch.size()));
}

// A bond law's parameters: its defaults, with every parameter that is also a material
// property (stiffnesses, Young's modulus, Poisson's ratio) taken from `material`.
// Strengths stay infinite: no bond breaks.
template <class Law>
typename Law::Params bond_params() {
  typename Law::Params params{};
  for (const auto& p : Law::parameters)
    for (const Parameter<dem::Material>& mp : dem::material_parameters())
      if (p.name == mp.name && !p.is_boolean()) p.set(params, mp.get(material));
  return params;
}

void register_pair_kernels() {
  dem::ContactLaws::for_each([]<class Law>(std::type_identity<Law>) {
    const typename Law::Params params = Law::mix(material, material, dem::StiffnessRule::contact);
    benchmark::RegisterBenchmark(("pair_kernel/contact/" + std::string(Law::name)).c_str(),
                                 [params](benchmark::State& state) {
                                   run_pair_kernel<Law, typename Law::Params, typename Law::History>(state, false,
                                                                                                     params);
                                 });
  });
  dem::BondLaws::for_each([]<class Law>(std::type_identity<Law>) {
    const typename Law::Params params = bond_params<Law>();
    benchmark::RegisterBenchmark(("pair_kernel/bond/" + std::string(Law::name)).c_str(),
                                 [params](benchmark::State& state) {
                                   run_pair_kernel<Law, typename Law::Params, typename Law::State>(state, true,
                                                                                                   params);
                                 });
  });
}

// Monodisperse LS packing of n spheres of radius 0.5 at volume fraction 0.6 (no overlap, few
// contacts), made once per size.
const Packing& dense_packing(long n) {
  static std::map<long, Packing> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    Random rng(7);
    const generate::LsStart start = generate::make_ls_start(n, {}, 0.5, dense_fraction, rng);
    generate::LsParams p;
    p.growth_rate = 0.5;  // fast: a set-up cost, not measured
    p.target_volume_fraction = dense_fraction;
    generate::LsSimulation sim(start.box, start.points, start.unit_radius, p, rng);
    if (sim.run().stop != generate::LsStop::target_reached)
      throw std::runtime_error("bench_micro: the LS set-up jammed below dense_fraction");
    it = cache.emplace(n, sim.packing()).first;
  }
  return it->second;
}

// Random centres of N spheres of radius 1 at nominal volume fraction 0.4 in a periodic cube
// (bench_neighbor's case without the void particles), skin 0.2; every particle moves by 0.01
// between builds (outside the timing).
void neighbor_build(benchmark::State& state) {
  const long n = state.range(0);
  const double edge = std::cbrt(4.0 * std::numbers::pi * static_cast<double>(n) / (3.0 * 0.4));
  Box box;
  box.length = {edge, edge, edge};
  Random rng(1);
  std::vector<Vec3> position(static_cast<std::size_t>(n));
  for (Vec3& x : position) x = {rng.uniform(0.0, edge), rng.uniform(0.0, edge), rng.uniform(0.0, edge)};
  const std::vector<double> radius(position.size(), 1.0);
  NeighborList list(0.2);
  list.build(box, position, radius);
  for (auto _ : state) {
    state.PauseTiming();
    for (Vec3& x : position) x += 0.01 * rng.unit_vector();
    state.ResumeTiming();
    list.build(box, position, radius);
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["pairs"] = static_cast<double>(list.pair_count());
}
BENCHMARK(neighbor_build)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// Equilibrium hard-sphere MD at volume fraction 0.6 (growth rate 0): one block per iteration.
// The simulation is made once per size (Google Benchmark calls the function once per trial
// run) and goes on from run to run.
void ls_event(benchmark::State& state) {
  const long n = state.range(0);
  static std::map<long, std::unique_ptr<generate::LsSimulation>> cache;
  std::unique_ptr<generate::LsSimulation>& sim = cache[n];
  if (!sim) {
    Random rng(3);
    generate::LsParams p;
    p.growth_rate = 0.0;
    p.max_blocks = 1;
    sim = std::make_unique<generate::LsSimulation>(dense_packing(n), p, rng);
    sim->run();  // first block: the calendar settles
  }
  const generate::LsStatus start = sim->status();
  for (auto _ : state) sim->run();
  const generate::LsStatus& end = sim->status();
  state.SetItemsProcessed(end.collisions - start.collisions);
  state.counters["events"] = benchmark::Counter(static_cast<double>(end.events() - start.events()),
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(ls_event)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// Monte-Carlo shaking (window 0.02, up to 150 trials per visit) of the 10^4-sphere packing at
// 0.6: one sweep per iteration, by the paper's rule (metropolis, the default) and by the
// freest-direction rule.
void shake_trial(benchmark::State& state, const char* rule) {
  Packing packing = dense_packing(10000);
  generate::ShakeParams params;
  params.move_rule = rule;
  generate::Shaker shaker(packing, params);
  Random rng(5);
  for (auto _ : state) shaker.sweep(rng);
  state.SetItemsProcessed(shaker.stats().trials);
  state.counters["moves"] = benchmark::Counter(static_cast<double>(shaker.stats().moves), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(shake_trial, metropolis, "metropolis")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shake_trial, freest, "freest")->Unit(benchmark::kMillisecond);

// The 10^4-sphere packing at 0.6 scaled to 1 mm radii and inflated by 1 % (overlaps up to 2 %
// of a radius, volume fraction 0.618), linear law with friction, local damping 0.7, relaxed for
// 200 steps before the timing (once per size, as ls_event); then one step per iteration
// (neighbour rebuilds included).
void engine_step(benchmark::State& state) {
  const long n = state.range(0);
  static std::map<long, std::unique_ptr<dem::Engine>> cache;
  std::unique_ptr<dem::Engine>& engine = cache[n];
  if (!engine) {
    Packing packing = dense_packing(n);
    const double scale = 2e-3;
    packing.box.length = scale * packing.box.length;
    for (Vec3& x : packing.position) x = scale * x;
    for (double& r : packing.radius) r *= 1.01 * scale;
    packing.velocity.clear();
    dem::EngineConfig config;
    config.types = {material};
    config.stiffness_rule = dem::StiffnessRule::contact;
    config.threads = 1;
    engine = std::make_unique<dem::Engine>(packing, config);
    engine->run(200);
  }
  for (auto _ : state) engine->run(1);
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(engine_step)->Arg(10000)->Unit(benchmark::kMillisecond);

// What a step's synchronization costs (issue #14, thread scaling): one OpenMP parallel region of
// two threads per iteration, and 1,000 barriers of two threads in one region, with the wait
// policy the packlab program sets (passive unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is given;
// core/thread_wait.hpp). Real time per region or barrier; a step of the engine forks two
// regions and passes one barrier (dem/step.cpp).
void openmp_fork_join(benchmark::State& state) {
  int sink = 0;
  for (auto _ : state) {
#pragma omp parallel num_threads(2)
    {
#pragma omp atomic
      sink += omp_get_thread_num();
    }
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(openmp_fork_join)->UseRealTime()->Unit(benchmark::kMicrosecond);

void openmp_barrier(benchmark::State& state) {
  constexpr int barriers = 1000;
  for (auto _ : state) {
#pragma omp parallel num_threads(2)
    for (int k = 0; k < barriers; ++k) {
#pragma omp barrier
    }
  }
  state.SetItemsProcessed(state.iterations() * barriers);
}
BENCHMARK(openmp_barrier)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  ensure_passive_thread_wait(argv);  // as the packlab program does
  register_pair_kernels();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
