// Waiting threads sleep instead of spinning. OpenMP's runtime (libgomp) lets a thread that
// reaches a barrier spin for up to 300,000 iterations before it sleeps; the engine meets a
// few barriers per time step, so on a machine where another process is busy on one core the
// spinning thread takes the core from the thread everyone waits for, and two threads ran up
// to 60x slower than one (issue #14). With OMP_WAIT_POLICY=passive they sleep at once: a
// little slower on an idle machine, never a collapse on a loaded one (docs/engine.md has the
// figures). libgomp reads the variable when it loads, before main(), so the program sets it
// and starts itself again; a user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT is respected.
#pragma once

namespace packlab {

// Call first thing in main(): returns only when the policy is in place (or cannot be set).
// Also turns OpenMP's dynamic team sizes off (fixed_thread_teams()).
void ensure_passive_thread_wait(char** argv);

// Every parallel region gets the threads it asks for: with OMP_DYNAMIC=true libgomp may give a
// smaller team on a loaded machine, and the regions that split their work into fixed per-thread
// ranges (the engine's step, the neighbour list's build, BD's new-bond lists) would leave the
// missing threads' ranges undone (found: the start of `generate bd` stopped with an overlap).
void fixed_thread_teams();

}  // namespace packlab
