#include <iostream>
#include <vector>

#include "cli/commands.h"
#include "clipblur/version.h"
#include "scene/error.h"

int main(int argc, char** argv) {
    using namespace clipblur;
    CLI::App app{"clipblur: motion blur by clipped-triangle propagation"};
    app.set_version_flag("--version", std::string("clipblur ") + kVersion + " (" + kGitHash + ")");
    app.require_subcommand(1);

    std::vector<std::pair<CLI::App*, cli::Action>> commands;
    auto add = [&](cli::Action (*registerCommand)(CLI::App&)) {
        const std::size_t before = app.get_subcommands({}).size();
        cli::Action action = registerCommand(app);
        commands.emplace_back(app.get_subcommands({})[before], std::move(action));
    };
    add(cli::addPathsCommand);

    add(cli::addValidateCommand);
    add(cli::addRenderCommand);
    add(cli::addSceneJsonCommand);

    add(cli::addMergeCommand);
    add(cli::addSubmitCommand);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : static_cast<int>(ExitCode::Usage);
    }

    try {
        for (auto& [sub, action] : commands)
            if (sub->parsed()) return action();
    } catch (const Error& e) {
        std::cerr << "clipblur: error: " << e.what() << "\n";
        return static_cast<int>(e.code());
    } catch (const std::exception& e) {
        std::cerr << "clipblur: internal error: " << e.what() << "\n";
        return static_cast<int>(ExitCode::Internal);
    }
    return static_cast<int>(ExitCode::Usage);
}
