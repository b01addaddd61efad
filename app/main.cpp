// deepgi: Deep G-Buffer global illumination. Sub-commands live in app/cmd_*.cpp.
#include "app/command.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

int main(int argc, char** argv) {
    CLI::App app{"deepgi: Deep G-Buffer global illumination (Mara et al., HPG 2016) renderer, viewer and reference"};
    app.require_subcommand(1);
    auto entries = deepgi::commandEntries();
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
    std::function<int()> run;
    std::vector<std::function<int()>> runners(entries.size());
    for (size_t i = 0; i < entries.size(); ++i) {
        CLI::App* sub = app.add_subcommand(entries[i].name, entries[i].description);
        runners[i] = entries[i].setup(*sub);
        sub->callback([&run, &runners, i] { run = runners[i]; });
    }
    // CLI11 answers an unknown first word with "A subcommand is required", which does not name it.
    if (argc > 1 && argv[1][0] != '-') {
        const std::string word = argv[1];
        std::string names;
        bool known = false;
        for (const auto& e : entries) {
            known = known || e.name == word;
            names += (names.empty() ? "" : ", ") + e.name;
        }
        if (!known) {
            std::fprintf(stderr, "deepgi: error: unknown subcommand '%s' (available: %s; see deepgi --help)\n",
                         word.c_str(), names.c_str());
            return 1;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        return run ? run() : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "deepgi: error: %s\n", e.what());
        return 1;
    }
}
