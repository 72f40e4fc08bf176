// Estimates of the memory a run needs, checked before anything is allocated: a size that
// cannot fit is refused with the estimate (InputError, exit code 2) instead of ending in
// std::bad_alloc after minutes, or in the kernel's out-of-memory killer.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace packlab {

// Physical memory of this machine [bytes]; 0 where it cannot be read.
double physical_memory_bytes();

// InputError "<key> = <value>: about N items need X GB (B bytes each), more than the Y GB of
// this machine" when items * bytes_per_item exceeds the physical memory (no check where that
// is unknown).
void require_memory(std::string_view key, double value, double items, double bytes_per_item);

// Heap bytes a vector holds (its capacity, not its size): the unit of the memory reports of the
// engine, the neighbour list and the Lubachevsky-Stillinger simulation.
template <class T>
std::size_t heap_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

// Gives a vector's heap back. (`v = {}` would not: it picks the initializer-list assignment,
// which empties the vector and keeps its capacity.)
template <class T>
void release_memory(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

}  // namespace packlab
