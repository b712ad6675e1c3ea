// Exposure and tone mapping: what turns a rendered (linear, unbounded) image into what an 8-bit
// display file stores. Exposure scales by 2^EV; the operators map linear Rec. 709 radiance to
// linear [0,1], which the PNG writer then encodes with the sRGB curve. Float outputs (EXR, PFM,
// HDR) stay linear: they get the exposure only (ApplyOutputTransform).
#pragma once

#include <string>

#include "core/color.h"
#include "image/image.h"

namespace prism {

enum class ToneMap {
    None,     // clamp to [0,1], as pbrt-v3 writes 8-bit images
    Neutral,  // Khronos PBR Neutral (the glTF sample viewer's default)
    Aces,     // Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab "ACESFitted")
    Filmic,   // John Hable's Uncharted 2 curve, exposure bias 2, white point 11.2
};

// "none", "neutral", "aces", "filmic" → the operator; false for any other name.
bool ParseToneMap(const std::string &name, ToneMap *op);
const char *ToneMapName(ToneMap op);

// Each operator on one linear colour (non-negative input; negative components are treated as 0).
// The results lie in [0,1] (None clamps).
RGB ToneMapNeutral(const RGB &c);
RGB ToneMapAces(const RGB &c);
RGB ToneMapFilmic(const RGB &c);
RGB ApplyToneMap(ToneMap op, const RGB &c);

// What is done to the rendered image before it is written.
struct OutputTransform {
    float exposure = 0;  // EV: pixels are scaled by 2^exposure
    ToneMap toneMap = ToneMap::None;
    // Exposure "auto": `exposure` is chosen from the image (ResolveAutoExposure).
    bool autoExposure = false;
};

// The exposure that maps the image's log-average luminance (Reinhard et al. 2002: exp of the
// mean of log(1e-4 + Y) over the pixels that are not black, so an empty background does not
// count) to middle grey 0.18, in EV, within [-20, 20]; 0 for an empty or black image.
float AutoExposureEV(const Image &img);
// With t.autoExposure, sets t.exposure to AutoExposureEV(img) (and leaves it alone otherwise).
void ResolveAutoExposure(OutputTransform &t, const Image &img);
// "auto" or a number of EV in [-64, 64]; false for anything else.
bool ParseExposure(const std::string &text, float *ev, bool *isAuto);

// Applies `t` in place: the exposure to every colour channel (never to alpha); the tone map too
// unless `linearOutput` (float formats keep linear radiance). Exposure 0 with None changes
// nothing, bit for bit.
void ApplyOutputTransform(Image &img, const OutputTransform &t, bool linearOutput);

}  // namespace prism
