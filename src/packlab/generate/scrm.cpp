#include "packlab/generate/scrm.hpp"

#include "packlab/core/binary_io.hpp"
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

ScrmRun::ScrmRun(LsSimulation simulation, const ScrmParams& params) : ScrmRun(std::move(simulation), params, true) {}

ScrmRun::ScrmRun(LsSimulation simulation, const ScrmParams& params, bool fresh)
    : simulation_(std::move(simulation)), params_(params), packing_(std::make_unique<Packing>()) {
  params_.validate();
  if (!fresh) return;
  LsParams segment = params_.ls;
  segment.max_blocks = params_.shakes_per_cycle > 0 ? params_.blocks_per_cycle : 0;
  simulation_.set_params(segment);
}

void ScrmRun::add(const ShakeStats& s) {
  const double steps =
      total_.mean_step * static_cast<double>(total_.moves) + s.mean_step * static_cast<double>(s.moves);
  total_.sweeps += s.sweeps;
  total_.visits += s.visits;
  total_.trials += s.trials;
  total_.moves += s.moves;
  total_.seconds += s.seconds;
  total_.mean_step = total_.moves > 0 ? steps / static_cast<double>(total_.moves) : 0.0;
  total_.window = s.window;
}

void ScrmRun::start_final_shakes() {
  ls_ = simulation_.status();
  if (params_.final_shakes > 0) {
    final_shaker_ = std::make_unique<Shaker>(*packing_, params_.shake);
    phase_ = Phase::final_shakes;
  } else {
    phase_ = Phase::done;
  }
}

bool ScrmRun::step(Random& rng, const ScrmProgress& on_progress) {
  if (phase_ == Phase::growth) {
    const LsStatus st = simulation_.run();
    ++cycles_;
    *packing_ = simulation_.packing();
    if (on_progress) on_progress(st, total_);
    if (st.stop != LsStop::max_blocks) {
      start_final_shakes();
      return !finished();
    }
    Shaker shaker(*packing_, params_.shake);
    shaker.sweeps(params_.shakes_per_cycle, rng);
    add(shaker.stats());
    simulation_.set_positions(packing_->position);
    if (on_progress) on_progress(st, total_);
  } else if (phase_ == Phase::final_shakes) {
    final_shaker_->sweep(rng);
    const ShakeStats& s = final_shaker_->stats();
    if (on_progress) {
      ShakeStats now = total_;
      now.sweeps += s.sweeps;
      on_progress(ls_, now);
    }
    if (s.sweeps >= params_.final_shakes) {
      add(s);
      phase_ = Phase::done;
    }
  }
  return !finished();
}

ScrmResult ScrmRun::result() const {
  ScrmResult result;
  result.packing = *packing_;
  result.ls = ls_;
  result.shake = total_;
  result.cycles = cycles_;
  return result;
}

void ScrmRun::save_state(std::ostream& out) const {
  simulation_.save_state(out);
  binary::write(out, static_cast<std::int32_t>(phase_));
  binary::write(out, cycles_);
  binary::write(out, ls_);
  write_shake_stats(out, total_);
  binary::write(out, static_cast<std::uint8_t>(final_shaker_ != nullptr));
  if (final_shaker_) final_shaker_->save_state(out);  // the shaken packing
}

ScrmRun ScrmRun::load_state(std::istream& in, const ScrmParams& params) {
  ScrmRun run(LsSimulation::load_state(in), params, false);
  std::int32_t phase = 0;
  binary::read(in, phase, "SCRM phase");
  if (phase < 0 || phase > static_cast<std::int32_t>(Phase::done)) fail_input("checkpoint is damaged: SCRM phase");
  run.phase_ = static_cast<Phase>(phase);
  binary::read(in, run.cycles_, "cycles");
  binary::read(in, run.ls_, "LS status");
  run.total_ = read_shake_stats(in);
  std::uint8_t shaking = 0;
  binary::read(in, shaking, "final shakes flag");
  // The packing of the last LS segment follows from the simulation's state; the final shakes
  // moved it on from there.
  if (run.cycles_ > 0) *run.packing_ = run.simulation_.packing();
  if (shaking != 0) {
    if (run.cycles_ == 0) fail_input("checkpoint is damaged: SCRM counters");
    run.final_shaker_ = std::make_unique<Shaker>(*run.packing_, run.params_.shake);
    run.final_shaker_->load_state(in);
  }
  return run;
}

ScrmResult run_scrm(LsSimulation& simulation, const ScrmParams& params, Random& rng, const ScrmProgress& on_progress) {
  ScrmRun run(simulation, params);
  while (run.step(rng, on_progress)) {
  }
  return run.result();
}

}  // namespace packlab::generate
