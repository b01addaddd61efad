#pragma once
// Small helpers shared by the renderer, the bench and the app: image-size parsing, medians, FNV-1a hashing, this
// thread's CPU clock.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace deepgi {

// "WxH" (e.g. "320x180") -> {W, H}. Strict: decimal integers 1..65536 (0..65536 if allowZero), an 'x' or 'X'
// between them, nothing else; throws std::runtime_error quoting the text otherwise.
std::pair<int, int> parseImageSize(const std::string& text, bool allowZero = false);

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
