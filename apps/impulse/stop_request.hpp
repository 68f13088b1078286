// SPDX-License-Identifier: MIT
// Ctrl-C and SIGTERM as a request to stop at the next whole sample, for the commands that write
// files as they go (run, render).
#pragma once

#include <csignal>

namespace impulse::app
{

/// While alive, SIGINT and SIGTERM set a flag instead of ending the process; the previous handlers
/// come back when it is destroyed. One at a time.
class StopRequest
{
  public:
    StopRequest();
    ~StopRequest();
    StopRequest(const StopRequest&) = delete;
    StopRequest& operator=(const StopRequest&) = delete;

    /// The signal caught (SIGINT or SIGTERM), or 0 while none was.
    int signal() const;
    /// The exit code of a process ended by that signal: 128 + its number.
    int exitCode() const { return 128 + signal(); }
    /// "Ctrl-C" or "SIGTERM".
    const char* name() const;

  private:
    struct sigaction m_previousInt
    {
    };
    struct sigaction m_previousTerm
    {
    };
};

} // namespace impulse::app
