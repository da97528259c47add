// Each `refx` subcommand lives in its own file and registers itself here.
#pragma once
#include <functional>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "refx/pipeline/device.h"

namespace refx::cli {

// A registered command returns the action to run once the command line is parsed;
// the action returns the process exit status.
using Action = std::function<int()>;
using Register = Action (*)(CLI::App& app);

Action addCapsCommand(CLI::App& app);
Action addReplayCommand(CLI::App& app);
Action addGalleryCommand(CLI::App& app);
Action addBenchCommand(CLI::App& app);
Action addAssetCommand(CLI::App& app);
Action addDisasmCommand(CLI::App& app);
Action addAsmCommand(CLI::App& app);
Action addValidateCommand(CLI::App& app);
Action addRenderCommand(CLI::App& app);
Action addWatchCommand(CLI::App& app);
Action addFxcCommand(CLI::App& app);
Action addTestCommand(CLI::App& app);

// "WxH" of --size into w and h (1..8192 each); refx::Error otherwise.
void parseSize(const std::string& s, int& w, int& h);

// A device of `caps` with a w x h A8R8G8B8 target and a depth buffer; `precision` is
// "exact" or "hardware".
std::unique_ptr<Device> makeTargetDevice(const CapsProfile& caps, int threads, const std::string& precision,
                                         int w, int h);

// True when stderr is a terminal (progress display).
bool stderrIsTerminal();

}  // namespace refx::cli
