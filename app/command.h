#pragma once
// Sub-commands register themselves: each app/cmd_*.cpp defines one static CommandRegistrar.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace deepgi {

// Called with the sub-command so it can add its options; returns the function run when the sub-command is chosen.
using CommandSetup = std::function<std::function<int()>(CLI::App& sub)>;

struct CommandEntry {
    std::string name, description;
    int order;  // position in --help
    CommandSetup setup;
};

inline std::vector<CommandEntry>& commandEntries() {
    static std::vector<CommandEntry> entries;
    return entries;
}

struct CommandRegistrar {
    CommandRegistrar(std::string name, std::string description, int order, CommandSetup setup) {
        commandEntries().push_back({std::move(name), std::move(description), order, std::move(setup)});
    }
};

}  // namespace deepgi
