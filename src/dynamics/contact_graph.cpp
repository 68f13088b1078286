// SPDX-License-Identifier: MIT
#include "dynamics/contact_graph.hpp"

#include <algorithm>

namespace impulse
{
namespace
{

// Tarjan's strongly connected components, iterative so that tall stacks cannot overflow the call
// stack. Returns the component of every node; components come out in reverse topological order
// (a component is finished after everything reachable from it).
std::vector<int> stronglyConnectedComponents(const std::vector<std::vector<std::uint32_t>>& successors,
                                             int& componentCount)
{
    const std::size_t n = successors.size();
    constexpr int kUnvisited = -1;
    std::vector<int> index(n, kUnvisited);
    std::vector<int> lowLink(n, 0);
    std::vector<bool> onStack(n, false);
    std::vector<int> component(n, -1);
    std::vector<std::uint32_t> stack;
    struct Frame
    {
        std::uint32_t node;
        std::size_t next;
    };
    std::vector<Frame> calls;
    int counter = 0;
    componentCount = 0;

    for (std::uint32_t root = 0; root < n; ++root)
    {
        if (index[root] != kUnvisited)
        {
            continue;
        }
        calls.push_back({root, 0});
        index[root] = lowLink[root] = counter++;
        stack.push_back(root);
        onStack[root] = true;
        while (!calls.empty())
        {
            Frame& frame = calls.back();
            const std::uint32_t v = frame.node;
            if (frame.next < successors[v].size())
            {
                const std::uint32_t w = successors[v][frame.next++];
                if (index[w] == kUnvisited)
                {
                    index[w] = lowLink[w] = counter++;
                    stack.push_back(w);
                    onStack[w] = true;
                    calls.push_back({w, 0});
                }
                else if (onStack[w])
                {
                    lowLink[v] = std::min(lowLink[v], index[w]);
                }
                continue;
            }
            if (lowLink[v] == index[v])
            {
                std::uint32_t w = 0;
                do
                {
                    w = stack.back();
                    stack.pop_back();
                    onStack[w] = false;
                    component[w] = componentCount;
                } while (w != v);
                ++componentCount;
            }
            calls.pop_back();
            if (!calls.empty())
            {
                const std::uint32_t parent = calls.back().node;
                lowLink[parent] = std::min(lowLink[parent], lowLink[v]);
            }
        }
    }
    return component;
}

} // namespace

std::vector<int> computeContactLevels(const std::vector<bool>& isDynamic, const std::vector<SupportEdge>& edges)
{
    const std::size_t n = isDynamic.size();
    // successors among dynamic bodies only: a static support adds no level
    std::vector<std::vector<std::uint32_t>> successors(n);
    for (const SupportEdge& edge : edges)
    {
        if (isDynamic[edge.support] && isDynamic[edge.body] && edge.support != edge.body)
        {
            successors[edge.support].push_back(edge.body);
        }
    }
    for (auto& list : successors)
    {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }

    int componentCount = 0;
    const std::vector<int> component = stronglyConnectedComponents(successors, componentCount);

    // Tarjan finishes a component after all components reachable from it, so visiting components
    // from the last finished to the first is a topological order (supports before what they hold).
    std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(componentCount));
    for (std::uint32_t v = 0; v < n; ++v)
    {
        if (isDynamic[v])
        {
            members[static_cast<std::size_t>(component[v])].push_back(v);
        }
    }
    std::vector<int> componentLevel(static_cast<std::size_t>(componentCount), 0);
    for (int c = componentCount - 1; c >= 0; --c)
    {
        for (const std::uint32_t v : members[static_cast<std::size_t>(c)])
        {
            for (const std::uint32_t w : successors[v])
            {
                const int cw = component[w];
                if (cw != c)
                {
                    componentLevel[static_cast<std::size_t>(cw)] = std::max(
                        componentLevel[static_cast<std::size_t>(cw)], componentLevel[static_cast<std::size_t>(c)] + 1);
                }
            }
        }
    }

    std::vector<int> level(n, -1);
    for (std::uint32_t v = 0; v < n; ++v)
    {
        if (isDynamic[v])
        {
            level[v] = componentLevel[static_cast<std::size_t>(component[v])];
        }
    }
    return level;
}

} // namespace impulse
