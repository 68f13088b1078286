// SPDX-License-Identifier: MIT
// Test support: a reference pile's oracle (support/pile_oracle.hpp) run in one go as a GoogleTest
// test, with its figures every simulated second and at the end on standard output.
#pragma once

#include "support/pile_oracle.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace impulse::test
{

/// Runs the pile's oracle to the end and expects it to hold; returns its figures.
inline PileFigures expectPileOracleHolds(const std::string& name)
{
    const ReferencePile* pile = findReferencePile(name);
    if (pile == nullptr)
    {
        ADD_FAILURE() << name << " is not a reference pile";
        return {};
    }
    PileRun run = referencePileRun(*pile);
    while (!run.finished())
    {
        run.step(std::cout);
    }
    if (run.failure().has_value())
    {
        ADD_FAILURE() << *run.failure();
        return run.figures();
    }
    std::cout << name << " at the end: kinetic energy " << run.world().kineticEnergy() << " J (peak "
              << run.figures().peakKinetic << ")" << std::endl;
    for (const PileCheck& check : run.finalChecks())
    {
        std::cout << name << ": " << check.what << " " << check.value << ", limit " << check.limit << std::endl;
        EXPECT_LT(check.value, check.limit) << name << ": " << check.what;
    }
    return run.figures();
}

} // namespace impulse::test
