#include "commands.h"

namespace refx::cli {

Action addReplayCommand(CLI::App& app) {
  app.add_subcommand("replay", "(not implemented yet)");
  return [] { return 1; };
}

}  // namespace refx::cli
