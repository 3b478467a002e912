#include "renderer/image_file.h"

#include <algorithm>
#include <cstring>

namespace clipblur {

namespace {

template <class T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

}  // namespace

ImageAttribute ImageAttribute::string(std::string name, std::string value) {
    return {std::move(name), kTypeString, {std::move(value)}, {}};
}

ImageAttribute ImageAttribute::integers(std::string name, AttributeType type, const std::vector<int>& values) {
    return {std::move(name), type, {}, bytesOf(values)};
}

ImageAttribute ImageAttribute::floats(std::string name, AttributeType type, const std::vector<float>& values) {
    return {std::move(name), type, {}, bytesOf(values)};
}

const ImageAttribute* ImageFile::find(std::string_view name) const {
    const auto it = std::find_if(attributes.begin(), attributes.end(), [&](const auto& a) { return a.name == name; });
    return it == attributes.end() ? nullptr : &*it;
}

std::string ImageFile::stringAttribute(std::string_view name) const {
    const ImageAttribute* a = find(name);
    return a && a->type == kTypeString && a->text.size() == 1 ? a->text.front() : std::string();
}

void ImageFile::set(ImageAttribute attribute) {
    erase(attribute.name);
    attributes.push_back(std::move(attribute));
}

void ImageFile::erase(std::string_view name) {
    std::erase_if(attributes, [&](const auto& a) { return a.name == name; });
}

}  // namespace clipblur
