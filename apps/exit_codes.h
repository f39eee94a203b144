// The `tandem` command's exit statuses (README, docs/reliability.md): a script can tell a bad
// command line from a bad file, a simulation that blew up from one that tore, and both from a
// disk that would not take the output.
#pragma once

namespace tandem::cli {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitOther = 1,       // anything else: no display for the viewer, no OpenGL, an internal error
  kExitUsage = 2,       // a bad command line: unknown command or option, a value out of range
  kExitBadInput = 3,    // a scene (file or name) or mesh that is missing, unreadable, invalid or too large
  kExitDiverged = 4,    // the simulation diverged: a step failed (non-finite or faster than divergence_speed)
  kExitViolated = 5,    // the run finished, but rows were left violated (an anchor torn, an edge overstretched)
  kExitOutputFailed = 6,  // the record, picture or video could not be written
};

}  // namespace tandem::cli
