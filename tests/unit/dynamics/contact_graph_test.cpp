// SPDX-License-Identifier: MIT
#include "dynamics/contact_graph.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace impulse
{
namespace
{

// body 0 is static (the ground) in every case below
std::vector<bool> groundAnd(std::size_t dynamicCount)
{
    std::vector<bool> isDynamic(dynamicCount + 1, true);
    isDynamic[0] = false;
    return isDynamic;
}

TEST(ContactGraph, StackGetsOneLevelPerBody)
{
    // ground <- 1 <- 2 <- 3
    const std::vector<int> levels = computeContactLevels(groundAnd(3), {{0, 1}, {1, 2}, {2, 3}});
    EXPECT_EQ(levels, (std::vector<int>{-1, 0, 1, 2}));
}

TEST(ContactGraph, BodiesRestingOnEachOtherShareALevel)
{
    // 1 and 2 lean on each other (a cycle); 3 rests on 2
    const std::vector<int> levels = computeContactLevels(groundAnd(3), {{0, 1}, {0, 2}, {1, 2}, {2, 1}, {2, 3}});
    EXPECT_EQ(levels[1], levels[2]);
    EXPECT_EQ(levels[3], levels[2] + 1);
}

TEST(ContactGraph, LintelAcrossUnequalStacksLiesAboveBothTops)
{
    // left stack 1-2, right stack 3-4-5-6, lintel 7 on 2 and 6: breadth-first distance from the
    // ground would give the lintel level 2, below box 6 (level 3); the lintel must be above it
    const std::vector<int> levels =
        computeContactLevels(groundAnd(7), {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {4, 5}, {5, 6}, {2, 7}, {6, 7}});
    EXPECT_EQ(levels[6], 3);
    EXPECT_EQ(levels[7], 4);
    EXPECT_GT(levels[7], levels[2]);
}

TEST(ContactGraph, EverySupportLiesBelowWhatItHolds)
{
    const std::vector<SupportEdge> edges{{0, 1}, {0, 2}, {1, 3}, {2, 3}, {3, 4}, {1, 5}, {5, 4}, {4, 6}};
    const std::vector<int> levels = computeContactLevels(groundAnd(6), edges);
    for (const SupportEdge& edge : edges)
    {
        if (edge.support != 0)
        {
            EXPECT_LT(levels[edge.support], levels[edge.body]) << edge.support << " -> " << edge.body;
        }
    }
}

TEST(ContactGraph, LevelsDoNotDependOnEdgeOrder)
{
    std::vector<SupportEdge> edges{{0, 1}, {1, 2}, {2, 3}, {3, 2}, {0, 4}, {4, 5}, {2, 5}};
    const std::vector<int> expected = computeContactLevels(groundAnd(5), edges);
    std::reverse(edges.begin(), edges.end());
    EXPECT_EQ(computeContactLevels(groundAnd(5), edges), expected);
    std::rotate(edges.begin(), edges.begin() + 3, edges.end());
    EXPECT_EQ(computeContactLevels(groundAnd(5), edges), expected);
}

TEST(ContactGraph, DeepChainDoesNotOverflowTheStack)
{
    const std::size_t n = 100000;
    std::vector<SupportEdge> edges;
    for (std::uint32_t i = 0; i < n; ++i)
    {
        edges.push_back({i, i + 1});
    }
    const std::vector<int> levels = computeContactLevels(groundAnd(n), edges);
    EXPECT_EQ(levels.back(), static_cast<int>(n) - 1);
}

} // namespace
} // namespace impulse
