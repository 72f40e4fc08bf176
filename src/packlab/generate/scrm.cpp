#include "packlab/generate/scrm.hpp"

#include "packlab/core/error.hpp"

namespace packlab::generate {

void ScrmParams::validate() const {
  ls.validate();
  shake.validate();
  require(ls.target_volume_fraction > 0.0, "phi", ls.target_volume_fraction, "> 0 (SCRM grows to a target)");
  require(blocks_per_cycle >= 1, "blocks_per_cycle", static_cast<double>(blocks_per_cycle), ">= 1");
  require(shakes_per_cycle >= 0, "shakes_per_cycle", static_cast<double>(shakes_per_cycle), ">= 0");
  require(final_shakes >= 0, "final_shakes", static_cast<double>(final_shakes), ">= 0");
}

ScrmResult run_scrm(LsSimulation& simulation, const ScrmParams& params, Random& rng,
                    const std::function<void(const LsStatus&, const ShakeStats&)>& on_progress) {
  params.validate();
  ScrmResult result;
  LsParams segment = params.ls;
  segment.max_blocks = params.shakes_per_cycle > 0 ? params.blocks_per_cycle : 0;
  simulation.set_params(segment);
  ShakeStats total;
  auto add = [&total](const ShakeStats& s) {
    const double steps = total.mean_step * static_cast<double>(total.moves) + s.mean_step * static_cast<double>(s.moves);
    total.sweeps += s.sweeps;
    total.visits += s.visits;
    total.trials += s.trials;
    total.moves += s.moves;
    total.seconds += s.seconds;
    total.mean_step = total.moves > 0 ? steps / static_cast<double>(total.moves) : 0.0;
    total.window = s.window;
  };
  for (;;) {
    const LsStatus st = simulation.run();
    ++result.cycles;
    result.packing = simulation.packing();
    if (on_progress) on_progress(st, total);
    if (st.stop != LsStop::max_blocks) break;
    Shaker shaker(result.packing, params.shake);
    shaker.sweeps(params.shakes_per_cycle, rng);
    add(shaker.stats());
    simulation.set_positions(result.packing.position);
    if (on_progress) on_progress(st, total);
  }
  result.ls = simulation.status();
  if (params.final_shakes > 0) {
    Shaker shaker(result.packing, params.shake);
    shaker.sweeps(params.final_shakes, rng, [&](const ShakeStats& s) {
      if (on_progress) {
        ShakeStats now = total;
        now.sweeps += s.sweeps;
        on_progress(result.ls, now);
      }
    });
    add(shaker.stats());
  }
  result.shake = total;
  return result;
}

}  // namespace packlab::generate
