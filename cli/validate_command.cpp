#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "io/job_loader.h"
#include "scene/scene_validation.h"

namespace clipblur::cli {


Action addValidateCommand(CLI::App& app) {
    struct Options {
        std::string job;
        std::vector<std::string> overrides;
    };
    auto opts = std::make_shared<Options>();
    CLI::App* sub = app.add_subcommand("validate", "Load and check a render job; print a summary");
    sub->add_option("job", opts->job, "Job file (.yaml, .yml or .json)")->required();
    sub->add_option("--set", opts->overrides, "Override a setting: key.path=value (repeatable)")
        ->allow_extra_args(false);

    return [opts]() {
        const RenderJob job = loadJob(opts->job, opts->overrides);
        const SceneSummary s = summarizeScene(job.scene);
        std::cout << job.source_file << ": ok\n"
                  << "  config hash:  " << job.config_hash << "\n"
                  << "  film:         " << job.scene.film.width << "x" << job.scene.film.height << "\n"
                  << "  frames:       " << job.frames.first << ".." << job.frames.last << " at " << job.frames.fps
                  << " fps, shutter [" << job.shutter.open << ", " << job.shutter.close << "]\n"
                  << "  camera keys:  " << job.scene.camera.keys.size() << "\n"
                  << "  method:       " << methodName(job.render.method) << "\n"
                  << "  objects:      " << s.objects << "\n"
                  << "  triangles:    " << s.triangles << "\n"
                  << "  degenerate:   " << s.degenerate_triangles << "\n"
                  << "  materials:    " << job.scene.materials.size() << "\n"
                  << "  lights:       " << job.scene.lights.size() << "\n"
                  << "  warnings:     " << job.warnings.size() << "\n";
        for (const std::string& w : job.warnings) std::cout << "warning: " << w << "\n";
        return 0;
    };
}

}  // namespace clipblur::cli
