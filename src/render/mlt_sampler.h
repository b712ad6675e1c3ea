// The state of one primary-sample-space Markov chain (Kelemen, Szirmay-Kalos, Antal and
// Csonka 2002, "A Simple and Robust Mutation Strategy for the Metropolis Light Transport
// Algorithm"; pbrt-v3 16.4.3 describes the same sampler): a vector of uniform values in
// [0, 1), one per dimension a bidirectional path draws (render/bdpt_vertex.h BdptSamples),
// created and mutated lazily, when a path evaluation first asks for a dimension in an
// iteration. A proposal is either a large step (every value drawn afresh) or a small step
// (each value moved by a normal perturbation of standard deviation sigma, wrapped around
// [0, 1)); Reject restores the values the proposal changed. The chain's random numbers are
// its own PCG32, so a chain is a pure function of its seed.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "render/bdpt_vertex.h"

namespace prism {

class MltSampler final : public BdptSamples {
  public:
    MltSampler(uint64_t seed, float sigma) : rng_(seed, 0x4d4c5453u), sigma_(sigma) {}

    // Begins the next proposal, a large step or a small one.
    void StartIteration(bool largeStep);
    // The proposal becomes the chain's state, or is undone.
    void Accept();
    void Reject();

    float Get1D(uint32_t dim) const override;
    Vec2f Get2D(uint32_t dim) const override;

  private:
    struct Value {
        float value = 0, backup = 0;
        int64_t modified = 0, backupModified = 0;  // the iteration that last set it
    };
    // The values of dimension dim (two, for 2-D draws): camera and light dimensions interleave.
    static size_t Index(uint32_t dim);
    // Value i brought up to the current iteration.
    float Ready(size_t i) const;
    float Normal() const;

    mutable PCG32 rng_;
    mutable std::vector<Value> x_;
    float sigma_;
    int64_t iteration_ = 0, lastLargeStep_ = 0;
    bool largeStep_ = true;
};

}  // namespace prism
