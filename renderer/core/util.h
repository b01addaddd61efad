#pragma once
// Small helpers shared by the renderer, the bench and the app: medians, FNV-1a hashing, this thread's CPU clock.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace deepgi {

// The median (mean of the two middle values for an even count); 0 for an empty list.
double median(std::vector<double> values);

// 64-bit FNV-1a over bytes, continuing from h (start with kFnvOffset).
constexpr uint64_t kFnvOffset = 1469598103934665603ull;
uint64_t fnv1a(uint64_t h, const void* data, size_t bytes);
template <class T>
uint64_t fnv1aValue(uint64_t h, const T& v) { return fnv1a(h, &v, sizeof(v)); }

// CPU time of the calling thread in milliseconds (CLOCK_THREAD_CPUTIME_ID).
double threadCpuMs();

}  // namespace deepgi
