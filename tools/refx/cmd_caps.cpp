// `refx caps`: lists the device generations; `refx caps PROFILE` prints one in full.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "refx/pipeline/caps.h"

namespace refx::cli {

Action addCapsCommand(CLI::App& app) {
  auto profile = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "caps", "List the device caps profiles, or print every field of one");
  cmd->add_option("profile", *profile, "Profile name (see `refx caps`) or path to a .caps file");
  return [profile] {
    if (profile->empty()) {
      size_t width = 0;
      for (const auto& name : capsProfileNames()) width = std::max(width, name.size());
      for (const auto& name : capsProfileNames()) {
        CapsProfile caps = loadCapsProfile(name);
        std::printf("%-*s  %s\n", int(width), name.c_str(), caps.description.c_str());
      }
      return 0;
    }
    std::fputs(describeCapsProfile(loadCapsProfile(*profile)).c_str(), stdout);
    return 0;
  };
}

}  // namespace refx::cli
