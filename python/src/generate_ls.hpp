// Pieces shared by the hard-sphere generators of the Python module (generate_ls.cpp,
// generate_shake.cpp, generate_scrm.cpp): the LS and shaking statistics as dicts and the
// documentation of the LS progress callback.
#pragma once

#include "common.hpp"
#include "packlab/generate/ls.hpp"
#include "packlab/generate/shake.hpp"

namespace packlab::python {

inline py::dict ls_status(const generate::LsStatus& s) {
  py::dict d;
  d["stop"] = generate::ls_stop_name(s.stop);
  d["volume_fraction"] = s.volume_fraction;
  d["reduced_pressure"] = s.reduced_pressure;
  d["blocks"] = s.blocks;
  d["collisions"] = s.collisions;
  d["transfers"] = s.transfers;
  d["stale_events"] = s.stale;
  d["simulated_time"] = s.time;
  d["seconds"] = s.seconds;
  return d;
}

inline py::dict shake_stats(const generate::ShakeStats& s) {
  py::dict d;
  d["sweeps"] = s.sweeps;
  d["visits"] = s.visits;
  d["trials"] = s.trials;
  d["moves"] = s.moves;
  d["mean_step"] = s.mean_step;
  d["seconds"] = s.seconds;
  d["window"] = s.window;
  return d;
}

inline const char* const ls_progress_doc =
    "progress(block, volume_fraction, reduced_pressure) is called (GIL held, at most every progress_interval s) "
    "after LS blocks.\n";

}  // namespace packlab::python
