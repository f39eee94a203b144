// `tandem render` and `tandem view`: pictures and videos with no display, and the interactive
// viewer. Built only when the rendering libraries are there (TANDEM_HAS_RENDER).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace tandem::cli {

// Adds the `render` and `view` subcommands; the returned function runs whichever was parsed
// and returns the exit status, or -1 when neither was.
std::function<int()> addRenderCommands(CLI::App& app);

}  // namespace tandem::cli
