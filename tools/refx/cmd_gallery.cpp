#include "commands.h"

namespace refx::cli {

Action addGalleryCommand(CLI::App& app) {
  app.add_subcommand("gallery", "(not implemented yet)");
  return [] { return 1; };
}

}  // namespace refx::cli
