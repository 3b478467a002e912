#pragma once

namespace clipblur {

// What the stochastic reference did for one frame.
struct StochasticStats {
    double scene_build_seconds = 0.0, render_seconds = 0.0;
    long long samples_per_pixel = 0, samples = 0, tiles = 0;
    long long primary_rays = 0, shadow_rays = 0, depth_rays = 0;
    long long triangles = 0, dropped_triangles = 0;  // EmbreeSceneStats
    long long moving_objects = 0, capped_time_step_objects = 0, max_time_steps = 0, vertex_evaluations = 0;

    long long rays() const { return primary_rays + shadow_rays + depth_rays; }

    template <class Fields>
    void fields(Fields& f) const {
        f.info("method", "stochastic");
        f.seconds("scene_build", scene_build_seconds);
        f.seconds("render", render_seconds);
        f.count("samples_per_pixel", samples_per_pixel);
        f.count("samples", samples);
        f.count("tiles", tiles);
        f.count("primary_rays", primary_rays);
        f.count("shadow_rays", shadow_rays);
        f.count("depth_rays", depth_rays);
        f.count("rays", rays());
        f.count("triangles", triangles);
        f.count("dropped_triangles", dropped_triangles);
        f.count("moving_objects", moving_objects);
        f.count("capped_time_step_objects", capped_time_step_objects);
        f.count("max_time_steps", max_time_steps);
        f.count("vertex_evaluations", vertex_evaluations);
    }
};

}  // namespace clipblur
