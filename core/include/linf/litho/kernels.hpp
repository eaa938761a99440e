// SOCS kernels of a Hopkins imaging model: I = sum_i w_i |K_i * M|^2 (docs/design.md,
// "Lithography model"). The kernels are held in the frequency domain, as the ICCAD 2013 files
// store them: n x n complex values for the n x n lowest spatial frequencies of a square period.
#pragma once
#include <complex>
#include <string>
#include <vector>

namespace linf::litho {

struct Kernels {
  // n, odd: frequencies -h..h on each axis, h = n / 2. Entry (r, c) of a kernel is the
  // frequency (fx, fy) = (r - h, c - h) / period (cycles per nm).
  int size = 0;
  // The side of the square period the frequencies belong to, in nm (2048 for the ICCAD 2013
  // kernels: the contest's 2048 x 2048 grid of 1 nm pixels). The image is periodic with it.
  double period = 0;
  std::vector<double> weights;                            // w_i, one a kernel
  std::vector<std::vector<std::complex<double>>> values;  // values[i][r * size + c]

  int half() const { return size / 2; }
  std::size_t count() const { return weights.size(); }
  const std::complex<double>& at(std::size_t i, int fx, int fy) const {
    return values[i][std::size_t(fx + half()) * std::size_t(size) + std::size_t(fy + half())];
  }
  // The image of a clear field (a mask of transmission 1 everywhere): sum_i w_i |K_i(0, 0)|^2.
  double clear_field() const;
};

// Reads a folder in the ICCAD 2013 format: `scales.txt` (the count, then one weight a kernel)
// and `fh0.bin` ... `fh<count-1>.bin` (a header of six big-endian int32: n, n, 2, three words
// not used; then n x n complex values, each a big-endian float32 real part and imaginary part).
// Throws std::invalid_argument with a sentence naming the file for a missing or unreadable
// file, a wrong header or size, kernels of different sizes, or a bad weights file.
Kernels read_kernels(const std::string& folder, double period = 2048.0);

}  // namespace linf::litho
