// SPDX-License-Identifier: MIT
// Test support: a reference pile's oracle (support/pile_oracle.hpp) run in one go as a GoogleTest
// test, with its figures every simulated second and at the end on standard output.
#pragma once

#include "support/pile_oracle.hpp"
#include "support/scene_run.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace impulse::test
{

inline void expectPileOracleHolds(const std::string& name, PileOracleKind kind, Real size = 0.0)
{
    PileRun run(loadReferenceScene(name), kind, size);
    if (kind == PileOracleKind::StaysInTheBox)
    {
        run.scene().options.threads = 0; // every core: the trajectory is the same at any thread count
    }
    while (!run.finished())
    {
        run.step(std::cout);
    }
    ASSERT_FALSE(run.failure().has_value()) << *run.failure();
    std::cout << name << " at the end: kinetic energy " << run.world().kineticEnergy() << " J (peak "
              << run.figures().peakKinetic << ")" << std::endl;
    for (const PileCheck& check : run.finalChecks())
    {
        std::cout << name << ": " << check.what << " " << check.value << ", limit " << check.limit << std::endl;
        EXPECT_LT(check.value, check.limit) << name << ": " << check.what;
    }
}

} // namespace impulse::test
