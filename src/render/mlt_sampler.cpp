#include "render/mlt_sampler.h"

#include <algorithm>
#include <cmath>

namespace prism {

void MltSampler::StartIteration(bool largeStep) {
    ++iteration_;
    largeStep_ = largeStep;
}

void MltSampler::Accept() {
    if (largeStep_) lastLargeStep_ = iteration_;
}

void MltSampler::Reject() {
    for (Value &v : x_)
        if (v.modified == iteration_) v.value = v.backup, v.modified = v.backupModified;
    // The rejected proposal never happened: small steps count accepted states only.
    --iteration_;
}

size_t MltSampler::Index(uint32_t dim) {
    const bool light = dim >= (1u << 16);
    const size_t d = light ? dim - (1u << 16) : dim;
    return 4 * d + (light ? 2 : 0);
}

float MltSampler::Normal() const {
    const float u1 = 1 - rng_.Uniform(), u2 = rng_.Uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * float(Pi) * u2);
}

float MltSampler::Ready(size_t i) const {
    // A value never drawn is a uniform one drawn at the last accepted large step.
    if (i >= x_.size()) x_.resize(i + 1, Value{0, 0, -1, -1});
    Value &v = x_[i];
    if (v.modified < lastLargeStep_) {
        v.value = rng_.Uniform();
        v.modified = lastLargeStep_;
    }
    if (v.modified < iteration_) {
        v.backup = v.value;
        v.backupModified = v.modified;
        if (largeStep_) {
            v.value = rng_.Uniform();
        } else {
            // The small steps since the value last changed, as one normal step.
            const float n = float(iteration_ - v.modified);
            v.value += Normal() * sigma_ * std::sqrt(n);
            v.value -= std::floor(v.value);
            v.value = std::clamp(v.value, 0.f, 0x1.fffffep-1f);
        }
        v.modified = iteration_;
    }
    return v.value;
}

float MltSampler::Get1D(uint32_t dim) const { return Ready(Index(dim)); }

Vec2f MltSampler::Get2D(uint32_t dim) const {
    const size_t i = Index(dim);
    const float a = Ready(i);
    return Vec2f(a, Ready(i + 1));
}

}  // namespace prism
