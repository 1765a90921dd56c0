#pragma once
// Runs the same soft simulation on 1 and on 2 OpenMP threads and expects bit-identical
// positions, directors and image counters: what the engine promises for any thread count.
#include "pedesis/soft/soft_state.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>

namespace pedesis::test {

// run() builds and runs the simulation, returning its final state.
template <int D, class Run> void expect_thread_independent(Run run) {
    omp_set_num_threads(1);
    const SoftState<D> one = run();
    omp_set_num_threads(2);
    const SoftState<D> two = run();
    omp_set_num_threads(1);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(
        std::memcmp(one.p.position.data(), two.p.position.data(), one.size() * sizeof(Vec<D>)), 0);
    EXPECT_EQ(std::memcmp(one.director.data(), two.director.data(), one.size() * sizeof(Vec<D>)),
              0);
    EXPECT_EQ(std::memcmp(one.image.data(), two.image.data(), one.size() * sizeof(one.image[0])),
              0);
}

} // namespace pedesis::test
