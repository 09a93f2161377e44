#pragma once
// How much work the main thread has done, as one counter for the whole
// process (SPEC.md §9.1, protocol 1.8). The main thread bumps it wherever it
// may spend more than about 0.1 s without finishing a step: each DEM and FDM
// step, each neighbour-list rebuild, the long loops of generation,
// serialisation and checkpoints. The heartbeat thread copies it into every
// pong, so a client tells a main thread that works from one that deadlocked
// or spins while the heartbeat still answers.
//
// Relaxed atomics: the counter orders nothing, it only has to move; a bump
// costs an uncontended atomic add, small beside any step.
#include <cstdint>

namespace dfc::work_progress {

/// One more piece of work done by the main thread.
void advance() noexcept;

/// The count so far: never decreases.
[[nodiscard]] std::int64_t current() noexcept;

/// advance() once every `every` iterations of a loop over `index` (at 0,
/// `every`, 2 `every`, ...): for loops whose single iterations are too cheap
/// to bump each.
inline void advance_every(std::int64_t index, std::int64_t every) noexcept {
  if (index % every == 0) advance();
}

}  // namespace dfc::work_progress
