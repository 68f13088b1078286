// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <vector>

namespace impulse
{

/// "body rests on support": the directed edge support -> body of the contact graph.
struct SupportEdge
{
    std::uint32_t support = 0;
    std::uint32_t body = 0;
};

/// Levels of the contact graph (GBF03 sec. 8): every support lies in a strictly lower level than
/// the bodies resting on it, except bodies that rest on each other in a cycle, which share one.
///
/// Strongly connected components (Tarjan) collapse the cycles; on the resulting DAG each
/// component's level is 1 + the highest level of the components it rests on (longest path from
/// the ground), 0 for those resting on nothing or on static bodies only. Breadth-first distance
/// from the ground is not used: it can place a lintel across unequal stacks below the top of the
/// taller stack, and freezing in that order deadlocks.
///
/// `isDynamic[i]` tells which bodies take part; static bodies get level -1. Deterministic: the
/// result depends only on the edge set, not on its order.
std::vector<int> computeContactLevels(const std::vector<bool>& isDynamic, const std::vector<SupportEdge>& edges);

} // namespace impulse
