#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <tbb/global_control.h>

#include "cli/commands.h"
#include "io/comp_channels.h"
#include "io/cryptomatte.h"
#include "io/exr_frame_header.h"
#include "io/image_writer.h"
#include "io/job_loader.h"
#include "io/reference_error.h"
#include "io/frame_path.h"
#include "io/progress_timing.h"
#include "io/shard.h"
#include "io/stats_writer.h"
#include "renderer/render.h"
#include "scene/error.h"

namespace clipblur::cli {

namespace {

// Set from the signal handler; a lock-free atomic store is async-signal-safe.
std::atomic<bool> g_cancel{false};

extern "C" void onStopSignal(int) { g_cancel.store(true); }

// Installs SIGINT/SIGTERM handlers for the lifetime of the object and restores the previous ones.
class StopSignals {
public:
    StopSignals() {
        g_cancel.store(false);
        struct sigaction action {};
        action.sa_handler = &onStopSignal;
        sigemptyset(&action.sa_mask);
        sigaction(SIGINT, &action, &previous_int_);
        sigaction(SIGTERM, &action, &previous_term_);
    }
    ~StopSignals() {
        sigaction(SIGINT, &previous_int_, nullptr);
        sigaction(SIGTERM, &previous_term_, nullptr);
    }
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

private:
    struct sigaction previous_int_ {};
    struct sigaction previous_term_ {};
};


enum class ProgressStyle { Bar, Lines, None };

ProgressStyle parseProgress(const std::string& text) {
    if (text == "bar") return ProgressStyle::Bar;
    if (text == "lines") return ProgressStyle::Lines;
    if (text == "none") return ProgressStyle::None;
    return ::isatty(STDERR_FILENO) ? ProgressStyle::Bar : ProgressStyle::Lines;  // auto
}

// Progress on stderr with elapsed time and ETA; calls arrive serialised from the renderer's worker threads.
class ProgressPrinter {
public:
    ProgressPrinter(ProgressStyle style, int frame)
        : style_(style), frame_(frame), start_(std::chrono::steady_clock::now()) {}

    void operator()(long long done, long long total) {
        if (total <= 0) return;
        const int percent = static_cast<int>(100 * done / total);
        const std::string timing = progressTiming(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(), done, total);
        if (style_ == ProgressStyle::Bar) {
            const int width = 40;
            const int filled = static_cast<int>(width * done / total);
            std::cerr << "\rframe " << frame_ << " [" << std::string(static_cast<std::size_t>(filled), '#')
                      << std::string(static_cast<std::size_t>(width - filled), ' ') << "] " << percent << "% " << timing
                      // Clears what a longer line before this one left behind.
                      << "   " << (done == total ? "\n" : "") << std::flush;
        } else if (style_ == ProgressStyle::Lines && percent / 10 > last_decile_) {
            // Log files get one line per 10%, not one per tile.
            last_decile_ = percent / 10;
            std::cerr << "frame " << frame_ << ": " << percent << "% (" << done << "/" << total << " tiles), " << timing
                      << "\n";
        }
    }

private:
    ProgressStyle style_;
    int frame_;
    int last_decile_ = -1;
    std::chrono::steady_clock::time_point start_;
};

std::string pngPathFor(const std::string& image_path) {
    std::filesystem::path p(image_path);
    p.replace_extension(".png");
    return p.string();
}

}  // namespace

Action addRenderCommand(CLI::App& app) {
    struct Options {
        std::string job;
        std::vector<std::string> overrides;
        int threads = 0;
        std::string frames;
        std::string out;
        std::string stats;
        std::string progress = "auto";
        std::string tile;
        std::string reference;
    };
    auto opts = std::make_shared<Options>();
    CLI::App* sub = app.add_subcommand("render", "Render the frames of a job to OpenEXR");
    sub->add_option("job", opts->job, "Job file (.yaml, .yml or .json)")->required();
    sub->add_option("--set", opts->overrides, "Override a setting: key.path=value (repeatable)")
        ->allow_extra_args(false);
    sub->add_option("--threads", opts->threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
    sub->add_option("--frames", opts->frames, "Frame range A-B (or one frame A), overriding the job's");
    sub->add_option("--out", opts->out, "Output image path; #### is replaced by the zero-padded frame");
    sub->add_option("--stats", opts->stats, "Stats JSON path (default: beside the image); #### allowed");
    sub->add_option("--progress", opts->progress, "Progress display")
        ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
    sub->add_option("--tile", opts->tile,
                    "Render shard I of N only (I/N), to <image>.tile-I-of-N.exr; a complete shard is skipped");
    sub->add_option("--reference", opts->reference,
                    "Reference image (#### allowed): RMSE and max error of R, G, B go to the stats and stdout");

    return [opts]() {
        RenderJob job = loadJob(opts->job, opts->overrides);
        if (!opts->frames.empty()) {
            const FrameRange range = parseFrameRange(opts->frames);
            job.frames.first = range.first;
            job.frames.last = range.last;
        }
        std::optional<TileShard> shard;
        if (!opts->tile.empty()) {
            shard = parseTileShard(opts->tile);
            job.render.window = shardWindow(job.scene.film.width, job.scene.film.height, *shard);
        }
        const std::string image_pattern = opts->out.empty() ? job.output.path : opts->out;
        const std::string stats_pattern = opts->stats.empty() ? job.output.stats_path : opts->stats;
        // A shard's files carry its tag, so the N shards of a frame never write the same path.
        const auto pathFor = [&](const std::string& pattern, int frame) {
            const std::string path = outputPathForFrame(pattern, frame, job.frames.first, job.frames.last);
            return shard ? shardPath(path, *shard) : path;
        };
        // Resolve every path before rendering so a bad pattern fails before any work is done.
        for (int f = job.frames.first; f <= job.frames.last; ++f) {
            pathFor(image_pattern, f);
            if (!stats_pattern.empty()) pathFor(stats_pattern, f);
        }

        std::optional<tbb::global_control> limit;
        if (opts->threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, opts->threads);
        const int threads =
            static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
        const ProgressStyle style = parseProgress(opts->progress);

        StopSignals signals;
        for (int frame = job.frames.first; frame <= job.frames.last; ++frame) {
            const std::string image_path = pathFor(image_pattern, frame);
            // A requeued farm element must not redo finished work; the config hash makes a shard of an
            // older job count as missing.
            if (shard && shardIsComplete(image_path, job.scene.film.width, job.scene.film.height, *shard,
                                         job.config_hash)) {
                std::cout << "frame " << frame << ": " << image_path << " complete, skipped\n" << std::flush;
                continue;
            }
            // Read before rendering: a wrong reference path must not cost a render.
            std::optional<ReferenceImage> reference;
            if (!opts->reference.empty())
                reference = readReference(outputPathForFrame(opts->reference, frame, job.frames.first, job.frames.last),
                                          job.scene.film.width, job.scene.film.height);
            const std::string start_time = utcTimestamp(std::chrono::system_clock::now());
            ProgressPrinter printer(style, frame);
            RenderCallbacks callbacks;
            callbacks.cancel = &g_cancel;
            if (style != ProgressStyle::None) callbacks.progress = [&printer](long long d, long long t) { printer(d, t); };
            RenderResult result = renderFrame(job, frame, callbacks);
            if (g_cancel.load()) throw Error(ExitCode::Interrupted, "interrupted; frame " + std::to_string(frame) + " not written");
            toForwardVectors(result.image, job.shutter.close - job.shutter.open);
            if (job.output.background == BackgroundMode::Bake) bakeBackground(result.image, job.scene.film.background);

            ImageMetadata meta;
            meta.method = methodName(job.render.method);
            if (job.render.method == Method::Stochastic || job.render.method == Method::Accumulation)
                meta.samples = job.render.samples;
            // Tiles plan their own counts; the header gives the largest (0 when nothing moved).
            if (const auto it = result.stats.counts.find("subframes_max_per_tile"); it != result.stats.counts.end())
                meta.subframes = static_cast<int>(it->second);
            meta.seed = job.render.seed;
            meta.config_hash = job.config_hash;
            meta.frame = frameHeader(job, frame);
            if (job.output.cryptomatte.enabled) {
                std::vector<std::string> names;
                for (const Object& object : job.scene.objects) names.push_back(object.name);
                meta.strings = addCryptomatte(result.image, result.objects, names, job.output.cryptomatte);
            }
            if (const auto it = result.stats.seconds.find("total"); it != result.stats.seconds.end())
                meta.render_seconds = it->second;
            if (shard) {
                meta.tile_index = shard->index;
                meta.tile_count = shard->count;
                result.stats.info["window"] = toString(result.image.window());
            }
            if (reference) {
                const ReferenceError e = compareWithReference(result.image, *reference);
                result.stats.error = {{"rmse", e.rmse}, {"max_abs", e.max_abs}, {"mean_abs", e.mean_abs}};
                result.stats.info["reference"] = outputPathForFrame(opts->reference, frame, job.frames.first, job.frames.last);
                std::cout << "frame " << frame << ": against the reference RMSE " << e.rmse << ", max error " << e.max_abs
                          << "\n";
            }
            writeExr(image_path, result.image, meta, ExrFormat{job.output.half, job.output.compression});
            std::cout << "frame " << frame << ": wrote " << image_path;
            // A shard's preview would be mostly black; previews belong to whole frames.
            if (job.output.png_preview && !shard) {
                const std::string png = pngPathFor(image_path);
                writePngPreview(png, result.image, job.scene.film.background);
                std::cout << " and " << png;
            }
            const std::string stats_path =
                stats_pattern.empty() ? defaultStatsPath(image_path) : pathFor(stats_pattern, frame);
            writeStats(stats_path, statsToJson(result.stats, {frame, image_path, threads, job.config_hash, start_time}));
            std::cout << " (stats " << stats_path << ")\n" << std::flush;
        }
        return 0;
    };
}

}  // namespace clipblur::cli
