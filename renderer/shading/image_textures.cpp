#include "renderer/shading/image_textures.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

namespace clipblur {

double srgbToLinear(double code) {
    return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

namespace {

bool isFloat(OIIO::TypeDesc format) {
    return format.basetype == OIIO::TypeDesc::FLOAT || format.basetype == OIIO::TypeDesc::HALF ||
           format.basetype == OIIO::TypeDesc::DOUBLE;
}

// The image as linear float RGB: grey repeated, alpha dropped (the renderer has no cut-outs).
OIIO::ImageBuf linearRgb(OIIO::ImageBuf& source) {
    const OIIO::ImageSpec& in = source.spec();
    // The file's own texel type: the buffer itself was read as float.
    const bool srgb = !isFloat(source.nativespec().format);
    OIIO::ImageSpec spec(in.width, in.height, 3, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf out(spec);
    std::vector<float> pixel(static_cast<std::size_t>(in.nchannels));
    for (int y = 0; y < in.height; ++y) {
        for (int x = 0; x < in.width; ++x) {
            source.getpixel(in.x + x, in.y + y, pixel.data(), in.nchannels);
            float rgb[3];
            for (int c = 0; c < 3; ++c) {
                const float v = pixel[static_cast<std::size_t>(in.nchannels >= 3 ? c : 0)];
                rgb[c] = srgb ? static_cast<float>(srgbToLinear(v)) : v;
            }
            out.setpixel(x, y, rgb, 3);
        }
    }
    return out;
}

}  // namespace

struct ImageTextures::Image {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;  // of the linear MIP-mapped copy
};

struct ImageTextures::State {
    OIIO::TextureSystem* system = nullptr;
    std::filesystem::path folder;
    mutable std::mutex mutex;
    std::map<std::string, std::unique_ptr<Image>> prepared;  // by source file; entries never move or go
};

ImageTextures& ImageTextures::shared() {
    // Never destroyed: OpenImageIO 2.4's TextureSystem::destroy deletes the system through a pointer of
    // the wrong type (ASan: new-delete-type-mismatch inside libOpenImageIO), and the process ends here
    // anyway. Reachable from this static to its end, so it is no leak; only the prepared files go.
    static ImageTextures* const instance = [] {
        auto* textures = new ImageTextures;
        std::atexit([] { ImageTextures::shared().removePreparedFiles(); });
        return textures;
    }();
    return *instance;
}

void ImageTextures::removePreparedFiles() {
    std::error_code ignored;
    std::filesystem::remove_all(state_->folder, ignored);
}

ImageTextures::ImageTextures() : state_(std::make_unique<State>()) {
    state_->system = OIIO::TextureSystem::create(false);
    // Every texel of a scene's textures stays cached: no re-reads while rendering, and lookups do not
    // depend on which thread evicted what.
    state_->system->attribute("max_memory_MB", 4096.0f);
    state_->system->attribute("autotile", 64);
    state_->folder = std::filesystem::temp_directory_path() / ("clipblur-textures-" + std::to_string(::getpid()));
}

ImageTextures::~ImageTextures() = default;

void ImageTextures::prepare(const std::string& file, const FileLoc& ref) {
    const std::lock_guard lock(state_->mutex);
    if (state_->prepared.count(file)) return;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throwSceneError(ref, "texture file '" + file + "' does not exist");
    OIIO::ImageBuf source(file);
    if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT) || source.spec().width <= 0 || source.spec().height <= 0)
        throwSceneError(ref, "cannot read texture file '" + file + "': " + source.geterror());
    const OIIO::ImageBuf linear = linearRgb(source);
    std::filesystem::create_directories(state_->folder, ec);
    const std::string copy = (state_->folder / (std::to_string(state_->prepared.size()) + ".exr")).string();
    OIIO::ImageSpec config;
    config.attribute("maketx:filtername", "box");
    config.attribute("maketx:fixnan", "box3");
    config.tile_width = config.tile_height = 64;
    config.format = OIIO::TypeDesc::FLOAT;
    config.attribute("wrapmodes", "periodic,periodic");
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, linear, copy, config))
        throwSceneError(ref, "cannot prepare texture file '" + file + "': " + OIIO::geterror());
    auto image = std::make_unique<Image>();
    image->handle = state_->system->get_texture_handle(OIIO::ustring(copy));
    if (!image->handle) throwSceneError(ref, "cannot open the prepared copy of texture file '" + file + "'");
    state_->prepared.emplace(file, std::move(image));
}

const ImageTextures::Image* ImageTextures::find(const std::string& file) const {
    const std::lock_guard lock(state_->mutex);
    const auto it = state_->prepared.find(file);
    return it == state_->prepared.end() ? nullptr : it->second.get();
}

glm::dvec3 ImageTextures::lookup(const Image& image, const glm::dvec2& st, const TextureFootprint& f) const {
    OIIO::TextureOpt options;
    options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
    // Bilinear between texel centres: the image function the stochastic reference point-samples, so that
    // its converged average is the area integral the filtered lookups approximate.
    options.interpmode = OIIO::TextureOpt::InterpBilinear;
    float rgb[3] = {0.0f, 0.0f, 0.0f};
    state_->system->texture(image.handle, state_->system->get_perthread_info(), options, static_cast<float>(st.x), static_cast<float>(st.y),
                            static_cast<float>(f.dx.x), static_cast<float>(f.dx.y), static_cast<float>(f.dy.x),
                            static_cast<float>(f.dy.y), 3, rgb);
    return glm::dvec3(rgb[0], rgb[1], rgb[2]);
}

}  // namespace clipblur
