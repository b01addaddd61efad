// deepgi: Deep G-Buffer global illumination. Sub-commands live in app/cmd_*.cpp.
#include "app/command.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>

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
