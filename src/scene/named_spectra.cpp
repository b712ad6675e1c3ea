#include "scene/named_spectra.h"

#include <algorithm>
#include <array>
#include <span>

#include "scene/spectrum.h"

namespace prism {

namespace {

// One tabulated sample of a complex index of refraction.
struct NK {
    double lambdaUm, n, k;
};

// Measured optical constants over the visible range (and one sample past each end), from the
// refractiveindex.info database, which is in the public domain (CC0): Ag, Au and Cu from
// P. B. Johnson and R. W. Christy, Phys. Rev. B 6, 4370 (1972); Al from A. D. Rakic, Appl.
// Opt. 34, 4755 (1995); CuZn (brass, 70% Cu) from M. R. Querry, CRDC-CR-85034 (1985), every
// 20 nm.
constexpr NK kSilver[] = {{0.3542, 0.10, 1.419}, {0.3679, 0.07, 1.657}, {0.3815, 0.05, 1.864},
                          {0.3974, 0.05, 2.070}, {0.4133, 0.05, 2.275}, {0.4305, 0.04, 2.462},
                          {0.4509, 0.04, 2.657}, {0.4714, 0.05, 2.869}, {0.4959, 0.05, 3.093},
                          {0.5209, 0.05, 3.324}, {0.5486, 0.06, 3.586}, {0.5821, 0.05, 3.858},
                          {0.6168, 0.06, 4.152}, {0.6595, 0.05, 4.483}, {0.7045, 0.04, 4.838},
                          {0.7560, 0.03, 5.242}, {0.8211, 0.04, 5.727}, {0.8920, 0.04, 6.312}};
constexpr NK kGold[] = {{0.3542, 1.50, 1.866}, {0.3679, 1.48, 1.895}, {0.3815, 1.46, 1.933},
                        {0.3974, 1.47, 1.952}, {0.4133, 1.46, 1.958}, {0.4305, 1.45, 1.948},
                        {0.4509, 1.38, 1.914}, {0.4714, 1.31, 1.849}, {0.4959, 1.04, 1.833},
                        {0.5209, 0.62, 2.081}, {0.5486, 0.43, 2.455}, {0.5821, 0.29, 2.863},
                        {0.6168, 0.21, 3.272}, {0.6595, 0.14, 3.697}, {0.7045, 0.13, 4.103},
                        {0.7560, 0.14, 4.542}, {0.8211, 0.16, 5.083}, {0.8920, 0.17, 5.663}};
constexpr NK kCopper[] = {{0.3542, 1.37, 1.916}, {0.3679, 1.36, 1.975}, {0.3815, 1.33, 2.045},
                          {0.3974, 1.32, 2.116}, {0.4133, 1.28, 2.207}, {0.4305, 1.25, 2.305},
                          {0.4509, 1.24, 2.397}, {0.4714, 1.25, 2.483}, {0.4959, 1.22, 2.564},
                          {0.5209, 1.18, 2.608}, {0.5486, 1.02, 2.577}, {0.5821, 0.70, 2.704},
                          {0.6168, 0.30, 3.205}, {0.6595, 0.22, 3.747}, {0.7045, 0.21, 4.205},
                          {0.7560, 0.24, 4.665}, {0.8211, 0.26, 5.180}, {0.8920, 0.30, 5.768}};
constexpr NK kAluminium[] = {
    {0.32628, 0.31474, 3.9165}, {0.36466, 0.39877, 4.3957}, {0.41328, 0.52135, 5.0008},
    {0.44280, 0.60790, 5.3676}, {0.47687, 0.72780, 5.7781}, {0.51660, 0.87340, 6.2418},
    {0.56357, 1.0728, 6.7839},  {0.61993, 1.3660, 7.4052},  {0.65225, 1.5724, 7.7354},
    {0.68881, 1.8301, 8.0601},  {0.72932, 2.1606, 8.3565},  {0.77491, 2.6154, 8.4914},
    {0.79478, 2.7675, 8.3866},  {0.81569, 2.7668, 8.2573},  {0.83774, 2.6945, 8.1878}};
constexpr NK kBrass[] = {
    {0.36, 1.503, 1.815}, {0.38, 1.487, 1.818}, {0.40, 1.445, 1.805}, {0.42, 1.350, 1.786},
    {0.44, 1.191, 1.797}, {0.46, 0.994, 1.883}, {0.48, 0.816, 2.046}, {0.50, 0.686, 2.250},
    {0.52, 0.602, 2.464}, {0.54, 0.549, 2.668}, {0.56, 0.505, 2.860}, {0.58, 0.468, 3.059},
    {0.60, 0.450, 3.253}, {0.62, 0.449, 3.434}, {0.64, 0.444, 3.609}, {0.66, 0.445, 3.778},
    {0.68, 0.444, 3.943}, {0.70, 0.446, 4.106}, {0.72, 0.450, 4.266}, {0.74, 0.455, 4.424},
    {0.76, 0.458, 4.579}, {0.78, 0.464, 4.737}, {0.80, 0.473, 4.890}, {0.82, 0.481, 5.039},
    {0.84, 0.486, 5.192}};

struct Metal {
    std::string_view name;  // "Cu": the spectra "metal-Cu-eta" and "metal-Cu-k"
    std::span<const NK> table;
};
constexpr Metal kMetals[] = {
    {"Ag", kSilver}, {"Al", kAluminium}, {"Au", kGold}, {"Cu", kCopper}, {"CuZn", kBrass}};

// Glasses by their catalogue indices at the Fraunhofer F, d and C lines (486.1, 587.6 and
// 656.3 nm; Schott's data sheets), between which a Cauchy curve n = A + B / lambda^2 is fitted.
// pbrt-v4's "glass-F5", "-F10" and "-F11" are Schott's SF5, SF10 and SF11 (both spellings
// are accepted).
struct Glass {
    std::string_view name;
    double nF, nd, nC;
};
constexpr Glass kGlasses[] = {
    {"BK7", 1.52238, 1.51680, 1.51432},   {"BAF10", 1.68000, 1.67003, 1.66578},
    {"FK51A", 1.49056, 1.48656, 1.48480}, {"LASF9", 1.86898, 1.85025, 1.84255},
    {"F5", 1.68750, 1.67271, 1.66664},    {"SF5", 1.68750, 1.67271, 1.66664},
    {"F10", 1.74643, 1.72828, 1.72091},   {"SF10", 1.74643, 1.72828, 1.72091},
    {"F11", 1.80651, 1.78472, 1.77596},   {"SF11", 1.80651, 1.78472, 1.77596}};

// Illuminants by their CIE 1931 chromaticities (CIE 15:2004, table T.3 and T.8; ACES's D60
// from SMPTE ST 2065-1).
struct Illuminant {
    std::string_view name;
    double x, y;
};
constexpr Illuminant kIlluminants[] = {
    {"stdillum-A", 0.44757, 0.40745},   {"stdillum-D50", 0.34567, 0.35850},
    {"stdillum-D65", 0.31271, 0.32902}, {"illum-acesD60", 0.32168, 0.33767},
    {"stdillum-F1", 0.31310, 0.33727},  {"stdillum-F2", 0.37208, 0.37529},
    {"stdillum-F3", 0.40910, 0.39430},  {"stdillum-F4", 0.44018, 0.40329},
    {"stdillum-F5", 0.31379, 0.34531},  {"stdillum-F6", 0.37790, 0.38835},
    {"stdillum-F7", 0.31292, 0.32933},  {"stdillum-F8", 0.34588, 0.35875},
    {"stdillum-F9", 0.37417, 0.37281},  {"stdillum-F10", 0.34609, 0.35986},
    {"stdillum-F11", 0.38052, 0.37713}, {"stdillum-F12", 0.43695, 0.40441}};

// pbrt-v4 names these too; Prism has no data for them.
constexpr std::string_view kNotBuiltIn[] = {"metal-MgO-eta", "metal-MgO-k", "metal-TiO2-eta",
                                            "metal-TiO2-k"};

// A spectrum that is not a radiance (an index of refraction) as RGB: SampledToRGB divided,
// channel by channel, by SampledToRGB of the constant 1, so a constant keeps its value.
RGB UnboundedToRGB(std::vector<std::pair<double, double>> samples) {
    static const RGB flat = SampledToRGB({{360, 1}, {830, 1}});
    const RGB c = SampledToRGB(std::move(samples));
    return {c.r / flat.r, c.g / flat.g, c.b / flat.b};
}

RGB MetalRGB(std::span<const NK> table, bool k) {
    std::vector<std::pair<double, double>> s;
    for (const NK &e : table) s.push_back({e.lambdaUm * 1000, k ? e.k : e.n});
    return UnboundedToRGB(std::move(s));
}

RGB GlassRGB(const Glass &g) {
    // Cauchy through F and C: n = A + B / lambda^2, lambda in um.
    const double lF = 0.4861, lC = 0.6563;
    const double B = (g.nF - g.nC) / (1 / (lF * lF) - 1 / (lC * lC)), A = g.nC - B / (lC * lC);
    std::vector<std::pair<double, double>> s;
    for (int nm = 360; nm <= 830; nm += 10) {
        const double l = nm / 1000.0;
        s.push_back({double(nm), A + B / (l * l)});
    }
    return UnboundedToRGB(std::move(s));
}

// The built-in spectrum `name` names, found by the name alone (nothing is computed): one of
// a metal's two tables, a glass or an illuminant.
struct Found {
    const Metal *metal = nullptr;
    bool k = false;  // the metal's k rather than its eta
    const Glass *glass = nullptr;
    const Illuminant *illuminant = nullptr;
};

std::optional<Found> Find(std::string_view name) {
    if (name.starts_with("metal-")) {
        const std::string_view rest = name.substr(6);  // "Cu-eta"
        for (const Metal &m : kMetals) {
            if (!rest.starts_with(m.name)) continue;
            const std::string_view part = rest.substr(m.name.size());
            if (part == "-eta" || part == "-k") return Found{&m, part == "-k", nullptr, nullptr};
        }
    } else if (name.starts_with("glass-")) {
        for (const Glass &g : kGlasses)
            if (name.substr(6) == g.name) return Found{nullptr, false, &g, nullptr};
    } else {
        for (const Illuminant &i : kIlluminants)
            if (name == i.name) return Found{nullptr, false, nullptr, &i};
    }
    return std::nullopt;
}

bool NotBuiltIn(std::string_view name) {
    return std::find(std::begin(kNotBuiltIn), std::end(kNotBuiltIn), name) != std::end(kNotBuiltIn);
}

}  // namespace

bool IsNamedSpectrum(std::string_view name) { return Find(name) || NotBuiltIn(name); }

std::optional<RGB> NamedSpectrumRGB(std::string_view name, std::string *why) {
    if (const std::optional<Found> f = Find(name)) {
        if (f->metal) return MetalRGB(f->metal->table, f->k);
        if (f->glass) return GlassRGB(*f->glass);
        const Illuminant &i = *f->illuminant;
        return XYZToRGB(i.x / i.y, 1.0, (1 - i.x - i.y) / i.y);
    }
    if (why) {
        // Appended piece by piece: g++ 12 warns (-Wrestrict, falsely) of "..." + std::string.
        const bool pbrtName = NotBuiltIn(name);
        why->assign(pbrtName ? "pbrt-v4's named spectrum \"" : "\"");
        why->append(name);
        why->append(pbrtName ? "\" is not built into Prism" : "\" is not a named spectrum");
    }
    return std::nullopt;
}

std::vector<std::string> BuiltInSpectrumNames() {
    std::vector<std::string> names;
    for (const Metal &m : kMetals) {
        names.push_back("metal-" + std::string(m.name) + "-eta");
        names.push_back("metal-" + std::string(m.name) + "-k");
    }
    for (const Glass &g : kGlasses) names.push_back("glass-" + std::string(g.name));
    for (const Illuminant &i : kIlluminants) names.emplace_back(i.name);
    return names;
}

}  // namespace prism
