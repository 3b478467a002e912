#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/pixel_bounds.h"

namespace clipblur {

// How a channel is stored in a file (pixels in memory are float either way).
enum class PixelType : std::uint8_t { UInt8, Half, Float };

// The type of a header attribute, field for field OpenImageIO's TypeDesc (base type, aggregate, vector
// semantics, array length; the module checks the numbering), so that an attribute read from one file
// is written to another unchanged: a merged frame keeps every attribute of its first shard.
struct AttributeType {
    std::uint8_t base = 0;
    std::uint8_t aggregate = 1;
    std::uint8_t semantics = 0;
    int array = 0;  // 0: not an array
    friend bool operator==(const AttributeType&, const AttributeType&) = default;
};
inline constexpr std::uint8_t kBaseInt32 = 7, kBaseFloat = 11, kBaseString = 13;
inline constexpr AttributeType kTypeInt{kBaseInt32};
inline constexpr AttributeType kTypeFloat{kBaseFloat};
inline constexpr AttributeType kTypeString{kBaseString};
inline constexpr AttributeType kTypeMatrix44{kBaseFloat, 16};
inline constexpr AttributeType kTypeRational{kBaseInt32, 2, 7};
inline constexpr AttributeType floatArray(int n) { return {kBaseFloat, 1, 0, n}; }

// One attribute: strings in `text` (one per element), every other type as its bytes in `bytes`.
struct ImageAttribute {
    std::string name;
    AttributeType type;
    std::vector<std::string> text;
    std::vector<unsigned char> bytes;

    static ImageAttribute string(std::string name, std::string value);
    static ImageAttribute integers(std::string name, AttributeType type, const std::vector<int>& values);
    static ImageAttribute floats(std::string name, AttributeType type, const std::vector<float>& values);
};

// An image file's first subimage: windows, channels, header, and (when read or to be written) its
// pixels interleaved as float, data window rows top to bottom.
struct ImageFile {
    std::string format;      // as read: OpenImageIO's format name ("openexr", "png", ...)
    int full_width = 0;      // display window, origin (0, 0) ...
    int full_height = 0;
    int full_x = 0;          // ... unless the file says otherwise
    int full_y = 0;
    PixelBounds window;      // data window
    bool flat = true;        // false for a volume image (never ours): depth or z offset
    std::vector<std::string> channels;
    std::vector<PixelType> types;  // per channel
    std::vector<ImageAttribute> attributes;
    std::vector<float> pixels;

    const ImageAttribute* find(std::string_view name) const;
    // The attribute's value when it is a string, else empty.
    std::string stringAttribute(std::string_view name) const;
    void set(ImageAttribute attribute);  // replaces one of the same name
    void erase(std::string_view name);
};

enum class ImageRead { Header, HeaderAndPixels };

}  // namespace clipblur
