// Shaking collective rearrangement model, SCRM (scrm-bimodal-packs.txt §3): Lubachevsky–
// Stillinger growth (generate/ls.hpp) alternated with global Monte-Carlo shakes
// (generate/shake.hpp), then `final_shakes` global shakes at the target volume fraction.
// The ratio of the alternation is `blocks_per_cycle` LS blocks (each events_per_block
// events per particle) to `shakes_per_cycle` global shakes.
#pragma once

#include <functional>

#include "packlab/generate/ls.hpp"
#include "packlab/generate/shake.hpp"

namespace packlab::generate {

struct ScrmParams {
  LsParams ls;                 // ls.target_volume_fraction > 0 is required
  ShakeParams shake;
  long blocks_per_cycle = 5;   // LS blocks between shakes
  long shakes_per_cycle = 1;   // global shakes after each LS segment (0 = plain LS, then final shakes)
  long final_shakes = 10;      // global shakes at the target
  void validate() const;
};

struct ScrmResult {
  Packing packing;
  LsStatus ls;
  ShakeStats shake;
  long cycles = 0;
};

// `on_progress(ls, shake)` is called after every LS segment and every shake.
ScrmResult run_scrm(LsSimulation& simulation, const ScrmParams& params, Random& rng,
                    const std::function<void(const LsStatus&, const ShakeStats&)>& on_progress = {});

}  // namespace packlab::generate
