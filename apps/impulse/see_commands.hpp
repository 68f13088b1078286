// SPDX-License-Identifier: MIT
// The subcommands that show a run: plot, render, view.
#pragma once

#include "plot_command.hpp"
#include "render_command.hpp"
#include "view_command.hpp"

#include <CLI/CLI.hpp>

#include <optional>

namespace impulse::app
{

/// Registers plot, render and view on the application; options are bound to its members, so it
/// stays where it was built.
class SeeCommands
{
  public:
    explicit SeeCommands(CLI::App& app);
    SeeCommands(const SeeCommands&) = delete;
    SeeCommands& operator=(const SeeCommands&) = delete;

    /// After parsing: the exit code of the subcommand chosen, if it is one of these.
    std::optional<int> runChosen() const;

  private:
    PlotOptions m_plot;
    RenderOptions m_render;
    ViewOptions m_view;
    bool m_noVideo = false;
    bool m_noRenderProgress = false;
    CLI::App* m_plotCommand = nullptr;
    CLI::App* m_renderCommand = nullptr;
    CLI::App* m_viewCommand = nullptr;
};

} // namespace impulse::app
