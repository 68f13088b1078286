// SPDX-License-Identifier: MIT
#include "stop_request.hpp"

namespace impulse::app
{
namespace
{

volatile std::sig_atomic_t caught = 0;

extern "C" void onStopSignal(int number)
{
    caught = number;
}

} // namespace

StopRequest::StopRequest()
{
    caught = 0;
    struct sigaction action
    {
    };
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &m_previousInt);
    sigaction(SIGTERM, &action, &m_previousTerm);
}

StopRequest::~StopRequest()
{
    sigaction(SIGINT, &m_previousInt, nullptr);
    sigaction(SIGTERM, &m_previousTerm, nullptr);
}

int StopRequest::signal() const
{
    return caught;
}

const char* StopRequest::name() const
{
    return caught == SIGINT ? "Ctrl-C" : "SIGTERM";
}

} // namespace impulse::app
