// SOCS kernels computed from optics: scalar Hopkins imaging of a partially coherent source
// through a circular pupil with defocus, decomposed into coherent kernels (docs/design.md,
// "Lithography model", "Kernels from optics").
#pragma once
#include <string>

#include "linf/litho/kernels.hpp"

namespace linf::litho {

struct Optics {
  double wavelength = 193;  // nm
  double na = 1.35;         // numerical aperture
  double medium = 1.44;     // refractive index between lens and wafer: 1 dry, 1.44 water at 193 nm
  double sigma_in = 0.7;    // illumination: source points with sigma_in <= |s| / (NA / wavelength) <= sigma_out;
  double sigma_out = 0.9;   //   sigma_in = 0 is conventional, sigma_in = sigma_out = 0 coherent
  // Quasar: only the four poles of the ring centred on the diagonals (45, 135, 225, 315
  // degrees), each `quasar_opening` degrees wide; 0 keeps the whole ring (annular).
  double quasar_opening = 0;
  double defocus = 0;       // nm, the wafer's distance from best focus
  double period = 2048;     // nm, the side of the square period the frequencies belong to
  int kernels = 24;         // at most this many kernels, largest weights first
};

// The presets (numbers in docs/design.md): `duv193` 193 nm, NA 1.35 water immersion, annular
// 0.7 / 0.9, period 2048 nm; `euv` 13.5 nm, NA 0.33 in vacuum, annular 0.5 / 0.9, period 512 nm.
// Throws std::invalid_argument for another name.
Optics optics_preset(const std::string& name);

// The kernels of `optics`. The source is sampled on the frequency grid of the period (points
// s = j / period in the annulus), each point of equal weight, the weights summing to 1; the
// pupil passes |f| <= NA / wavelength with the defocus phase
// exp(2 pi i z (sqrt((n / wavelength)^2 - |f|^2) - n / wavelength)). The TCC T = A A^H, A's
// columns the source points' shifted pupils, is decomposed through the small Gram matrix A^H A.
// The kernels kept are the largest, never splitting a group of equal weights; their weights are
// scaled so that a clear field images to exactly 1. Throws std::invalid_argument (a sentence
// naming the value) for a non-positive wavelength, NA or period, NA >= the medium's index, a
// negative sigma, sigma_in > sigma_out, sigma_out > 1, a quasar opening outside [0, 90] degrees,
// or fewer than one kernel.
Kernels kernels_from_optics(const Optics& optics);

}  // namespace linf::litho
