// The near list: a second, tighter list drawn from the Verlet list (a two-level neighbour list).
//
// The Verlet list holds every pair within r_i + r_j + reach + skin, so that it stays valid
// while the particles move up to half the skin; the pair loop must visit each listed pair at
// every step to find the ones that act. In a sparse packing almost none do: in the void
// expansion method's Fig. 1 case 0.1-0.5 % of the ~14,500 listed pairs touch at a check (the
// rest are gas neighbours within the skin), and visiting them was half of the run's time
// (docs/engine.md, "Performance"). The near list keeps, per thread range, only the listed
// pairs within r_i + r_j + reach + margin that no bond holds; the margin is
// near_margin_ratio x skin, or more where the fastest particle would cross that in fewer than
// ten steps (at most the skin). A pair left out cannot act until some particle pair has closed the margin, i.e.
// until the particles may have moved margin / 2 each; the bound on that is the sum over the
// steps since the refresh of dt max_i |v_i| (each particle moves dt |v_i| in a step, and
// positions change only through the integration), and the list is refreshed before the step
// at which twice that bound would reach the margin. It is also refreshed after every Verlet
// rebuild, repartition, change of radii and broken bond (stale).
//
// What the pair loop then computes is exactly what it computed over the whole list: the near
// pairs are a subsequence of the listed ones (ascending), every pair that acts is in it, and
// the pairs left out are those the loop would have found not acting and whose history it
// would have cleared, as the refresh clears it. The forces are the same sums in the same
// order: results are the same bit for bit with or without the near list, at any margin.
//
// A dense packing gains nothing (most listed pairs touch): where the near list would keep
// more than `near_use_fraction` of the listed pairs, the loop walks the whole list until the
// next Verlet rebuild decides again.
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "packlab/core/memory.hpp"
#include "packlab/core/parallel_errors.hpp"
#include "packlab/dem/engine.hpp"

namespace packlab::dem {

namespace {

// The near list is walked only when it holds at most this fraction of the listed pairs:
// walking it reads two indices per pair and the histories out of order, and refreshing it
// reads the whole list.
constexpr double near_use_fraction = 0.6;

// Rounding: the drift bound and the distances are computed in floating point; refreshing a
// little early keeps the bound's guarantee far from round-off.
constexpr double near_margin_used = 0.99;

// The margin is sized for about this many steps of the fastest particle's motion (at least the
// configured one, at most the skin): a gas whose fastest particle crosses the least margin in
// a step or two would refresh the list at almost every step (62,622 refreshes in the VEM
// blow-up's 69,000 steps), each reading the whole Verlet list.
constexpr double near_steps_per_refresh = 10.0;

}  // namespace

bool Engine::near_list_due() const {
  if (!(near_base_margin_ > 0.0)) return false;
  return near_stale_ || (near_active_ && 2.0 * near_drift_ >= near_margin_used * near_margin_);
}

std::size_t Engine::near_pairs() const {
  if (!near_active_) return neighbors_.pair_count();
  std::size_t count = 0;
  for (int t = 0; t < threads_; ++t) count += work_[static_cast<std::size_t>(t)].near_pairs.size();
  return count;
}

void Engine::refresh_near_pairs() {
  ++near_refreshes_;
  near_stale_ = false;
  near_drift_ = 0.0;
  const int T = threads_;
  // Each particle moves dt |v| per step: twice that for a pair (both may close in).
  near_margin_ = std::clamp(2.0 * near_steps_per_refresh * dt_ * last_max_speed_, near_base_margin_,
                            std::max(near_base_margin_, neighbors_.skin()));
  const double margin = near_margin_;
  ParallelErrors errors;
  std::visit(
      [&](auto& model) {
        using Law = std::decay_t<decltype(model.law)>;
        using History = typename Law::History;
        const Vec3* __restrict x = particles_.position.data();
        const double* __restrict rad = particles_.radius.data();
        const int* __restrict type = particles_.type.data();
        const int* __restrict first = neighbors_.first_pairs().data();
        const int* __restrict partner = neighbors_.partner().data();
        const std::uint8_t* __restrict image = neighbors_.image().data();
        const Vec3* __restrict offsets = &neighbors_.image_offset(0);
        const bool any_bonded = !pair_bonded_.empty();
        const std::uint8_t* __restrict bonded = pair_bonded_.data();
        History* __restrict history = model.history.data();
        const bool keep_histories = pair_histories_;
        const auto* __restrict params = model.pair_params.data();
        const int type_count = model.type_count;
#pragma omp parallel num_threads(T)
        errors.run(omp_get_thread_num(), [&] {
          ThreadWork& w = work_[static_cast<std::size_t>(omp_get_thread_num())];
          w.near_pairs.clear();
          w.near_owners.clear();
          for (int i = w.particle_begin; i < w.particle_end; ++i) {
            for (int p = first[i]; p < first[i + 1]; ++p) {
              const int j = partner[p];
              // The same distance as the pair loop's (gather_pairs), so the same rounding.
              const Vec3 d = x[j] + offsets[image[p]] - x[i];
              const double reach =
                  type_count == 1 ? Law::reach(params[0]) : Law::reach(params[type[i] * type_count + type[j]]);
              const double cutoff = rad[i] + rad[j] + reach + margin;
              if (norm2(d) < cutoff * cutoff && (!any_bonded || bonded[p] == 0)) {
                w.near_pairs.push_back(p);
                w.near_owners.push_back(i);
              } else if (keep_histories) {
                history[p] = History{};  // not acting: the pair loop would have cleared it
              }
            }
          }
        });
      },
      model_);
  std::size_t near_count = 0;
  for (int t = 0; t < T; ++t) near_count += work_[static_cast<std::size_t>(t)].near_pairs.size();
  near_active_ = !errors.failed() &&
                 static_cast<double>(near_count) <= near_use_fraction * static_cast<double>(neighbors_.pair_count());
  if (!near_active_)  // the whole list is walked until the next decision
    for (int t = 0; t < T; ++t) {
      release_memory(work_[static_cast<std::size_t>(t)].near_pairs);
      release_memory(work_[static_cast<std::size_t>(t)].near_owners);
    }
  collect_crossing_pairs();
  errors.rethrow();
}

}  // namespace packlab::dem
