// Every flag of vkray's commands: how its value is checked and bound into
// Options, and its default help line. options.cpp says which command takes
// which flags.
#pragma once

#include "app/options.h"

#include <CLI/CLI.hpp>

#include <string>

namespace vkray {

inline constexpr const char* kIdsExpected =
    "--ids: expected two files, A.id.pfm B.id.pfm (or A.exr B.exr)";

// Adds flag `name` ("-o", "--size", as a command names it) to `app`, bound
// into `o`, with `help` or, empty, the flag's default help line.
CLI::Option* addFlag(CLI::App& app, Options& o, const std::string& name,
                     const std::string& help = {});

// `text` as a whole number in [lo, hi], else an Error naming `flag`.
int parseInt(const std::string& flag, const std::string& text, int lo, int hi);

}  // namespace vkray
