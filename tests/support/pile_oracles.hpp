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

inline void expectPileOracleHolds(const std::string& name)
{
    const ReferencePile* pile = findReferencePile(name);
    ASSERT_NE(pile, nullptr) << name << " is not a reference pile";
    PileRun run = referencePileRun(*pile);
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
