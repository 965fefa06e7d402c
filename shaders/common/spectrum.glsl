// Wavelengths for KHR_materials_dispersion. A path that meets a dispersive material carries one
// wavelength from then on, drawn uniformly over [WAVELENGTH_MIN, WAVELENGTH_MAX] nm, and its
// throughput is multiplied by that wavelength's RGB weight: the CIE 1931 colour matching
// functions (the multi-lobe Gaussian fit of Wyman, Sloan and Shirley 2013) in linear Rec. 709,
// clipped at 0 (the spectral colours outside the gamut would otherwise give negative samples),
// and divided by their mean over the range, so that a flat spectrum -- white light through
// clear glass -- stays white on average. Every other material keeps its RGB values along such a
// path: the usual hero-wavelength-in-RGB approximation.
#ifndef PT_COMMON_SPECTRUM_GLSL
#define PT_COMMON_SPECTRUM_GLSL

const float WAVELENGTH_MIN = 380.0;
const float WAVELENGTH_MAX = 780.0;

float cieLobe(float lambda, float mu, float sigmaBelow, float sigmaAbove) {
    float t = (lambda - mu) / (lambda < mu ? sigmaBelow : sigmaAbove);
    return exp(-0.5 * t * t);
}

vec3 cieXyz(float lambda) {
    float x = 1.056 * cieLobe(lambda, 599.8, 37.9, 31.0) + 0.362 * cieLobe(lambda, 442.0, 16.0, 26.7) -
              0.065 * cieLobe(lambda, 501.1, 20.4, 26.2);
    float y = 0.821 * cieLobe(lambda, 568.8, 46.9, 40.5) + 0.286 * cieLobe(lambda, 530.9, 16.3, 31.1);
    float z = 1.217 * cieLobe(lambda, 437.0, 11.8, 36.0) + 0.681 * cieLobe(lambda, 459.0, 26.0, 13.8);
    return vec3(x, y, z);
}

// The RGB weight of one wavelength sample; its mean over the range is (1, 1, 1).
vec3 wavelengthWeight(float lambda) {
    const mat3 xyzToRec709 =
        mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.0415560, 1.0572252);
    // The clipped RGB's mean over [380, 780] nm (midpoint rule, 400,000 points).
    const vec3 mean = vec3(0.44044331, 0.28846392, 0.27329614);
    return max(xyzToRec709 * cieXyz(lambda), vec3(0.0)) / mean;
}

// KHR_materials_dispersion: Cauchy's two terms fitted to the Abbe number V = 20 / dispersion at
// the d line, n(lambda) = max(n_d + (n_d - 1) / V (523655 / lambda^2 - 1.5168), 1).
float dispersedIor(float ior, float dispersion, float lambda) {
    return max(ior + (ior - 1.0) * (dispersion / 20.0) * (523655.0 / (lambda * lambda) - 1.5168), 1.0);
}

#endif
