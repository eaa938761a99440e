// One column of a caller's table read in place, possibly strided (every tenth double of a
// row-major block, such as the gauge table's centre x): a full layer's columns are millions of
// values, and the core reads them without a copy.
#pragma once
#include <cstddef>
#include <cstring>

namespace linf {

template <class T>
struct Strided {
  const char* data = nullptr;
  std::ptrdiff_t stride = sizeof(T);  // bytes from one value to the next
  std::size_t n = 0;

  std::size_t size() const { return n; }
  // Copied out, as the values need not be aligned.
  T operator[](std::size_t i) const {
    T v;
    std::memcpy(&v, data + std::ptrdiff_t(i) * stride, sizeof v);
    return v;
  }
};

}  // namespace linf
