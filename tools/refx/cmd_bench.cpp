#include "commands.h"

namespace refx::cli {

Action addBenchCommand(CLI::App& app) {
  app.add_subcommand("bench", "(not implemented yet)");
  return [] { return 1; };
}

}  // namespace refx::cli
