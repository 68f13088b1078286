// SPDX-License-Identifier: MIT
// Loops whose iterations touch disjoint data, run on several threads with OpenMP when the build
// has it. OpenMP comes with the compiler (no library to install), and its static loops need no
// task graph: each iteration writes only its own bodies, islands or slots, so the results do not
// depend on which thread ran what, and the world stays bit-identical at any thread count.
#pragma once

#include <cstddef>
#include <thread>

#ifdef IMPULSE_HAVE_OPENMP
#include <omp.h>
#endif

namespace impulse
{

/// Threads to use for `requested` (0: one per hardware thread); 1 when built without OpenMP.
inline int resolveThreadCount(int requested)
{
#ifdef IMPULSE_HAVE_OPENMP
    if (requested > 0)
    {
        return requested;
    }
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware > 0 ? static_cast<int>(hardware) : 1;
#else
    (void)requested;
    return 1;
#endif
}

/// Calls work(i, thread) for i in [0, count), `thread` in [0, threads) naming the caller's scratch.
/// Iterations are handed out one at a time (they may differ widely in cost, as islands do).
template <class Work> void parallelFor(int threads, std::size_t count, Work&& work)
{
#ifdef IMPULSE_HAVE_OPENMP
    if (threads > 1 && count > 1)
    {
        const auto n = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
        for (std::ptrdiff_t i = 0; i < n; ++i)
        {
            work(static_cast<std::size_t>(i), omp_get_thread_num());
        }
        return;
    }
#endif
    (void)threads;
    for (std::size_t i = 0; i < count; ++i)
    {
        work(i, 0);
    }
}

/// As parallelFor, for many cheap iterations of equal cost (per-body updates): handed out in
/// contiguous blocks, one per thread.
template <class Work> void parallelForEach(int threads, std::size_t count, Work&& work)
{
#ifdef IMPULSE_HAVE_OPENMP
    if (threads > 1 && count > 256)
    {
        const auto n = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for num_threads(threads) schedule(static)
        for (std::ptrdiff_t i = 0; i < n; ++i)
        {
            work(static_cast<std::size_t>(i));
        }
        return;
    }
#endif
    (void)threads;
    for (std::size_t i = 0; i < count; ++i)
    {
        work(i);
    }
}

} // namespace impulse
