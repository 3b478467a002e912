#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <tbb/global_control.h>

#include "cli/commands.h"
#include "io/atomic_file.h"
#include "io/comp_channels.h"
#include "io/cryptomatte.h"
#include "io/exr_frame_header.h"
#include "io/image_writer.h"
#include "io/job_loader.h"
#include "io/reference_error.h"
#include "io/frame_path.h"
#include "io/output_paths.h"
#include "io/progress_timing.h"
#include "io/shard.h"
#include "io/stats_writer.h"
#include "renderer/render.h"
#include "renderer/worker_threads.h"
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

void throwIfStopped(const std::string& message) {
    if (g_cancel.load()) throw Error(ExitCode::Interrupted, message);
}

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
    bool resume = false;
};

// The files of one frame; png and reference are empty when not wanted.
struct FrameFiles {
    int frame = 0;
    std::string image;
    std::string png;
    std::string stats;
    std::string reference;
};

std::vector<FrameFiles> planFrames(const RenderJob& job, const Options& o, const std::optional<TileShard>& shard) {
    const std::string image_pattern = o.out.empty() ? job.output.path : o.out;
    const std::string stats_pattern = o.stats.empty() ? job.output.stats_path : o.stats;
    const int first = job.frames.first, last = job.frames.last;
    // A shard's files carry its tag, so the N shards of a frame never write the same path.
    const auto pathFor = [&](const std::string& pattern, int frame) {
        const std::string path = outputPathForFrame(pattern, frame, first, last);
        return shard ? shardPath(path, *shard) : path;
    };
    std::vector<FrameFiles> frames;
    for (int f = first; f <= last; ++f) {
        FrameFiles files{f, pathFor(image_pattern, f), {}, {}, {}};
        // A shard's preview would be mostly black; previews belong to whole frames.
        if (job.output.png_preview && !shard) files.png = pngPathFor(files.image);
        files.stats = stats_pattern.empty() ? defaultStatsPath(files.image) : pathFor(stats_pattern, f);
        if (!o.reference.empty()) files.reference = outputPathForFrame(o.reference, f, first, last);
        frames.push_back(std::move(files));
    }
    return frames;
}

// Before any rendering: every reference exists, and the outputs are distinct, writable and spare the
// inputs (`read`: the job's files; the references are added).
void checkFrameFiles(const std::vector<FrameFiles>& frames, std::vector<std::filesystem::path> read) {
    std::vector<PlannedOutput> outputs;
    for (const FrameFiles& f : frames) {
        const std::string of = " of frame " + std::to_string(f.frame);
        outputs.push_back({f.image, "image" + of});
        if (!f.png.empty()) outputs.push_back({f.png, "PNG preview" + of});
        outputs.push_back({f.stats, "stats" + of});
        if (f.reference.empty()) continue;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(f.reference, ec))
            throw Error(ExitCode::Config, "reference image " + f.reference + of + " is missing or not a file");
        read.push_back(f.reference);
    }
    checkPlannedOutputs(outputs, read);
}

// Done when its image is complete for this job. The image is moved into place after the files beside it
// (writeFrame), so a complete image means they are there too.
bool frameIsDone(const RenderJob& job, const FrameFiles& files, const std::optional<TileShard>& shard) {
    const int w = job.scene.film.width, h = job.scene.film.height;
    if (shard) return shardIsComplete(files.image, {.width = w, .height = h, .shard = *shard, .config_hash = job.config_hash});
    return checkImage(files.image, ImageExpectation{w, h, PixelBounds::sized(0, 0, w, h), job.config_hash, {}}).complete;
}

ImageMetadata metadataFor(const RenderJob& job, int frame, RenderResult& result, const std::optional<TileShard>& shard) {
    ImageMetadata meta;
    meta.method = methodName(job.render.method);
    if (job.render.method == Method::Stochastic || job.render.method == Method::Accumulation)
        meta.samples = job.render.samples;
    // Tiles plan their own counts; the header gives the largest (0 when nothing moved).
    meta.subframes = static_cast<int>(result.stats.subframesMaxPerTile());
    meta.seed = job.render.seed;
    meta.config_hash = job.config_hash;
    meta.frame = frameHeader(job, frame);
    meta.render_seconds = result.stats.total_seconds;
    if (shard) {
        meta.tile_index = shard->index;
        meta.tile_count = shard->count;
        result.stats.window = result.image.window;
    }
    return meta;
}

// Renders one frame and moves all its files into place together, or none of them.
void renderAndWriteFrame(const RenderJob& job, const FrameFiles& files, const std::optional<TileShard>& shard,
                         int threads, ProgressStyle style) {
    const int frame = files.frame;
    // Read before rendering: a bad reference must not cost a render.
    std::optional<ReferenceImage> reference;
    if (!files.reference.empty()) reference = readReference(files.reference, job.scene.film.width, job.scene.film.height);
    const std::string start_time = utcTimestamp(std::chrono::system_clock::now());
    ProgressPrinter printer(style, frame);
    RenderCallbacks callbacks;
    callbacks.cancel = &g_cancel;
    if (style != ProgressStyle::None) callbacks.progress = [&printer](long long d, long long t) { printer(d, t); };
    RenderResult result = renderFrame(job, frame, callbacks);
    throwIfStopped("interrupted; frame " + std::to_string(frame) + " not written");
    toForwardVectors(result.image, job.shutter.close - job.shutter.open);
    if (job.output.background == BackgroundMode::Bake) bakeBackground(result.image, job.scene.film.background);

    ImageMetadata meta = metadataFor(job, frame, result, shard);
    if (job.output.cryptomatte.enabled) {
        std::vector<std::string> names;
        for (const Object& object : job.scene.objects) names.push_back(object.name);
        meta.strings = addCryptomatte(result.image, result.objects, names, job.output.cryptomatte);
    }
    if (reference) {
        const ReferenceError e = compareWithReference(result.image, *reference);
        result.stats.reference = RenderStats::Reference{files.reference, e.rmse, e.max_abs, e.mean_abs};
        std::cout << "frame " << frame << ": against the reference RMSE " << e.rmse << ", max error " << e.max_abs
                  << "\n";
    }
    AtomicFileGroup outputs;
    if (!files.png.empty()) writePngPreview(outputs, files.png, result.image, job.scene.film.background);
    writeStats(outputs, files.stats,
               statsToJson(result.stats, {frame, files.image, threads, job.config_hash, start_time}));
    // The image last: --resume takes a complete image for a complete frame.
    writeExr(outputs, files.image, result.image, meta, ExrFormat{job.output.half, job.output.compression});
    outputs.commit();
    std::cout << "frame " << frame << ": wrote " << files.image;
    if (!files.png.empty()) std::cout << " and " << files.png;
    std::cout << " (stats " << files.stats << ")\n" << std::flush;
    // What may show in the image (a hole, strobing): on stderr too, not only in the stats.
    for (const std::string& w : result.stats.warnings) std::cerr << "clipblur: warning: frame " << frame << ": " << w << "\n";
}

}  // namespace

Action addRenderCommand(CLI::App& app) {
    auto opts = std::make_shared<Options>();
    CLI::App* sub = app.add_subcommand("render", "Render the frames of a job to OpenEXR");
    sub->add_option("job", opts->job, "Job file (.yaml, .yml or .json)")->required();
    sub->add_option("--set", opts->overrides, "Override a setting: key.path=value (repeatable)")
        ->allow_extra_args(false);
    sub->add_option("--threads", opts->threads, "Worker threads (default: all cores)")->check(CLI::Range(0, kMaxThreads));
    sub->add_option("--frames", opts->frames, "Frame range A-B (or one frame A), overriding the job's");
    sub->add_option("--out", opts->out, "Output image path; #### is replaced by the zero-padded frame");
    sub->add_option("--stats", opts->stats, "Stats JSON path (default: beside the image); #### allowed");
    sub->add_option("--progress", opts->progress, "Progress display")
        ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
    sub->add_option("--tile", opts->tile,
                    "Render shard I of N only (I/N), to <image>.tile-I-of-N.exr; a complete shard is skipped");
    sub->add_option("--reference", opts->reference,
                    "Reference image (#### allowed): RMSE and max error of R, G, B go to the stats and stdout");
    sub->add_flag("--resume", opts->resume,
                  "Skip frames whose image is already complete for this job (same config hash)");

    return [opts]() {
        // Installed before loading, so a stop signal while a large job loads also ends with exit 130.
        StopSignals signals;
        std::vector<std::filesystem::path> read;
        RenderJob job = loadJob(opts->job, opts->overrides, &read);
        throwIfStopped("interrupted while loading the job; nothing rendered");
        for (const std::string& w : job.warnings) std::cerr << "clipblur: warning: " << w << "\n";
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
        // Every path is resolved and checked before rendering so a bad one fails before any work is done.
        const std::vector<FrameFiles> frames = planFrames(job, *opts, shard);
        checkFrameFiles(frames, read);
        std::optional<tbb::global_control> limit;
        if (opts->threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, opts->threads);
        const int threads =
            static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
        const ProgressStyle style = parseProgress(opts->progress);
        for (const FrameFiles& files : frames) {
            // A requeued farm element or a resumed render must not redo finished work; the config hash
            // makes an image of an older job count as missing.
            if ((shard || opts->resume) && frameIsDone(job, files, shard)) {
                std::cout << "frame " << files.frame << ": " << files.image << " complete, skipped\n" << std::flush;
                continue;
            }
            renderAndWriteFrame(job, files, shard, threads, style);
        }
        return 0;
    };
}

}  // namespace clipblur::cli
