// The directive status tables of docs/PBRT3_STATUS.md and docs/PBRT4_STATUS.md, and the probe
// scenes their tests build: one row per (directive, type), with what Prism does with it.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace prism::test {

using StatusKey = std::pair<std::string, std::string>;  // (directive, type or "—")

// A probe of a directive without a type that pbrt-v3 and pbrt-v4 share (transforms,
// attributes, instances, Include): text to put in the world block, before WorldBegin, or
// before the Camera.
struct SharedProbe {
    enum class Where { World, Options, BeforeCamera };
    std::string directive;
    Where where;
    std::string text;
};
std::vector<SharedProbe> SharedDirectiveProbes();
// Puts `sp` into a probe's parts (a struct with world, options and camera strings).
template <class Parts>
void ApplySharedProbe(const SharedProbe &sp, Parts &x) {
    if (sp.where == SharedProbe::Where::World) x.world = sp.text;
    if (sp.where == SharedProbe::Where::Options) x.options = sp.text;
    if (sp.where == SharedProbe::Where::BeforeCamera) x.camera = sp.text + x.camera;
}

// The rows "| directive | type | status | ... |" of the table in the file `doc` (relative to
// the source tree): status by key. A key listed twice is a test failure.
std::map<StatusKey, std::string> StatusTableRows(const std::string &doc);

// The files the probes read (lens.dat, part.pbrt, quad.ply, t.png, env.exr, m.bsdf: a
// Lambertian table), written in `dir`.
void WriteStatusProbeInputs(const std::filesystem::path &dir);

// What Prism does with a probe scene written in `dir`: "rejected" (an error), "warned" or
// "simulated", and the first message, for the failure report.
std::pair<std::string, std::string> ObserveStatusProbe(const std::filesystem::path &dir,
                                                       const std::string &text);

// Checks that `doc` lists exactly the keys of `probes` and that each probe's scene builds as
// its row says.
void CheckStatusTable(const std::string &doc, const std::string &scratch,
                      const std::map<StatusKey, std::string> &probes);

}  // namespace prism::test
