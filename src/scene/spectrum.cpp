#include "scene/spectrum.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/file_io.h"
#include "core/memory.h"

namespace prism {

// Piecewise Gaussian of Wyman et al. 2013: separate widths left and right of the mean, given
// as the inverse standard deviations the paper tabulates.
static double Lobe(double lambda, double mu, double invSigmaLeft, double invSigmaRight) {
    double t = (lambda - mu) * (lambda < mu ? invSigmaLeft : invSigmaRight);
    return std::exp(-0.5 * t * t);
}

double CIEXBar(double lambda) {
    return 1.056 * Lobe(lambda, 599.8, 0.0264, 0.0323) +
           0.362 * Lobe(lambda, 442.0, 0.0624, 0.0374) -
           0.065 * Lobe(lambda, 501.1, 0.0490, 0.0382);
}

double CIEYBar(double lambda) {
    return 0.821 * Lobe(lambda, 568.8, 0.0213, 0.0247) +
           0.286 * Lobe(lambda, 530.9, 0.0613, 0.0322);
}

double CIEZBar(double lambda) {
    return 1.217 * Lobe(lambda, 437.0, 0.0845, 0.0278) +
           0.681 * Lobe(lambda, 459.0, 0.0385, 0.0725);
}

namespace {

// The integration grid of pbrt's CIE tables: 1 nm steps over 360–830 nm.
constexpr int LambdaMin = 360, LambdaMax = 830, NumSamples = LambdaMax - LambdaMin + 1;

struct CMFTable {
    std::array<double, NumSamples> x, y, z;
    double yIntegral = 0;
    CMFTable() {
        for (int i = 0; i < NumSamples; ++i) {
            double l = LambdaMin + i;
            x[i] = CIEXBar(l);
            y[i] = CIEYBar(l);
            z[i] = CIEZBar(l);
            yIntegral += y[i];
        }
    }
};

const CMFTable &Table() {
    static const CMFTable table;
    return table;
}

// XYZ of a spectrum evaluated by `eval` on the table grid, normalized so Y of a flat 1 is 1.
template <typename F>
RGB IntegrateToRGB(F eval) {
    const CMFTable &t = Table();
    double x = 0, y = 0, z = 0;
    for (int i = 0; i < NumSamples; ++i) {
        double v = eval(double(LambdaMin + i));
        x += v * t.x[i];
        y += v * t.y[i];
        z += v * t.z[i];
    }
    return XYZToRGB(x / t.yIntegral, y / t.yIntegral, z / t.yIntegral);
}

// Planck's law: spectral radiance at lambda (nm) for temperature T (K), in W/(sr m^2 m).
double Planck(double lambdaNm, double T) {
    constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = lambdaNm * 1e-9;
    double l5 = (l * l) * (l * l) * l;
    return (2 * h * c * c) / (l5 * std::expm1((h * c) / (l * kb * T)));
}

}  // namespace

RGB XYZToRGB(double x, double y, double z) {
    return {float(3.2404542 * x - 1.5371385 * y - 0.4985314 * z),
            float(-0.9692660 * x + 1.8760108 * y + 0.0415560 * z),
            float(0.0556434 * x - 0.2040259 * y + 1.0572252 * z)};
}

RGB SampledToRGB(std::vector<std::pair<double, double>> samples) {
    if (samples.empty()) return RGB(0.f);
    if (!std::is_sorted(samples.begin(), samples.end()))
        std::stable_sort(samples.begin(), samples.end(),
                         [](const auto &a, const auto &b) { return a.first < b.first; });
    size_t seg = 0;  // grid wavelengths increase, so the segment search only moves forward
    return IntegrateToRGB([&](double l) {
        if (l <= samples.front().first) return samples.front().second;
        if (l >= samples.back().first) return samples.back().second;
        while (samples[seg + 1].first < l) ++seg;
        const auto &[l0, v0] = samples[seg];
        const auto &[l1, v1] = samples[seg + 1];
        double t = l1 > l0 ? (l - l0) / (l1 - l0) : 0.0;
        return v0 + t * (v1 - v0);
    });
}

RGB BlackbodyToRGB(double temperatureK, double scale) {
    if (!(temperatureK > 0) || !std::isfinite(temperatureK)) return RGB(0.f);
    // Wien's displacement law gives the peak wavelength; pbrt-v3 normalizes by the radiance
    // there even when the peak lies outside the visible range.
    double peakNm = 2.8977721e-3 / temperatureK * 1e9;
    double peak = Planck(peakNm, temperatureK);
    if (!(peak > 0) || !std::isfinite(peak)) return RGB(0.f);
    RGB rgb = IntegrateToRGB([&](double l) { return Planck(l, temperatureK) / peak; });
    return rgb * float(scale);
}

std::optional<RGB> ReadSpdFile(const std::string &path, const std::string &displayName,
                               std::string *error, const MemoryBudget *budget, const FileLoc &loc) {
    std::string text;
    FileReadError readError;
    const uint64_t maxBytes =
        budget ? budget->Remaining() / kSpdBytesPerFileByte : std::numeric_limits<uint64_t>::max();
    if (!ReadFileContents(path, &text, &readError, maxBytes)) {
        if (readError.tooLarge && budget)
            budget->Check(readError.size * kSpdBytesPerFileByte,
                          "spectrum file " + Quote(displayName), loc);  // throws

        *error = "cannot open spectrum file " + Quote(displayName) + ": " + readError.reason;
        return std::nullopt;
    }
    std::vector<double> values;
    bool ok = true;
    size_t i = 0;
    while (i < text.size() && ok) {
        char c = text[i];
        if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
            ++i;
        } else {
            const char *first = text.data() + i, *last = text.data() + text.size();
            if (*first == '+') ++first;
            double v;
            auto [ptr, ec] = std::from_chars(first, last, v);
            if (ec != std::errc() || !std::isfinite(v))
                ok = false;
            else
                values.push_back(v);
            i = size_t(ptr - text.data());
        }
    }
    if (!ok || values.size() < 2 || values.size() % 2 != 0) {
        *error = "cannot read spectrum file " + Quote(displayName) +
                 ": expected (wavelength, value) pairs";
        return std::nullopt;
    }
    std::vector<std::pair<double, double>> samples(values.size() / 2);
    for (size_t k = 0; k < samples.size(); ++k) samples[k] = {values[2 * k], values[2 * k + 1]};
    return SampledToRGB(std::move(samples));
}

}  // namespace prism
