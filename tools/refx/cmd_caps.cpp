#include "commands.h"

namespace refx::cli {

Action addCapsCommand(CLI::App& app) {
  app.add_subcommand("caps", "(not implemented yet)");
  return [] { return 1; };
}

}  // namespace refx::cli
