// .bsdf files in the layout pbrt-v3's Material "fourier" reads (render/fourier_bsdf.h), for
// tests and probes: a table of the Fourier coefficients of f·|μi| in the azimuth difference.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace prism::test {

// The file's bytes for zenith cosines `mu` (increasing, in [-1, 1]), `channels` 1 or 3 and
// `order` coefficients per channel: `coeffs(muI, muO)` gives channel-major coefficients
// (channels × order values; trailing zeros are trimmed). The CDF rows are the integrals of the
// a_0 splines, as pbrt-v3's own tables hold them.
std::string FourierBsdfBytes(const std::vector<float> &mu, int channels, int order, float eta,
                             const std::function<std::vector<float>(float, float)> &coeffs);

// A two-sided Lambertian reflector of albedo `rho`: a_0 = rho |μi| / π where μi μo < 0,
// one channel, on `n` cosines evenly spaced over [-1, 1].
std::string LambertianFourierBsdf(float rho, int n = 41);

}  // namespace prism::test
