// Shaking collective rearrangement model, SCRM (scrm-bimodal-packs.txt §3): Lubachevsky–
// Stillinger growth (generate/ls.hpp) alternated with global Monte-Carlo shakes
// (generate/shake.hpp), then `final_shakes` global shakes at the target volume fraction.
// The ratio of the alternation is `blocks_per_cycle` LS blocks (each events_per_block
// events per particle) to `shakes_per_cycle` global shakes.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <ostream>

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

using ScrmProgress = std::function<void(const LsStatus&, const ShakeStats&)>;

// SCRM as a run that can stop and go on: step() does one LS segment and the global shakes
// after it, or one of the final shakes; between two steps save_state() writes the whole state
// (the LS simulation, the phase, the counters, the shake statistics and, during the final
// shakes, the shaken packing), so that a run loaded from it, given the generator in the saved
// state, ends exactly as the uninterrupted one.
class ScrmRun {
 public:
  ScrmRun(LsSimulation simulation, const ScrmParams& params);
  // False once the run is done. `on_progress(ls, shake)` after every LS segment and every shake.
  bool step(Random& rng, const ScrmProgress& on_progress = {});
  bool finished() const { return phase_ == Phase::done; }
  ScrmResult result() const;
  void save_state(std::ostream& out) const;
  static ScrmRun load_state(std::istream& in, const ScrmParams& params);

 private:
  enum class Phase : std::int32_t { growth, final_shakes, done };
  ScrmRun(LsSimulation simulation, const ScrmParams& params, bool fresh);
  void start_final_shakes();
  void add(const ShakeStats& s);

  LsSimulation simulation_;
  ScrmParams params_;
  Phase phase_ = Phase::growth;
  long cycles_ = 0;
  LsStatus ls_;                           // at the end of the growth
  ShakeStats total_;                      // every shake so far
  std::unique_ptr<Packing> packing_;      // the result so far (a fixed address: the final shaker holds it)
  std::unique_ptr<Shaker> final_shaker_;  // from the end of the growth on
};

// `on_progress(ls, shake)` is called after every LS segment and every shake.
ScrmResult run_scrm(LsSimulation& simulation, const ScrmParams& params, Random& rng,
                    const ScrmProgress& on_progress = {});

}  // namespace packlab::generate
